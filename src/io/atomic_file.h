/* Output files that appear complete or not at all: data goes to a temporary
 * file beside the target (path + ".tmp-XXXXXX", same directory so that the
 * final rename is atomic), which is renamed over the target on success and
 * removed on failure. */
#ifndef SUBSURF_IO_ATOMIC_FILE_H
#define SUBSURF_IO_ATOMIC_FILE_H

#include "subsurf/status.h"

#include <stddef.h>

typedef struct {
  const char *path; /* the target, borrowed from the caller */
  char *tmp_path;
  int fd;
} ss_atomic_file;

/* Creates the temporary file; SS_ERR_IO naming `path` when that fails. */
ss_status ss_atomic_file_open(ss_atomic_file *f, const char *path, ss_error *err);
/* Writes all `size` bytes at the current position. */
ss_status ss_atomic_file_write(ss_atomic_file *f, const void *data, size_t size, ss_error *err);
/* Flushes, closes and renames the temporary file over the target; on failure
 * removes it. Either way `f` is released. */
ss_status ss_atomic_file_commit(ss_atomic_file *f, ss_error *err);
/* Closes and removes the temporary file and releases `f`. */
void ss_atomic_file_abort(ss_atomic_file *f);

#endif
