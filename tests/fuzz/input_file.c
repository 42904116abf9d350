#include "input_file.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

static char path[256];

static void remove_input(void) { unlink(path); }

const char *ss_fuzz_input_file(const uint8_t *data, size_t size, const char *suffix) {
  if (!path[0]) {
    const char *dir = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/subsurf-fuzz-%ld%s", dir ? dir : "/tmp", (long)getpid(),
             suffix);
    atexit(remove_input);
  }
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd < 0) {
    return NULL;
  }
  size_t done = 0;
  while (done < size) {
    ssize_t n = write(fd, data + done, size - done);
    if (n <= 0) {
      close(fd);
      return NULL;
    }
    done += (size_t)n;
  }
  return close(fd) == 0 ? path : NULL;
}

const char *ss_fuzz_input_file_crc(const uint8_t *data, size_t size, size_t min_size,
                                   const char *suffix) {
  uint8_t *copy = malloc(size + 1);
  if (!copy) {
    return NULL;
  }
  memcpy(copy, data, size);
  if (size >= min_size && size >= 4) {
    uLong crc = crc32(crc32(0L, Z_NULL, 0), copy, (uInt)(size - 4));
    for (int i = 0; i < 4; ++i) {
      copy[size - 4 + (size_t)i] = (uint8_t)(crc >> (8 * i));
    }
  }
  const char *p = ss_fuzz_input_file(copy, size, suffix);
  free(copy);
  return p;
}

void ss_fuzz_parse_scene(const uint8_t *data, size_t size, ss_fuzz_scene_parser parse) {
  char *text = malloc(size + 1);
  if (!text) {
    return;
  }
  memcpy(text, data, size);
  text[size] = '\0';
  ss_scene *scene = NULL;
  ss_error err;
  if (parse(text, getenv("SUBSURF_FUZZ_BASE_DIR"), &scene, &err) == SS_OK) {
    ss_scene_destroy(scene);
  }
  free(text);
}
