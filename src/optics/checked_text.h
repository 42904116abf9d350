/* Shipped text tables (the data directory's .txt files) end in the line
 * "crc32 XXXXXXXX", the CRC-32 (zlib) of every byte before it, so that a
 * corrupt or truncated file is refused before it is parsed. */
#ifndef SUBSURF_OPTICS_CHECKED_TEXT_H
#define SUBSURF_OPTICS_CHECKED_TEXT_H

#include "core/input_file.h"
#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

/* Checks the checksum of a table's text; *body receives the length of the
 * text before its checksum line. Messages start with `label`. */
ss_status ss_checked_text_verify(const char *text, size_t size, const char *label, size_t *body,
                                 ss_error *err);

/* Reads a regular file, to its end and within the cap of its `kind`
 * (ss_input_file_read), into a malloc'd NUL-terminated buffer. */
ss_status ss_checked_text_read(const char *path, ss_input_kind kind, char **text, size_t *size,
                               ss_error *err);

#endif
