/* Scene text files (scene_file.h). */
#include "io/scene_file.h"

#include "core/input_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Scene files describe; geometry lives in mesh files. The limit keeps a
 * mistaken argument (a huge binary file) from being read into memory. */
#define SS_SCENE_FILE_MAX ((uint64_t)64 << 20)

ss_status ss_scene_file_read(const char *path, const char *what, char **out, char dir[SS_PATH_SIZE],
                             ss_error *err) {
  *out = NULL;
  FILE *f;
  uint64_t file_size;
  ss_status st = ss_input_file_open(path, path, &f, &file_size, err);
  if (st != SS_OK) {
    return st;
  }
  if (file_size > SS_SCENE_FILE_MAX) {
    fclose(f);
    return ss_error_set(err, SS_ERR_PARSE,
                        "%s: %llu bytes is too large for a scene file (at most 64 MiB; "
                        "geometry belongs in mesh files)",
                        path, (unsigned long long)file_size);
  }
  char *text = NULL;
  size_t size = 0, cap = 0;
  for (;;) {
    if (size + 4096 + 1 > cap) {
      cap = cap ? 2 * cap : 65536;
      char *grown = realloc(text, cap);
      if (!grown) {
        free(text);
        fclose(f);
        return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", path);
      }
      text = grown;
    }
    size_t n = fread(text + size, 1, cap - size - 1, f);
    size += n;
    if (n == 0) {
      break;
    }
  }
  int failed = ferror(f);
  fclose(f);
  if (failed) {
    free(text);
    return ss_error_set(err, SS_ERR_IO, "%s: read error", path);
  }
  text[size] = '\0';
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
