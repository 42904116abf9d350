/* Text buffers (text_buf.h). */
#include "cli/text_buf.h"

#include "core/atomic_file.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int reserve(ss_text_buf *b, size_t extra) {
  if (b->failed) {
    return 0;
  }
  if (b->len + extra + 1 <= b->cap) {
    return 1;
  }
  size_t cap = b->cap ? b->cap : 4096;
  while (cap < b->len + extra + 1) {
    cap *= 2;
  }
  char *data = realloc(b->data, cap);
  if (!data) {
    b->failed = 1;
    return 0;
  }
  b->data = data;
  b->cap = cap;
  return 1;
}

void ss_text_printf(ss_text_buf *b, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0 || !reserve(b, (size_t)n)) {
    b->failed = 1;
    return;
  }
  va_start(ap, fmt);
  vsnprintf(b->data + b->len, (size_t)n + 1, fmt, ap);
  va_end(ap);
  b->len += (size_t)n;
}

void ss_text_escaped(ss_text_buf *b, const char *s) {
  for (; *s; ++s) {
    switch (*s) {
    case '&':
      ss_text_printf(b, "&amp;");
      break;
    case '<':
      ss_text_printf(b, "&lt;");
      break;
    case '>':
      ss_text_printf(b, "&gt;");
      break;
    case '"':
      ss_text_printf(b, "&quot;");
      break;
    case '\'':
      ss_text_printf(b, "&#39;");
      break;
    default:
      ss_text_printf(b, "%c", *s);
    }
  }
}

ss_status ss_text_save(const ss_text_buf *b, const char *path, ss_file_kind kind, ss_error *err) {
  if (b->failed) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory writing '%s'", path);
  }
  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, kind, err);
  if (st != SS_OK) {
    return st;
  }
  st = ss_atomic_file_write(&f, b->data ? b->data : "", b->len, err);
  if (st != SS_OK) {
    ss_atomic_file_abort(&f);
    return st;
  }
  return ss_atomic_file_commit(&f, err);
}

void ss_text_free(ss_text_buf *b) {
  free(b->data);
  memset(b, 0, sizeof *b);
}
