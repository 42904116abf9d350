/* A growing text buffer written with printf formats and saved as a file
 * that appears complete or not at all (core/atomic_file.h): the SVG plots
 * and the HTML report of `subsurf compare`. */
#ifndef SUBSURF_CLI_TEXT_BUF_H
#define SUBSURF_CLI_TEXT_BUF_H

#include "core/file_kind.h"
#include "subsurf/status.h"

#include <stddef.h>

typedef struct {
  char *data;
  size_t len, cap;
  int failed; /* an allocation failed: the text is incomplete */
} ss_text_buf;

/* Appends printf-formatted text. */
void ss_text_printf(ss_text_buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Appends `s` with &, <, >, " and ' escaped for HTML and XML. */
void ss_text_escaped(ss_text_buf *b, const char *s);
/* Writes the text, a file of `kind`, to `path` atomically (replacing only
 * a file of that kind); SS_ERR_NO_MEMORY when incomplete. */
ss_status ss_text_save(const ss_text_buf *b, const char *path, ss_file_kind kind, ss_error *err);
void ss_text_free(ss_text_buf *b);

#endif
