/* Test helper: reads a scene file and frees the scene, for tests that only
 * look at whether (and with which message) a file is refused. */
#ifndef SUBSURF_TESTS_READ_SCENE_FILE_H
#define SUBSURF_TESTS_READ_SCENE_FILE_H

#include "subsurf/scene.h"
#include "subsurf/scene_io.h"

static inline ss_status read_scene_file(const char *path, ss_error *err) {
  ss_scene *s = NULL;
  ss_status st = ss_scene_read_json(path, &s, err);
  if (st == SS_OK) {
    ss_scene_destroy(s);
  }
  return st;
}

#endif
