#include "subsurf/batch_runner.h"

#include "subsurf/threads.h"

#include <sched.h>
#include <stdlib.h>
#include <string.h>

enum { SLOT_FREE = -1, SLOT_TRACING = -2 };

typedef struct {
  ss_batch_tally *tally;
  double *buffers;
  int64_t *state; /* SLOT_FREE, SLOT_TRACING, or the batch parked there */
  uint64_t *paths;
  int nslots;
  int64_t next_merge;
  uint64_t done;
} pool;

static int take_free_slot(pool *p) {
  int slot = -1;
#pragma omp critical(ss_batch_pool)
  for (int i = 0; i < p->nslots; ++i) {
    if (p->state[i] == SLOT_FREE) {
      p->state[i] = SLOT_TRACING;
      slot = i;
      break;
    }
  }
  return slot;
}

/* Parks a finished batch and merges every batch that is now next in order. */
static void park_and_merge(pool *p, int slot, int64_t batch, uint64_t paths,
                           ss_batch_merged_fn merged, void *ctx) {
#pragma omp critical(ss_batch_pool)
  {
    p->state[slot] = batch;
    p->paths[slot] = paths;
    int progressed = 0;
    for (int found = 1; found;) {
      found = 0;
      for (int i = 0; i < p->nslots; ++i) {
        if (p->state[i] == p->next_merge) {
          if (p->paths[i] > 0) {
            ss_batch_tally_add_batch(p->tally, p->buffers + (size_t)i * p->tally->nbins,
                                     p->paths[i]);
            p->done += p->paths[i];
            progressed = 1;
          }
          p->state[i] = SLOT_FREE;
          p->next_merge++;
          found = 1;
        }
      }
    }
    if (progressed && merged) {
      merged(ctx, p->done);
    }
  }
}

/* Each thread traces into one slot; two spares each absorb the spread of
 * batch durations before anyone has to wait. */
#define SLOTS_PER_THREAD 3

double ss_batch_run_bytes(size_t nbins, int threads) {
  int nthreads = ss_threads_team(threads);
  return (double)SLOTS_PER_THREAD * nthreads * (double)(nbins ? nbins : 1) * sizeof(double);
}

ss_status ss_batch_run(ss_batch_tally *tally, int64_t nbatches, int threads, ss_batch_fn run,
                       ss_batch_merged_fn merged, void *ctx, uint64_t *events, ss_error *err) {
  int nthreads = ss_threads_team(threads);
  pool p;
  memset(&p, 0, sizeof p);
  p.tally = tally;
  p.nslots = SLOTS_PER_THREAD * nthreads;
  size_t nbins = tally->nbins ? tally->nbins : 1;
  p.buffers = malloc((size_t)p.nslots * nbins * sizeof *p.buffers);
  p.state = malloc((size_t)p.nslots * sizeof *p.state);
  p.paths = calloc((size_t)p.nslots, sizeof *p.paths);
  if (!p.buffers || !p.state || !p.paths) {
    free(p.buffers);
    free(p.state);
    free(p.paths);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for %d tally buffers of %zu bins",
                        p.nslots, nbins);
  }
  for (int i = 0; i < p.nslots; ++i) {
    p.state[i] = SLOT_FREE;
  }
  int64_t next_batch = 0;
  uint64_t total_events = 0;
#pragma omp parallel num_threads(nthreads) reduction(+ : total_events)
  for (;;) {
    /* Take a slot before claiming a batch: then every claimed batch that is
     * not merged yet holds a slot, so the batch next in order is always being
     * traced or parked (and merged), and a waiting thread always gets a slot
     * back eventually. */
    int slot;
    while ((slot = take_free_slot(&p)) < 0) {
      sched_yield();
    }
    int64_t b;
#pragma omp atomic capture
    b = next_batch++;
    if (b >= nbatches) {
#pragma omp critical(ss_batch_pool)
      p.state[slot] = SLOT_FREE;
      break;
    }
    double *sums = p.buffers + (size_t)slot * nbins;
    memset(sums, 0, nbins * sizeof *sums);
    uint64_t ev = 0;
    uint64_t paths = run(ctx, b, sums, &ev);
    total_events += ev;
    park_and_merge(&p, slot, b, paths, merged, ctx);
  }
  free(p.buffers);
  free(p.state);
  free(p.paths);
  if (events) {
    *events = total_events;
  }
  return SS_OK;
}
