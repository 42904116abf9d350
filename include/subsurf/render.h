/* Rendering a committed scene into a film: OpenMP over 16 x 16 tiles, in
 * passes of one sample per pixel so that a stopped render is uniformly
 * converged; one parallel region runs as many passes as take about 0.1 s
 * (each tile's passes in order on one thread), so fast passes do not each
 * end at a barrier, and a stopped render's tiles differ by at most one
 * region's passes. Sample s of pixel (x, y) draws its random numbers from the PCG32
 * stream hash(y * width + x, seed), advanced to s * 2^32 (pbrt-v4's
 * IndependentSampler idea): the image is bit-identical for any number of
 * threads and any crop window at a fixed seed. */
#ifndef SUBSURF_RENDER_H
#define SUBSURF_RENDER_H

#include "subsurf/arg.h"
#include "subsurf/film.h"
#include "subsurf/integrator.h"
#include "subsurf/scene.h"
#include "subsurf/status.h"

#include "subsurf/progress.h"

#include <signal.h>
#include <stdint.h>

/* The side of the square tiles a render shares out, one thread to a tile at
 * a time (a window of one tile renders on one thread whatever the threads
 * asked for), and the unit of tile_stride / tile_offset below. In each
 * parallel region thread i of the team (of min(threads, tiles owned)) takes
 * the i-th tile first, then the tiles left go to whichever thread is free,
 * so that every thread renders. */
#define SS_RENDER_TILE 16

/* The most samples per pixel a render takes. */
#define SS_RENDER_MAX_SPP (1 << 30)

/* The grammar of a render's numbers as the command line (`subsurf render
 * --NAME`) and the flat interface take them: spp, threads, seed; ended by
 * {NULL} (arg.h). */
extern const ss_arg ss_render_args[];

/* An integrator's per-scene precomputation (ss_integrator_ops.prepare: the
 * hierarchical integrator's irradiance points and octrees, the fem
 * integrator's mesh and solve), made once by ss_render_prepare and handed to
 * any number of ss_render calls on the same committed scene (its
 * integrator, lights and options unchanged): a render in passes, such as
 * `subsurf compare`'s doubling spp, then prepares once. It depends on the
 * scene alone, not on a render's spp, seed, crop or threads. */
typedef struct ss_render_prepared ss_render_prepared;

typedef struct {
  int spp;
  uint64_t seed;
  int threads;       /* 0: OpenMP's default */
  double time_limit; /* seconds; 0: none */
  int crop[4];       /* x0, y0, x1, y1 (pixels, x1/y1 exclusive); all 0: full image */
  /* Renders only the window's 16 x 16 tiles t with t % tile_stride ==
   * tile_offset (the others stay empty), so that processes can share an
   * image tile by tile; tile_stride 0 or 1: every tile. */
  int tile_stride, tile_offset;
  /* Stops the render (partial result, SS_ERR_INTERRUPTED) when it becomes
   * non-zero; may be NULL. The library installs no signal handler. */
  const volatile sig_atomic_t *cancel;
  /* Reports the camera samples done (counting a resumed film's) out of
   * spp x pixels of the window, from one thread at a time, after each tile
   * and once at the end; NULL: no reports. The library itself never draws. */
  ss_progress_fn progress;
  void *progress_ctx;
  /* A film to continue (e.g. from ss_checkpoint_read) instead of a new one,
   * the crop window's size; ss_render takes it over: it returns it in *film,
   * or destroys it on error. Each pixel resumes at its next sample, so the image is
   * bit-identical to an uninterrupted render. NULL: a new film. */
  ss_film *resume;
  /* Called between passes (every pixel holds whole samples), at most every
   * checkpoint_interval seconds, with the film so far; NULL: never. */
  void (*checkpoint)(void *ctx, const ss_film *film);
  void *checkpoint_ctx;
  double checkpoint_interval;
  /* The scene's prepared integrator state (ss_render_prepare, borrowed);
   * NULL: ss_render prepares and releases its own. */
  const ss_render_prepared *prepared;
} ss_render_options;

typedef struct {
  double seconds;
  uint64_t samples;   /* camera samples traced */
  uint64_t nonfinite; /* NaN/Inf samples dropped */
  uint32_t min_spp;   /* fewest samples of any pixel */
  ss_path_stats work;
  int stopped_by_time;    /* the time limit ended the render early */
  int interrupted;        /* *cancel ended the render early */
  int prepares;           /* integrator preparations this render made (0 or 1) */
  double prepare_seconds; /* their wall time (not in `seconds`) */
  /* Threads that traced camera samples, the most in one parallel region:
   * min(threads, tiles owned) unless the render stopped early or a resumed
   * film held a thread's tiles already. */
  int threads;
} ss_render_stats;

/* Options from the scene's render settings: spp, seed, time limit; full
 * image, default threads, no cancel flag, no progress reports. */
void ss_render_options_from_scene(const ss_scene *scene, ss_render_options *o);

/* Renders with the integrator named in scene->integrator. *film receives the
 * crop window's pixels (or the whole image). Returns SS_OK when finished or
 * stopped by the time limit, SS_ERR_INTERRUPTED (film still valid, partial)
 * when stopped by *cancel, other codes with no film on bad options. */
ss_status ss_render(const ss_scene *scene, const ss_render_options *o, ss_film **film,
                    ss_render_stats *stats, ss_error *err);

/* Runs the scene's integrator's prepare (when it has one) for renders with
 * ss_render_options.prepared = *out; the error of a failed prepare. */
ss_status ss_render_prepare(const ss_scene *scene, ss_render_prepared **out, ss_error *err);
void ss_render_prepared_destroy(ss_render_prepared *p);
/* The integrator preparations p made (0 or 1) and their wall time. */
int ss_render_prepared_count(const ss_render_prepared *p);
double ss_render_prepared_seconds(const ss_render_prepared *p);

/* The radiance estimate of one camera sample, exactly as ss_render draws it
 * (for tests and benchmarks). */
ss_rgb ss_render_sample(const ss_scene *scene, const ss_integrator_ops *ops, const void *state,
                        int x, int y, uint32_t sample, uint64_t seed, ss_path_stats *stats);

#endif
