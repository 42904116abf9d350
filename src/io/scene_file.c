/* Scene text files (scene_file.h). */
#include "io/scene_file.h"

#include "core/input_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_scene_file_read(const char *path, const char *what, char **out, char dir[SS_PATH_SIZE],
                             ss_error *err) {
  *out = NULL;
  unsigned char *data;
  size_t size;
  ss_status st = ss_input_file_read(path, path, SS_INPUT_SCENE, &data, &size, err);
  if (st != SS_OK) {
    return st;
  }
  char *text = (char *)data;
  if (strlen(text) != size) {
    free(text);
    return ss_error_set(err, SS_ERR_PARSE, "%s: contains a NUL byte (not %s)", path, what);
  }
  snprintf(dir, SS_PATH_SIZE, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash) {
    *slash = '\0';
    if (!dir[0]) {
      snprintf(dir, SS_PATH_SIZE, "/");
    }
  } else {
    snprintf(dir, SS_PATH_SIZE, ".");
  }
  *out = text;
  return SS_OK;
}
