/* A progress bar on stderr with elapsed and remaining time, for the
 * commands that run long jobs. It draws only when enabled and stderr is a
 * terminal, and redraws at most 10 times a second; ss_progress_update may be
 * called from any thread. */
#ifndef SUBSURF_CLI_PROGRESS_BAR_H
#define SUBSURF_CLI_PROGRESS_BAR_H

#include "subsurf/progress.h"

#include <stdint.h>

typedef struct {
  const char *label;
  uint64_t total;
  uint64_t done; /* the last value reported through ss_progress_report */
  int enabled;
  double start_seconds;
  double last_draw_seconds;
  double time_limit; /* > 0: remaining time also bounded by the time limit */
} ss_progress;

void ss_progress_begin(ss_progress *p, const char *label, uint64_t total, int enabled,
                       double time_limit);
void ss_progress_update(ss_progress *p, uint64_t done);
/* An ss_progress_fn for the library's reports: ctx is the ss_progress; it
 * takes the total from the report and remembers `done`. */
void ss_progress_report(void *ctx, uint64_t done, uint64_t total);
/* Draws the final state and ends the line. */
void ss_progress_end(ss_progress *p, uint64_t done);

#endif
