/* Scene loading shared by the benchmarks that render a bundled scene. */
#ifndef SUBSURF_BENCH_SCENE_H
#define SUBSURF_BENCH_SCENE_H

#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>

/* $SUBSURF_SOURCE_DIR/scenes/NAME (or ./scenes/NAME) into buf. */
static inline const char *bench_scene_path(char *buf, size_t size, const char *name) {
  const char *root = getenv("SUBSURF_SOURCE_DIR");
  snprintf(buf, size, "%s/scenes/%s", root ? root : ".", name);
  return buf;
}

/* The scene file at `path`, or NULL after printing why. */
static inline ss_scene *bench_read_scene(const char *path) {
  ss_scene *s;
  ss_error err;
  if (ss_scene_read_json(path, &s, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return NULL;
  }
  return s;
}

#endif
