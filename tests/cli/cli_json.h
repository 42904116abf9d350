/* Reading a JSON file a CLI test's command wrote into its directory. */
#ifndef SUBSURF_TESTS_CLI_JSON_H
#define SUBSURF_TESTS_CLI_JSON_H

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

#endif
