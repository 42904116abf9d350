#include "subsurf/number.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ss_number_format(double v, char *buf, unsigned long size) {
  if (v == floor(v) && fabs(v) < 0x1p63) {
    snprintf(buf, size, "%lld", (long long)v);
  } else {
    snprintf(buf, size, "%g", v);
  }
}

/* Length of the longest prefix of `s` made of decimal digits. */
static size_t digits(const char *s) {
  size_t n = 0;
  while (s[n] >= '0' && s[n] <= '9') {
    ++n;
  }
  return n;
}

/* 1 when the whole of `s` matches the grammar of number.h. */
static int well_formed(const char *s) {
  s += *s == '+' || *s == '-';
  size_t whole = digits(s);
  s += whole;
  size_t frac = 0;
  if (*s == '.') {
    frac = digits(++s);
    s += frac;
  }
  if (whole + frac == 0) {
    return 0;
  }
  if (*s == 'e' || *s == 'E') {
    ++s;
    s += *s == '+' || *s == '-';
    size_t exp = digits(s);
    if (exp == 0) {
      return 0;
    }
    s += exp;
  }
  return *s == '\0';
}

int ss_number_parse(const char *text, double *out) {
  if (!well_formed(text)) {
    return 0;
  }
  /* The grammar leaves strtod no choice: only the range remains to check.
   * Underflow (ERANGE with a tiny result) keeps the tiny value. */
  errno = 0;
  double v = strtod(text, NULL);
  if (!isfinite(v) || (errno == ERANGE && fabs(v) > DBL_MIN)) {
    return 0;
  }
  *out = v + 0.0; /* -0 becomes +0 */
  return 1;
}

int ss_number_parse_n(const char *text, unsigned long len, double *out) {
  char field[64];
  if (len >= sizeof field) {
    return 0;
  }
  memcpy(field, text, len);
  field[len] = '\0';
  return ss_number_parse(field, out);
}
