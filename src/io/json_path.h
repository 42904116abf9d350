/* Reading JSON documents with errors that name the key path and the line
 * (private to src/io). cJSON keeps no source positions, so the position of a
 * key path is recovered by re-scanning the (already valid) text along that
 * path. The helpers below type-check values, reject unknown keys and format
 * messages "FILE:LINE: KEY.PATH[3]: what was expected". */
#ifndef SUBSURF_IO_JSON_PATH_H
#define SUBSURF_IO_JSON_PATH_H

#include "subsurf/rgb.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <cjson/cJSON.h>

#define SS_JSON_MAX_DEPTH 32

typedef struct {
  const char *key; /* object member, or NULL for an array element */
  int index;
} ss_json_elem;

typedef struct {
  const char *text; /* the whole document */
  const char *file; /* for messages */
  ss_error *err;
  int depth;
  ss_json_elem path[SS_JSON_MAX_DEPTH];
} ss_json_ctx;

/* Byte offset in `text` of the value (or member key) at `path`; -1 when the
 * path does not exist. The text must be valid JSON. */
long ss_json_locate(const char *text, const ss_json_elem *path, int depth);
/* 1-based line of a byte offset. */
int ss_json_line(const char *text, long offset);

void ss_json_push_key(ss_json_ctx *c, const char *key);
void ss_json_push_index(ss_json_ctx *c, int index);
void ss_json_pop(ss_json_ctx *c);

/* Records "FILE:LINE: PATH: message" (the line of the current path, or of
 * its deepest existing prefix) and returns `status`. */
ss_status ss_json_fail(ss_json_ctx *c, ss_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Same, with the current path extended by `key` for the message. */
ss_status ss_json_fail_key(ss_json_ctx *c, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Prefixes an existing message in c->err with "FILE:LINE: PATH: ". */
ss_status ss_json_wrap(ss_json_ctx *c, ss_status status);

/* Fails on the first member of `obj` whose key is not in the NULL-terminated
 * list `allowed` (duplicate keys: json_strict.h). */
ss_status ss_json_check_keys(ss_json_ctx *c, const cJSON *obj, const char *const *allowed);
/* Requires `item` to be an object (or array). */
ss_status ss_json_expect_object(ss_json_ctx *c, const cJSON *item);

/* Optional members: when absent the output keeps its current (default)
 * value. Numbers must be finite and within [lo, hi]. */
ss_status ss_json_number(ss_json_ctx *c, const cJSON *obj, const char *key, double lo, double hi,
                         double *out);
ss_status ss_json_int(ss_json_ctx *c, const cJSON *obj, const char *key, long lo, long hi,
                      long *out);
ss_status ss_json_bool(ss_json_ctx *c, const cJSON *obj, const char *key, int *out);
/* Copies a string into out (size bytes); a longer string is an error. */
ss_status ss_json_string(ss_json_ctx *c, const cJSON *obj, const char *key, char *out, size_t size);
ss_status ss_json_vec3(ss_json_ctx *c, const cJSON *obj, const char *key, ss_vec3 *out);
/* An RGB value: a number (grey) or an array of 3 numbers, each >= lo. */
ss_status ss_json_rgb(ss_json_ctx *c, const cJSON *obj, const char *key, double lo, ss_rgb *out);
/* Fails with "missing required key" when obj has no member `key`. */
ss_status ss_json_require(ss_json_ctx *c, const cJSON *obj, const char *key);

#endif
