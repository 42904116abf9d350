/* Rendering across processes with Open MPI (docs/render.md, "Many
 * machines"): `mpirun -np N subsurf render ...`. Each rank renders every
 * N-th 16 x 16 tile at the same seed, so each pixel's samples are exactly
 * those a single process draws, and rank 0 collects the pixels: the image is
 * bit-identical for any number of ranks and threads. The library knows
 * nothing of MPI; only the CLI does, through the plugin of mpi_plugin.h.
 * Without mpirun nothing is initialised, and the plugin is not loaded. */
#ifndef SUBSURF_CLI_MPI_JOB_H
#define SUBSURF_CLI_MPI_JOB_H

#include "cli/mpi_plugin.h"
#include "subsurf/film.h"
#include "subsurf/halfspace.h"
#include "subsurf/render.h"

#include <stddef.h>

/* Initialises MPI when the process was started by mpirun (its environment
 * says so); returns the number of ranks (1 without mpirun). When the plugin
 * or MPI_Init fails it prints why and ends the process (exit 1). */
int ss_mpi_start(void);
/* MPI_Finalize when ss_mpi_start initialised it. */
void ss_mpi_finish(void);
int ss_mpi_rank(void);
int ss_mpi_size(void);

/* 0 when every rank holds the same bytes; otherwise rank 0 prints one line
 * naming `what` ("the command line", a file) and every rank returns 2. Like
 * ss_mpi_all_ok, it waits for the other ranks at most ss_mpi_timeout() plus
 * twice the time since MPI started, then prints why and ends the job
 * (MPI_Abort: mpirun exits non-zero). */
int ss_mpi_check_same(const char *cmd, const char *what, const void *data, size_t size);
/* The same for a file's content (a file one rank cannot read counts as a
 * difference). */
int ss_mpi_check_same_file(const char *cmd, const char *path);

/* ss_mpi_check_same on the arguments (main.c calls it for every command). */
int ss_mpi_check_args(const char *cmd, int argc, char **argv);

/* Every rank goes on only if all can (a rank alone in error would leave the
 * others waiting for it): the rank's own exit code, or 2 for the others;
 * 0 when every rank's rc is 0. For the start-up: a rank that does not answer
 * in time ends the job, as in ss_mpi_check_same. */
int ss_mpi_all_ok(int rc);

/* Seconds a rank waits for another beyond the time its own work took,
 * before it takes that rank as lost: SUBSURF_MPI_TIMEOUT, or 60. */
double ss_mpi_timeout(void);

/* MPI_Test on a request (1 done, 0 not yet, -1 failed), holding the lock
 * by which worker threads call MPI in turn; ss_mpi_locked(1/0) takes and
 * releases that lock around other calls. */
int ss_mpi_test(ss_mpi_request *request);
void ss_mpi_locked(int on);

/* MPI_Isend and MPI_Irecv of `bytes` bytes to or from a rank (0, or -1 on
 * failure), and MPI_Abort of the job (mpirun exits non-zero); only after
 * ss_mpi_start returned more than 1. */
int ss_mpi_isend(const void *buf, int bytes, int to, int tag, ss_mpi_request *req);
int ss_mpi_irecv(void *buf, int bytes, int from, int tag, ss_mpi_request *req);
void ss_mpi_abort(void);

/* 1 when `flag` is non-zero on any rank (every rank calls it); `flag`
 * without MPI. */
int ss_mpi_any(int flag);

/* Rank 0 receives every other rank's tiles (ss_render_options.tile_stride
 * = size, tile_offset = rank) into `film` and the sums of the work
 * counters into *stats; the other ranks send theirs. Waits at most
 * `timeout` seconds for a rank; returns 0, or 1 after printing why. */
int ss_mpi_gather_film(const char *cmd, ss_film *film, ss_render_stats *stats, double timeout);

/* Splits ss_halfspace_run's batches over the ranks (mpi_halfspace.c):
 * rank r traces the batches b with b % size == r and sends each to rank 0,
 * whose run takes the others' sums from the messages, merged in batch order
 * as in one process. `channel` (0, 1, 2) keeps the runs of successive
 * channels apart. The context lives as long as the run. */
typedef struct {
  int channel;
  double t0;         /* when the run started */
  double first_done; /* when rank 0 finished its first batch; 0: not yet */
  const char *cmd;
} ss_mpi_batches;

void ss_mpi_split_batches(ss_halfspace_params *p, ss_mpi_batches *ctx, const char *cmd,
                          int channel);

#endif
