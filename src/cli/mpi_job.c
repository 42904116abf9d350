/* Rendering across processes with Open MPI (mpi_job.h), whose calls go
 * through the plugin of mpi_plugin.h. */
#include "cli/mpi_job.h"

#include "cli/mpi_plugin.h"
#include "io/plugin.h"
#include "subsurf/progress.h"

#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const ss_mpi_plugin_api *mpi; /* set when ss_mpi_start initialised MPI */
static int rank, size = 1;
static double t_start;       /* when MPI_Init returned */
static const char *job = ""; /* the command, for messages (ss_mpi_check_args) */
/* Worker threads call MPI (halfspace's batches) one at a time. */
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

int ss_mpi_start(void) {
  if (!getenv("OMPI_COMM_WORLD_SIZE") && !getenv("PMIX_RANK")) {
    return 1;
  }
  ss_error err;
  void *plugin; /* its ss_mpi_plugin */
  const ss_dynlib_symbol symbol = {"ss_mpi_plugin", &plugin};
  if (ss_plugin_open(SS_MPI_PLUGIN_FILE, "mpirun", "libopenmpi", &symbol, 1, &err) != SS_OK) {
    fprintf(stderr, "subsurf: %s\n", err.message);
    exit(1);
  }
  const ss_mpi_plugin_api *api = plugin;
  if (api->init(&rank, &size) != 0) {
    fprintf(stderr, "subsurf: MPI_Init failed (threads calling MPI in turn are needed)\n");
    exit(1);
  }
  mpi = api;
  t_start = ss_seconds();
  return size;
}

void ss_mpi_finish(void) {
  if (mpi) {
    mpi->finalize();
  }
}

int ss_mpi_rank(void) { return rank; }
int ss_mpi_size(void) { return size; }

/* FNV-1a, 64 bits: the fingerprint the ranks compare. */
static uint64_t fingerprint(const void *data, size_t n) {
  const unsigned char *p = data;
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < n; i++) {
    h = (h ^ p[i]) * 1099511628211ull;
  }
  return h;
}

void ss_mpi_abort(void) { mpi->abort(1); }

/* Waits for a request, at most `timeout` seconds. */
static int wait_for(ss_mpi_request *req, double timeout) {
  double start = ss_seconds();
  for (;;) {
    int done = ss_mpi_test(req);
    if (done != 0) {
      return done < 0 ? -1 : 0;
    }
    if (ss_seconds() - start > timeout) {
      return 1;
    }
    struct timespec pause = {0, 1000000};
    nanosleep(&pause, NULL);
  }
}

/* An all-reduce of the start-up (the ranks compare their command lines,
 * files and set-up results). It waits for the other ranks at most
 * SUBSURF_MPI_TIMEOUT plus twice the time this rank has run since MPI
 * started (a rank slower to load a scene delays the others by about as
 * much); a rank stopped or stuck there ends the job, as in the later stages,
 * since MPI_Finalize would wait for it forever. 0, or -1 when MPI failed. */
static int start_up_allreduce(const void *in, void *out, int count, int type, int op,
                              const char *what) {
  ss_mpi_request req;
  if (mpi->iallreduce(in, out, count, type, op, &req) != 0) {
    return -1;
  }
  double limit = ss_mpi_timeout() + 2.0 * (ss_seconds() - t_start);
  int waited = wait_for(&req, limit);
  if (waited > 0) {
    fprintf(stderr,
            "subsurf %s: rank %d: not all %d MPI ranks answered within %.0f s while the ranks "
            "compared %s at start-up (a rank stopped or stuck; SUBSURF_MPI_TIMEOUT sets the "
            "time-out); the job fails\n",
            job, rank, size, limit, what);
    ss_mpi_abort();
  }
  return waited;
}

static int agree(const char *what, uint64_t h) {
  /* One reduction gives both the least and the greatest fingerprint:
   * max(h) = ~min(~h). */
  uint64_t in[2] = {h, ~h}, lo[2] = {0, 0};
  if (start_up_allreduce(in, lo, 2, SS_MPI_UINT64, SS_MPI_MIN, what) != 0) {
    fprintf(stderr, "subsurf %s: rank %d: MPI failed while the ranks compared %s\n", job, rank,
            what);
    return 2;
  }
  if (lo[0] != ~lo[1]) {
    if (rank == 0) {
      fprintf(stderr,
              "subsurf %s: the %d MPI ranks disagree on %s (each rank must be started with the "
              "same arguments and see the same files)\n",
              job, size, what);
    }
    return 2;
  }
  return 0;
}

int ss_mpi_check_same(const char *cmd, const char *what, const void *data, size_t n) {
  job = cmd;
  return size > 1 ? agree(what, fingerprint(data, n)) : 0;
}

int ss_mpi_check_same_file(const char *cmd, const char *path) {
  if (size <= 1) {
    return 0;
  }
  uint64_t h = (uint64_t)rank + 1; /* differs from every other rank's if unreadable */
  FILE *f = fopen(path, "rb");
  if (f) {
    h = 1469598103934665603ull;
    unsigned char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
      h ^= fingerprint(buf, n);
      h *= 1099511628211ull;
    }
    fclose(f);
  }
  char what[600];
  snprintf(what, sizeof what, "the content of %s", path);
  job = cmd;
  return agree(what, h);
}

