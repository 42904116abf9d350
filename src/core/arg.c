#include "subsurf/arg.h"

#include "subsurf/number.h"

#include <math.h>
#include <string.h>

const ss_arg *ss_arg_find(const ss_arg *args, const char *name) {
  for (const ss_arg *a = args; name && a->name; ++a) {
    if (!strcmp(a->name, name)) {
      return a;
    }
  }
  return NULL;
}

ss_status ss_arg_parse(const ss_arg *a, const char *text, double *out, ss_error *err) {
  const ss_status bad = SS_ERR_INVALID_ARGUMENT;
  double v;
  int number = ss_number_parse(text, &v);
  switch (a->type) {
  case SS_ARG_NUMBER_OR_INF:
    if (!strcmp(text, "inf") || !strcmp(text, "infinite")) {
      *out = INFINITY;
      return SS_OK;
    }
    if (!number) {
      return ss_error_set(err, bad, "expected a finite decimal number or inf, got '%s'", text);
    }
    break;
  case SS_ARG_NUMBER:
    if (!number) {
      return ss_error_set(err, bad, "expected a finite decimal number, got '%s'", text);
    }
    break;
  case SS_ARG_WHOLE: {
    int unbounded = a->hi == SS_ARG_U64_END;
    if (!number || !(v >= a->lo) || !(unbounded ? v < a->hi : v <= a->hi) || v != floor(v)) {
      if (unbounded) {
        return ss_error_set(err, bad, "expected a whole number >= %.0f, got '%s'", a->lo, text);
      }
      return ss_error_set(err, bad, "expected a whole number in [%.0f, %.0f], got '%s'", a->lo,
                          a->hi, text);
    }
    break;
  }
  }
  *out = v;
  return SS_OK;
}
