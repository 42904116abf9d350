/* Shipped text tables (the data directory's .txt files) end in the line
 * "crc32 XXXXXXXX", the CRC-32 (zlib) of every byte before it, so that a
 * corrupt or truncated file is refused before it is parsed. */
#ifndef SUBSURF_OPTICS_CHECKED_TEXT_H
#define SUBSURF_OPTICS_CHECKED_TEXT_H

#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

/* Checks the checksum of a table's text; *body receives the length of the
 * text before its checksum line. Messages start with `label`. */
ss_status ss_checked_text_verify(const char *text, size_t size, const char *label, size_t *body,
                                 ss_error *err);

/* Reads a regular file of at most max_size bytes into a malloc'd buffer
 * (`kind` names what it should be in the message for a larger file, e.g.
 * "an albedo table"). */
ss_status ss_checked_text_read(const char *path, uint64_t max_size, const char *kind, char **text,
                               size_t *size, ss_error *err);

#endif
