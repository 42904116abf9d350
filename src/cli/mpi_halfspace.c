/* `mpirun -np N subsurf halfspace` (mpi_job.h): the batches of paths are
 * split over the ranks and rank 0 merges every batch's sums in batch order,
 * exactly as one process does, so results are bit-identical for any number
 * of ranks and threads. A message is one batch: its paths, its scattering
 * events and its per-bin sums (8 bytes per bin). */
#include "cli/mpi_job.h"

#include "subsurf/progress.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define HEADER 2 /* paths and events, ahead of the sums */
/* Message tags: channel * BATCH_TAGS + batch (ss_halfspace_run has at most
 * 1024 batches). */
#define BATCH_TAGS 1024

static int tag_of(const ss_mpi_batches *b, int64_t batch) {
  return 1 + b->channel * BATCH_TAGS + (int)(batch % BATCH_TAGS);
}

static void pause_1ms(void) {
  struct timespec t = {0, 1000000};
  nanosleep(&t, NULL);
}

/* A batch's message buffer; out of memory ends the job. */
static double *message(const ss_mpi_batches *b, size_t nbins) {
  double *msg = malloc((nbins + HEADER) * sizeof *msg);
  if (!msg) {
    fprintf(stderr, "subsurf %s: rank %d: out of memory for a batch message\n", b->cmd,
            ss_mpi_rank());
    ss_mpi_locked(1);
    ss_mpi_abort();
  }
  return msg;
}

/* Rank 0 takes the first batch it finishes as the measure of how long a
 * batch may take; the other ranks send theirs. */
static void sink(void *ctx, int64_t batch, const double *sums, size_t nbins, uint64_t paths,
                 uint64_t events) {
  ss_mpi_batches *b = ctx;
  double start = ss_seconds();
  if (ss_mpi_rank() == 0) {
    ss_mpi_locked(1);
    if (b->first_done == 0.0) {
      b->first_done = start;
    }
    ss_mpi_locked(0);
    return;
  }
  double *msg = message(b, nbins);
  memcpy(&msg[0], &paths, sizeof paths);
  memcpy(&msg[1], &events, sizeof events);
  memcpy(msg + HEADER, sums, nbins * sizeof *sums);
  ss_mpi_request req;
  ss_mpi_locked(1);
  int rc = ss_mpi_isend(msg, (int)((nbins + HEADER) * sizeof *msg), 0, tag_of(b, batch), &req);
  ss_mpi_locked(0);
  /* Rank 0 receives batches in order: it may still be on earlier ones,
   * which took at most about as long as this rank's run so far. */
  double limit = ss_mpi_timeout() + 2.0 * (start - b->t0);
  int done = rc == 0 ? 0 : -1;
  while (done == 0 && (done = ss_mpi_test(&req)) == 0) {
    if (ss_seconds() - start > limit) {
      done = -2;
      break;
    }
    pause_1ms();
  }
  free(msg);
  if (done < 0) {
    fprintf(stderr, "subsurf %s: rank %d could not send batch %lld to rank 0%s; the job fails\n",
            b->cmd, ss_mpi_rank(), (long long)batch, done == -2 ? " within the time-out" : "");
    ss_mpi_locked(1);
    ss_mpi_abort();
  }
}

/* Rank 0: another rank's batch. The time-out starts once rank 0 has
 * finished a batch of its own (batches run side by side on all ranks), and
 * is the time-out base plus twice the time rank 0 had run by then. */
static uint64_t source(void *ctx, int64_t batch, double *sums, size_t nbins, uint64_t *events) {
  ss_mpi_batches *b = ctx;
  int from = (int)(batch % ss_mpi_size());
  double *msg = message(b, nbins);
  ss_mpi_request req;
  ss_mpi_locked(1);
  int rc = ss_mpi_irecv(msg, (int)((nbins + HEADER) * sizeof *msg), from, tag_of(b, batch), &req);
  ss_mpi_locked(0);
  double start = ss_seconds();
  int done = rc == 0 ? 0 : -1;
  while (done == 0 && (done = ss_mpi_test(&req)) == 0) {
    ss_mpi_locked(1);
    double first = b->first_done;
    ss_mpi_locked(0);
    double since = first > start ? first : start;
    if (first > 0.0 && ss_seconds() - since > ss_mpi_timeout() + 2.0 * (since - b->t0)) {
      done = -2;
      break;
    }
    pause_1ms();
  }
  if (done < 0) {
    fprintf(stderr, "subsurf %s: rank %d %s batch %lld; the job fails\n", b->cmd, from,
            done == -2 ? "sent nothing within the time-out for" : "was lost before sending",
            (long long)batch);
    ss_mpi_locked(1);
    ss_mpi_abort();
  }
  uint64_t paths;
  memcpy(&paths, &msg[0], sizeof paths);
  uint64_t ev;
  memcpy(&ev, &msg[1], sizeof ev);
  *events += ev;
  memcpy(sums, msg + HEADER, nbins * sizeof *sums);
  free(msg);
  return paths;
}

void ss_mpi_split_batches(ss_halfspace_params *p, ss_mpi_batches *ctx, const char *cmd,
                          int channel) {
  memset(ctx, 0, sizeof *ctx);
  if (ss_mpi_size() <= 1) {
    return;
  }
  ctx->channel = channel;
  ctx->t0 = ss_seconds();
  ctx->cmd = cmd;
  p->batch_stride = ss_mpi_size();
  p->batch_offset = ss_mpi_rank();
  p->batch_source = ss_mpi_rank() == 0 ? source : NULL;
  p->batch_sink = sink;
  p->batch_ctx = ctx;
}
