/* Helpers of the pbrt importer's tests: scenes written to a temporary
 * directory, read with their warnings collected. */
#ifndef SUBSURF_TESTS_IO_PBRT_TEST_H
#define SUBSURF_TESTS_IO_PBRT_TEST_H

#include <criterion/criterion.h>

#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  char text[1 << 14]; /* the warnings, one per line */
  int count;
} pbrt_warnings;

static inline void pbrt_collect(void *user, const char *message) {
  pbrt_warnings *w = user;
  size_t n = strlen(w->text);
  snprintf(w->text + n, sizeof w->text - n, "%s\n", message);
  w->count++;
}

/* A fresh temporary directory in dir. */
static inline void pbrt_tmpdir(char *dir, size_t size) {
  snprintf(dir, size, "/tmp/subsurf-pbrt-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static inline void pbrt_write(const char *dir, const char *name, const char *text) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f, "cannot write %s", path);
  fputs(text, f);
  cr_assert_eq(fclose(f), 0);
}

static inline void pbrt_rmdir(const char *dir) {
  char cmd[512];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_expect_eq(system(cmd), 0);
}

/* Writes `text` as dir/name and reads it. */
static inline ss_status pbrt_read(const char *dir, const char *name, const char *text, ss_scene **s,
                                  pbrt_warnings *w, ss_error *err) {
  char path[512];
  pbrt_write(dir, name, text);
  snprintf(path, sizeof path, "%s/%s", dir, name);
  memset(w, 0, sizeof *w);
  return ss_scene_read_pbrt(path, s, pbrt_collect, w, err);
}

/* The camera of every test scene: pbrt's mirrored LookAt (Scale -1 1 1)
 * from (0, 0, 5) toward the origin, so that pbrt's world and subsurf's
 * coincide; 32 x 32, a lamp so that the scene commits. */
#define PBRT_TEST_HEADER                                                                           \
  "Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 30\n"              \
  "Film \"image\" \"integer xresolution\" 32 \"integer yresolution\" 32\nWorldBegin\n"             \
  "LightSource \"point\" \"rgb I\" [1 1 1] \"point from\" [0 5 5]\n"

#endif
