/* Status codes and error records. Library functions return an ss_status and,
 * on failure, fill an ss_error whose message names the context (file, line,
 * key or option). The library never prints and never exits; the CLI decides. */
#ifndef SUBSURF_STATUS_H
#define SUBSURF_STATUS_H

#include <stddef.h>

typedef enum {
  SS_OK = 0,
  SS_ERR_INVALID_ARGUMENT, /* a parameter out of range, NaN, unknown name */
  SS_ERR_IO,               /* a file could not be opened, read or written */
  SS_ERR_PARSE,            /* a file's content is malformed */
  SS_ERR_NO_MEMORY,
  SS_ERR_INTERRUPTED, /* stopped by a signal; results are partial */
  SS_ERR_UNSUPPORTED,
} ss_status;

#define SS_ERROR_MESSAGE_SIZE 1024

typedef struct {
  ss_status status;
  char message[SS_ERROR_MESSAGE_SIZE];
} ss_error;

/* Records a formatted message in `err` (which may be NULL) and returns
 * `status`, so that callers can write `return ss_error_set(err, ...)`. */
ss_status ss_error_set(ss_error *err, ss_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Prepends context ("scene.json: ") to an existing message. */
void ss_error_prefix(ss_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

void ss_error_clear(ss_error *err);
/* Rewrites the text in place (within `size` bytes, truncating) with its
 * control characters escaped (\n, \t, \r, \xNN), so that a message quoting
 * the user's strings stays one line. ss_error_set and ss_error_prefix apply
 * it to every message. */
void ss_text_escape_controls(char *text, size_t size);

const char *ss_status_name(ss_status status);

#endif
