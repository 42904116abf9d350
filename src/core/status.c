#include "subsurf/status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

ss_status ss_error_set(ss_error *err, ss_status status, const char *fmt, ...) {
  if (err) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
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
