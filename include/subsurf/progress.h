/* A progress bar on stderr with elapsed and remaining time. It draws only
 * when enabled and stderr is a terminal, and redraws at most 10 times a
 * second; ss_progress_update may be called from any thread. */
#ifndef SUBSURF_PROGRESS_H
#define SUBSURF_PROGRESS_H

#include <stdint.h>

typedef struct {
  const char *label;
  uint64_t total;
  int enabled;
  double start_seconds;
  double last_draw_seconds;
  double time_limit; /* > 0: remaining time also bounded by the time limit */
} ss_progress;

void ss_progress_begin(ss_progress *p, const char *label, uint64_t total, int enabled,
                       double time_limit);
void ss_progress_update(ss_progress *p, uint64_t done);
/* Draws the final state and ends the line. */
void ss_progress_end(ss_progress *p, uint64_t done);

/* Monotonic wall-clock seconds. */
double ss_seconds(void);

#endif
