/* Strict JSON for the scene reader (private to src/io): RFC 8259's grammar
 * (no leading zeros, no "1." or ".5", no trailing commas, no control
 * characters or invalid UTF-8 in strings, no lone surrogates, no NUL) and
 * unique keys in every object. */
#ifndef SUBSURF_IO_JSON_STRICT_H
#define SUBSURF_IO_JSON_STRICT_H

#include "io/json_path.h"

/* SS_ERR_PARSE "FILE:LINE: invalid JSON: what" at the first departure. */
ss_status ss_json_check_strict(const char *text, const char *file, ss_error *err);

/* "FILE:LINE: key.path: duplicate key" for the first object, anywhere
 * below `item`, with two members of the same (decoded) name. */
ss_status ss_json_check_unique_keys(ss_json_ctx *c, const cJSON *item);

#endif
