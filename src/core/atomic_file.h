/* Output files that appear complete or not at all. A regular file (new or
 * existing, also when reached through a symbolic link) is written to a
 * temporary file beside it (same directory, so that the final rename is
 * atomic), which is renamed over it on success and removed on failure; a
 * symbolic link stays a link to the new file. Anything else (a device such
 * as /dev/null, a FIFO, the process's own stdout or stderr given as a path
 * such as /dev/stdout, a dangling link) is not replaced: the output is kept
 * in memory and written to it in one go at commit, so a failed write still
 * writes nothing there. An existing regular file is replaced only by a file
 * of its own kind (file_kind.h): an image never replaces a scene. */
#ifndef SUBSURF_CORE_ATOMIC_FILE_H
#define SUBSURF_CORE_ATOMIC_FILE_H

#include "core/file_kind.h"
#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

typedef struct {
  const char *path;   /* the target as given (messages), borrowed from the caller */
  char *target;       /* where the data goes: path, or the resolved link target */
  char *tmp_path;     /* the temporary file; NULL when writing directly */
  int fd;             /* the temporary file's descriptor, -1 when direct */
  int create;         /* direct: create the target (a dangling link) */
  unsigned char *buf; /* direct: the data, written at commit */
  size_t size, cap;
} ss_atomic_file;

/* Prepares the output, a file of `kind`; SS_ERR_IO naming `path` when it
 * cannot be written (a directory, a missing directory, no permission),
 * SS_ERR_INVALID_ARGUMENT when it is a non-empty regular file of another
 * kind. */
ss_status ss_atomic_file_open(ss_atomic_file *f, const char *path, ss_file_kind kind,
                              ss_error *err);
/* Whether `path` could be opened as above (checked by doing so: a temporary
 * file is created and removed). Commands check all their outputs at once,
 * before any work, with core/output_plan.h. */
ss_status ss_atomic_file_check(const char *path, ss_file_kind kind, ss_error *err);
/* Appends all `size` bytes. */
ss_status ss_atomic_file_write(ss_atomic_file *f, const void *data, size_t size, ss_error *err);
/* Writes all `size` bytes at byte `offset` (for formats that patch earlier
 * parts, like EXR's chunk offset table); bytes never written read as 0. */
ss_status ss_atomic_file_pwrite(ss_atomic_file *f, const void *data, size_t size, uint64_t offset,
                                ss_error *err);
/* Flushes and renames the temporary file over the target (or writes the
 * data to a non-regular target); on failure removes the temporary file.
 * Either way `f` is released. */
ss_status ss_atomic_file_commit(ss_atomic_file *f, ss_error *err);
/* Removes the temporary file (writes nothing to a direct target) and
 * releases `f`. */
void ss_atomic_file_abort(ss_atomic_file *f);

#endif
