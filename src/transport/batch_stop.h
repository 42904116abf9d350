/* The stop flag that the threads of a batched Monte Carlo run (the
 * half-space tracer, its white profiles, the layer walk) poll every few
 * paths: any thread that sees the caller's cancel flag or a time limit
 * raises it, and every thread ends its batch once it is raised. */
#ifndef SUBSURF_TRANSPORT_BATCH_STOP_H
#define SUBSURF_TRANSPORT_BATCH_STOP_H

#include <signal.h>

typedef struct {
  int stop;        /* set once by any thread, read by all (atomically) */
  int interrupted; /* the stop came from *cancel */
} ss_batch_stop;

/* 1 when the thread should end its batch: *cancel is set (recorded as
 * interrupted), `expired` (the caller's time limit), or another thread
 * stopped. */
static inline int ss_batch_stop_poll(ss_batch_stop *s, const volatile sig_atomic_t *cancel,
                                     int expired) {
  int cancelled = cancel && *cancel, stopped;
  if (cancelled) {
#pragma omp atomic write
    s->interrupted = 1;
  }
#pragma omp atomic read
  stopped = s->stop;
  if (cancelled || expired || stopped) {
#pragma omp atomic write
    s->stop = 1;
    return 1;
  }
  return 0;
}

#endif
