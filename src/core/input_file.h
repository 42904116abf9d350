/* Opening input files (scenes, meshes, tables): only regular files are read,
 * so a directory, a device or a FIFO given as an input is refused with a
 * clear message before anything is read, and readers know the file's size
 * before they allocate anything a header announces. A file read whole is
 * read to its end, never to the size it reports (a /proc file reports 0
 * bytes and holds gigabytes, a file may grow while it is read), and never
 * beyond the cap of its kind. */
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

/* The kinds of input read whole, each with its cap (README's limits). */
typedef enum {
  SS_INPUT_SCENE,         /* JSON or pbrt text, an Include: 64 MiB */
  SS_INPUT_MESH,          /* PLY or OBJ: 1 GiB */
  SS_INPUT_TEXTURE,       /* PNG or HDR texture: 512 MiB */
  SS_INPUT_ALBEDO_TABLE,  /* half-space albedo table text: 1 MiB */
  SS_INPUT_PROFILE_TABLE, /* half-space profile table text: 4 MiB */
  SS_INPUT_BSSRDF_TABLE,  /* `subsurf table` output: 4 GiB */
  SS_INPUT_GRID,          /* raw density grid: 8 GiB */
  SS_INPUT_FEM_CACHE,     /* fem integrator cache: 4 GiB */
} ss_input_kind;

/* The cap of a kind in bytes. */
uint64_t ss_input_cap(ss_input_kind kind);

/* Opens `path` as ss_input_file_open does and reads it to its end into
 * *data (malloc'ed, the caller frees; NUL-terminated one byte past *size).
 * A file that reports more than the kind's cap, or holds more (found once
 * cap + 1 bytes are read), is refused with SS_ERR_PARSE "LABEL: more than N MiB, the limit for
 * KIND". */
ss_status ss_input_file_read(const char *path, const char *label, ss_input_kind kind,
                             unsigned char **data, size_t *size, ss_error *err);

#endif
