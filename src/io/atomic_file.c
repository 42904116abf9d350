#include "io/atomic_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define SS_TMP_SUFFIX ".tmp-XXXXXX"

ss_status ss_atomic_file_open(ss_atomic_file *f, const char *path, ss_error *err) {
  f->path = path;
  f->fd = -1;
  size_t len = strlen(path);
  f->tmp_path = malloc(len + sizeof SS_TMP_SUFFIX);
  if (!f->tmp_path) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "cannot write %s: out of memory", path);
  }
  memcpy(f->tmp_path, path, len);
  memcpy(f->tmp_path + len, SS_TMP_SUFFIX, sizeof SS_TMP_SUFFIX);
  f->fd = mkstemp(f->tmp_path);
  if (f->fd < 0) {
    int e = errno;
    free(f->tmp_path);
    f->tmp_path = NULL;
    return ss_error_set(err, SS_ERR_IO, "cannot write %s: %s", path, strerror(e));
  }
  /* mkstemp creates the file private (0600); an image is an ordinary output
   * file, readable by others like one made by fopen under the usual umask. */
  fchmod(f->fd, 0644);
  return SS_OK;
}

ss_status ss_atomic_file_write(ss_atomic_file *f, const void *data, size_t size, ss_error *err) {
  const char *p = data;
  while (size > 0) {
    ssize_t n = write(f->fd, p, size);
    if (n < 0) {
      if (errno == EINTR) {
        continue;
      }
      return ss_error_set(err, SS_ERR_IO, "cannot write %s: %s", f->path, strerror(errno));
    }
    p += n;
    size -= (size_t)n;
  }
  return SS_OK;
}

static void release(ss_atomic_file *f) {
  free(f->tmp_path);
  f->tmp_path = NULL;
  f->fd = -1;
}

ss_status ss_atomic_file_commit(ss_atomic_file *f, ss_error *err) {
  /* fsync before rename: after a crash the target is either the old file or
   * the complete new one, never a renamed but still empty file. */
  if (fsync(f->fd) != 0 && errno != EINVAL) {
    int e = errno;
    ss_atomic_file_abort(f);
    return ss_error_set(err, SS_ERR_IO, "cannot write %s: %s", f->path, strerror(e));
  }
  if (close(f->fd) != 0) {
    int e = errno;
    f->fd = -1;
    ss_atomic_file_abort(f);
    return ss_error_set(err, SS_ERR_IO, "cannot write %s: %s", f->path, strerror(e));
  }
  f->fd = -1;
  if (rename(f->tmp_path, f->path) != 0) {
    int e = errno;
    ss_atomic_file_abort(f);
    return ss_error_set(err, SS_ERR_IO, "cannot write %s: %s", f->path, strerror(e));
  }
  release(f);
  return SS_OK;
}

void ss_atomic_file_abort(ss_atomic_file *f) {
  if (f->fd >= 0) {
    close(f->fd);
  }
  if (f->tmp_path) {
    unlink(f->tmp_path);
  }
  release(f);
}
