/* Opening input files (scenes, meshes, tables): only regular files are read,
 * so a directory, a device or a FIFO given as an input is refused with a
 * clear message before anything is read, and readers know the file's size
 * before they allocate anything a header announces. */
#ifndef SUBSURF_CORE_INPUT_FILE_H
#define SUBSURF_CORE_INPUT_FILE_H

#include "subsurf/status.h"

#include <stdint.h>
#include <stdio.h>

/* Opens `path` for binary reading. On failure *out is NULL and the message
 * reads "LABEL: cannot open: REASON" or "LABEL: is a directory (expected a
 * regular file)"; `label` names the file in the caller's style (the path,
 * or e.g. "table file 'x'"). `size` (may be NULL) receives the size. The
 * file is remembered as an input of the run (core/input_registry.h). */
ss_status ss_input_file_open(const char *path, const char *label, FILE **out, uint64_t *size,
                             ss_error *err);

#endif
