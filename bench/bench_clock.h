/* Timing helpers shared by the micro-benchmarks: the calling thread's CPU
 * time (insensitive to other processes taking the core), the process's CPU
 * time and the comparison
 * for qsort-ing timings to take their median. */
#ifndef SUBSURF_BENCH_CLOCK_H
#define SUBSURF_BENCH_CLOCK_H

#include <time.h>

static inline double thread_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The CPU time of the whole process (all its threads): beside the wall
 * clock it tells how many cores a parallel section actually got. */
static inline double process_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

#endif
