/* The clock of progress reports and timings (progress.h). */
#include "subsurf/progress.h"

#include <time.h>

double ss_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
