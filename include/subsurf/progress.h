/* Progress reporting. The library never draws: long runs (ss_render,
 * ss_halfspace_run) report through an ss_progress_fn the caller supplies,
 * and the CLI draws its bar from it (src/cli/progress_bar.h). */
#ifndef SUBSURF_PROGRESS_H
#define SUBSURF_PROGRESS_H

#include <stdint.h>

/* Called from one thread at a time with the work done so far and the total
 * (camera samples for a render, paths for the half-space reference). */
typedef void (*ss_progress_fn)(void *ctx, uint64_t done, uint64_t total);

/* Monotonic wall-clock seconds. */
double ss_seconds(void);

#endif
