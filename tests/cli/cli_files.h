/* Files of a CLI test's directory: writing inputs, reading the JSON a
 * command wrote, removing the directory. */
#ifndef SUBSURF_TESTS_CLI_FILES_H
#define SUBSURF_TESTS_CLI_FILES_H

#include "cli_run.h"

#include <cjson/cJSON.h>

/* Parses dir/name (up to 1 MiB); fails the test when it is not JSON. */
static inline cJSON *cli_load_json(const char *dir, const char *name) {
  char path[512];
  static char text[1 << 20];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  cli_slurp(path, text, sizeof text);
  cJSON *j = cJSON_Parse(text);
  cr_assert(j != NULL, "%s is not JSON", name);
  return j;
}

/* Writes `text` to dir/name. */
static inline void cli_write_text(const char *dir, const char *name, const char *text) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f, "cannot write %s", path);
  cr_assert_geq(fputs(text, f), 0);
  cr_assert_eq(fclose(f), 0);
}

/* Removes the directory and everything in it. */
static inline void cli_remove_dir(const char *dir) {
  char cmd[512];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_expect_eq(system(cmd), 0);
}

#endif
