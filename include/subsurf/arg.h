/* The grammar of a number that both the command line and the flat interface
 * (ffi.h, the Python module) take: one declaration per argument, read by
 * both, so that they accept the same values and refuse the others in the
 * same words. The text is number.h's grammar; the ranges that depend on
 * other arguments are the run's own validation (ss_halfspace_validate). */
#ifndef SUBSURF_ARG_H
#define SUBSURF_ARG_H

#include "subsurf/status.h"

typedef enum {
  SS_ARG_NUMBER,        /* a finite number */
  SS_ARG_NUMBER_OR_INF, /* a finite number, or "inf" / "infinite" for INFINITY */
  SS_ARG_WHOLE,         /* a whole number in [lo, hi] */
} ss_arg_type;

/* The upper end of SS_ARG_WHOLE for the range of uint64_t (2^64, excluded:
 * the first double above it): such an argument has no upper bound. */
#define SS_ARG_U64_END 0x1p64

typedef struct {
  const char *name; /* as on the command line, without "--" */
  ss_arg_type type;
  double lo, hi; /* SS_ARG_WHOLE's range */
} ss_arg;

/* The declaration of `name` in `args` (ended by an entry whose name is
 * NULL); NULL when it has none. */
const ss_arg *ss_arg_find(const ss_arg *args, const char *name);

/* Reads `text` as the argument: SS_OK and *out, or SS_ERR_INVALID_ARGUMENT
 * with what was expected and the text ("expected a whole number in [0,
 * 4096], got '1e5'"); the caller puts the argument's name in front. */
ss_status ss_arg_parse(const ss_arg *a, const char *text, double *out, ss_error *err);

#endif
