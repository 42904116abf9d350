#include "subsurf/status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void ss_text_escape_controls(char *text, size_t size) {
  char copy[SS_ERROR_MESSAGE_SIZE * 2];
  snprintf(copy, sizeof copy, "%s", text);
  size_t out = 0;
  for (const unsigned char *c = (const unsigned char *)copy; *c && out + 1 < size; ++c) {
    char esc[5] = {(char)*c, 0};
    if (*c == '\n' || *c == '\t' || *c == '\r') {
      snprintf(esc, sizeof esc, "\\%c", *c == '\n' ? 'n' : (*c == '\t' ? 't' : 'r'));
    } else if (*c < 0x20 || *c == 0x7f) {
      snprintf(esc, sizeof esc, "\\x%02x", *c);
    }
    size_t len = strlen(esc);
    if (out + len >= size) {
      break;
    }
    memcpy(text + out, esc, len);
    out += len;
  }
  text[out] = '\0';
}

ss_status ss_error_set(ss_error *err, ss_status status, const char *fmt, ...) {
  if (err) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    ss_text_escape_controls(err->message, sizeof err->message);
    err->status = status;
  }
  return status;
}

void ss_error_prefix(ss_error *err, const char *fmt, ...) {
  if (!err) {
    return;
  }
  char prefix[SS_ERROR_MESSAGE_SIZE];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(prefix, sizeof prefix, fmt, ap);
  va_end(ap);
  size_t plen = strnlen(prefix, sizeof err->message - 1);
  size_t mlen = strnlen(err->message, sizeof err->message - 1);
  if (plen + mlen > sizeof err->message - 1) {
    mlen = sizeof err->message - 1 - plen;
  }
  memmove(err->message + plen, err->message, mlen);
  memcpy(err->message, prefix, plen);
  err->message[plen + mlen] = '\0';
  ss_text_escape_controls(err->message, sizeof err->message);
}

void ss_error_clear(ss_error *err) {
  if (err) {
    err->status = SS_OK;
    err->message[0] = '\0';
  }
}

const char *ss_status_name(ss_status status) {
  switch (status) {
  case SS_OK:
    return "ok";
  case SS_ERR_INVALID_ARGUMENT:
    return "invalid argument";
  case SS_ERR_IO:
    return "i/o error";
  case SS_ERR_PARSE:
    return "parse error";
  case SS_ERR_NO_MEMORY:
    return "out of memory";
  case SS_ERR_INTERRUPTED:
    return "interrupted";
  case SS_ERR_UNSUPPORTED:
    return "unsupported";
  }
  return "unknown status";
}
