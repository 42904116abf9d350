/* The worker threads a caller may ask the library for. OpenMP creates a team
 * of the size asked without a bound of its own, and libgomp fails (exits the
 * process, or a thread's stack is never mapped) for tens of thousands; every
 * entry point that takes a thread count (the half-space reference, renders,
 * tables, and the command line and the flat interface through them) checks
 * it against this one limit. */
#ifndef SUBSURF_THREADS_H
#define SUBSURF_THREADS_H

#include "subsurf/arg.h"
#include "subsurf/status.h"

#define SS_THREADS_MAX 4096

/* A thread count in an argument table (arg.h): 0 (all cores) to the limit. */
#define SS_THREADS_ARG                                                                             \
  { "threads", SS_ARG_WHOLE, 0, SS_THREADS_MAX }

/* SS_OK when 0 <= threads <= SS_THREADS_MAX (0: OpenMP's default), else
 * SS_ERR_INVALID_ARGUMENT with "threads must be in [0, 4096] (got N)". */
ss_status ss_threads_check(int threads, ss_error *err);

/* The team for `threads`: itself, or for 0 OpenMP's default, at most
 * SS_THREADS_MAX (OMP_NUM_THREADS may ask for more). */
int ss_threads_team(int threads);

#endif
