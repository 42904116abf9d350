/* Runs independent batches of Monte Carlo paths on all threads and merges
 * their tallies in batch order, so that sums (and therefore results) are
 * bit-identical for any number of threads. Unlike an OpenMP `ordered` loop, a
 * thread that finishes early parks its tallies in a spare buffer and goes on
 * with the next batch instead of waiting for its predecessor. */
#ifndef SUBSURF_BATCH_RUNNER_H
#define SUBSURF_BATCH_RUNNER_H

#include "subsurf/stats.h"
#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

/* Traces batch `batch` into `sums` (tally->nbins zeroed doubles); returns the
 * number of paths traced (0 to skip the batch, e.g. after a stop request) and
 * adds the scattering events to *events. Called concurrently. */
typedef uint64_t (*ss_batch_fn)(void *ctx, int64_t batch, double *sums, uint64_t *events);

/* Called after each merge, one thread at a time, with the paths merged so far. */
typedef void (*ss_batch_merged_fn)(void *ctx, uint64_t paths_done);

ss_status ss_batch_run(ss_batch_tally *tally, int64_t nbatches, int threads, ss_batch_fn run,
                       ss_batch_merged_fn merged, void *ctx, uint64_t *events, ss_error *err);

/* Bytes ss_batch_run allocates for `nbins` bins on `threads` threads (0: all),
 * beyond the tally itself: callers check that a run fits before starting. */
double ss_batch_run_bytes(size_t nbins, int threads);

#endif
