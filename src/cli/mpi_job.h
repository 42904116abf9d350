/* Rendering across processes with Open MPI (docs/render.md, "Many
 * machines"): `mpirun -np N subsurf render ...`. Each rank renders every
 * N-th 16 x 16 tile at the same seed, so each pixel's samples are exactly
 * those a single process draws, and rank 0 collects the pixels: the image is
 * bit-identical for any number of ranks and threads. The library knows
 * nothing of MPI; only the CLI does. Without mpirun nothing is initialised. */
#ifndef SUBSURF_CLI_MPI_JOB_H
#define SUBSURF_CLI_MPI_JOB_H

#include "subsurf/film.h"
#include "subsurf/render.h"

#include <stddef.h>

/* Initialises MPI when the process was started by mpirun (its environment
 * says so); returns the number of ranks (1 without mpirun). */
int ss_mpi_start(void);
/* MPI_Finalize when ss_mpi_start initialised it. */
void ss_mpi_finish(void);
int ss_mpi_rank(void);
int ss_mpi_size(void);

/* 0 when every rank holds the same bytes; otherwise rank 0 prints one line
 * naming `what` ("the command line", a file) and every rank returns 2. */
int ss_mpi_check_same(const char *cmd, const char *what, const void *data, size_t size);
/* The same for a file's content (a file one rank cannot read counts as a
 * difference). */
int ss_mpi_check_same_file(const char *cmd, const char *path);

/* 1 when `flag` is non-zero on any rank (every rank calls it); `flag`
 * without MPI. */
int ss_mpi_any(int flag);

/* Rank 0 receives every other rank's tiles (ss_render_options.tile_stride
 * = size, tile_offset = rank) into `film` and the sums of the work
 * counters into *stats; the other ranks send theirs. Waits at most
 * `timeout` seconds for a rank; returns 0, or 1 after printing why. */
int ss_mpi_gather_film(const char *cmd, ss_film *film, ss_render_stats *stats, double timeout);

#endif