int ss_mpi_any(int flag) {
  if (size <= 1) {
    return flag != 0;
  }
  int mine = flag != 0, any = 1;
  if (mpi->allreduce(&mine, &any, 1, SS_MPI_INT, SS_MPI_MAX) != 0) {
    return 1;
  }
  return any;
}

int ss_mpi_check_args(const char *cmd, int argc, char **argv) {
  char line[8192];
  size_t used = 0;
  for (int i = 0; i < argc && used < sizeof line; i++) {
    int n = snprintf(line + used, sizeof line - used, "%s%c", argv[i], 0);
    used += n > 0 ? (size_t)n + 1 : 0;
  }
  return ss_mpi_check_same(cmd, "the command line", line, used < sizeof line ? used : sizeof line);
}

int ss_mpi_all_ok(int rc) {
  if (size <= 1) {
    return rc;
  }
  int mine = rc != 0, any = 1;
  if (start_up_allreduce(&mine, &any, 1, SS_MPI_INT, SS_MPI_MAX, "whether each could go on") != 0) {
    any = 1;
  }
  return any ? (rc ? rc : 2) : 0;
}

double ss_mpi_timeout(void) {
  const char *v = getenv("SUBSURF_MPI_TIMEOUT");
  double t = v ? atof(v) : 0.0;
  return t > 0.0 && t < 1e9 ? t : 60.0;
}

int ss_mpi_test(ss_mpi_request *request) {
  pthread_mutex_lock(&lock);
  int done = mpi->test(request);
  pthread_mutex_unlock(&lock);
  return done;
}

int ss_mpi_isend(const void *buf, int bytes, int to, int tag, ss_mpi_request *req) {
  return mpi->isend(buf, bytes, SS_MPI_BYTE, to, tag, req);
}

int ss_mpi_irecv(void *buf, int bytes, int from, int tag, ss_mpi_request *req) {
  return mpi->irecv(buf, bytes, SS_MPI_BYTE, from, tag, req);
}

void ss_mpi_locked(int on) {
  if (on) {
    pthread_mutex_lock(&lock);
  } else {
    pthread_mutex_unlock(&lock);
  }
}

/* Copies the pixels of rank r's tiles (raster order) between the film and
 * a packed buffer: out when `pack`, in otherwise. Returns their number. */
static size_t tile_pixels(ss_film *film, int r, ss_film_pixel_state *buf, int pack) {
  int w = ss_film_width(film), h = ss_film_height(film);
  int tiles_x = (w + SS_RENDER_TILE - 1) / SS_RENDER_TILE;
  size_t k = 0;
  for (int y = 0; y < h; y++) {
    for (int x = 0; x < w; x++) {
      if ((y / SS_RENDER_TILE * tiles_x + x / SS_RENDER_TILE) % size != r) {
        continue;
      }
      if (buf && pack) {
        ss_film_get_pixel_state(film, x, y, &buf[k]);
      } else if (buf) {
        ss_film_set_pixel_state(film, x, y, &buf[k]);
      }
      k++;
    }
  }
  return k;
}

int ss_mpi_gather_film(const char *cmd, ss_film *film, ss_render_stats *stats, double timeout) {
  if (size <= 1) {
    return 0;
  }
  /* ss_path_stats is a struct of uint64_t counters: summed as an array. */
  enum { COUNTERS = sizeof(ss_path_stats) / sizeof(uint64_t) };
  _Static_assert(sizeof(ss_path_stats) % sizeof(uint64_t) == 0, "ss_path_stats: uint64_t only");
  ss_path_stats work = stats->work, sum;
  mpi->reduce(&work, &sum, COUNTERS, SS_MPI_UINT64, SS_MPI_SUM, 0);
  /* Each rank sends only its own tiles' pixels: one film in all. */
  size_t most = 0;
  for (int r = 0; r < size; r++) {
    size_t n = tile_pixels(film, r, NULL, 0);
    most = n > most ? n : most;
  }
  ss_film_pixel_state *px = malloc((most ? most : 1) * sizeof *px);
  if (!px) {
    fprintf(stderr, "subsurf %s: rank %d: out of memory for the film exchange\n", cmd, rank);
    ss_mpi_abort();
    return 1;
  }
  int rc = 0;
  if (rank != 0) {
    size_t n = tile_pixels(film, rank, px, 1);
    ss_mpi_request req;
    if (ss_mpi_isend(px, (int)(n * sizeof *px), 0, 1, &req) != 0 || wait_for(&req, timeout) != 0) {
      fprintf(stderr, "subsurf %s: rank %d could not send its tiles to rank 0\n", cmd, rank);
      rc = 1;
    }
    free(px);
    return rc;
  }
  for (int r = 1; r < size && rc == 0; r++) {
    size_t n = tile_pixels(film, r, NULL, 0);
    ss_mpi_request req;
    int wr = ss_mpi_irecv(px, (int)(n * sizeof *px), r, 1, &req);
    int waited = wr == 0 ? wait_for(&req, timeout) : -1;
    if (waited != 0) {
      fprintf(stderr, "subsurf %s: rank %d %s; the job fails\n", cmd, r,
              waited > 0 ? "sent no tiles within the time-out" : "was lost");
      ss_mpi_abort();
      rc = 1;
      break;
    }
    tile_pixels(film, r, px, 0);
  }
  free(px);
  stats->work = sum;
  stats->samples = sum.camera_rays;
  stats->nonfinite = ss_film_nonfinite_count(film);
  stats->min_spp = ss_film_min_samples(film);
  return rc;
}
