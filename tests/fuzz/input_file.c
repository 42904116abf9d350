#include "input_file.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

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
