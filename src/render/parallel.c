/* Tiled, deterministic parallel rendering (see render.h). */
#include "subsurf/render.h"

#include "subsurf/progress.h"
#include "subsurf/threads.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#define REGION_SECONDS 0.1
/* The BVH is rebuilt at high quality when a render's camera samples number
 * at least the triangles / REFINE_TRIANGLES_PER_SAMPLE: on the 327 k-triangle
 * skin sphere the rebuild costs about 0.25 s of CPU and the low-quality BVH
 * about 8 us per sample (a 25 % slower render with MNEE): they break even
 * at about 30 k samples (bench/RESULTS.md). */
#define REFINE_TRIANGLES_PER_SAMPLE 8

void ss_render_options_from_scene(const ss_scene *scene, ss_render_options *o) {
  memset(o, 0, sizeof *o);
  o->spp = scene->render.spp;
  o->seed = scene->render.seed;
  o->time_limit = scene->render.time_limit;
  memcpy(o->crop, scene->render.crop, sizeof o->crop);
}

ss_rgb ss_render_sample(const ss_scene *scene, const ss_integrator_ops *ops, const void *state,
                        int x, int y, uint32_t sample, uint64_t seed, ss_path_stats *stats) {
  uint64_t pixel = (uint64_t)y * (uint64_t)scene->camera.width + (uint64_t)x;
  ss_rng rng;
  /* One stream per (pixel, seed); each sample owns 2^32 draws of it. */
  ss_rng_seed(&rng, seed, ss_hash64(pixel ^ ss_hash64(seed)));
  ss_rng_advance(&rng, (uint64_t)sample << 32);
  double u1 = ss_rng_uniform(&rng), u2 = ss_rng_uniform(&rng);
  ss_ray ray = ss_camera_generate_ray(&scene->camera, x, y, u1, u2);
  stats->camera_rays++;
  stats->paths++;
  return ops->li(scene, state, ray, &rng, stats);
}

static ss_status check_options(const ss_scene *scene, const ss_render_options *o, int crop[4],
                               ss_error *err) {
  if (!scene->committed) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "render: the scene is not committed");
  }
  if (o->spp < 1 || o->spp > SS_RENDER_MAX_SPP) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "render: spp must be in [1, %d], got %d",
                        SS_RENDER_MAX_SPP, o->spp);
  }
  if (ss_threads_check(o->threads, err) != SS_OK) {
    ss_error_prefix(err, "render: ");
    return SS_ERR_INVALID_ARGUMENT;
  }
  if (!(o->time_limit >= 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "render: time limit must be >= 0");
  }
  if (o->tile_stride < 0 || o->tile_offset < 0 ||
      (o->tile_stride > 1 && o->tile_offset >= o->tile_stride)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "render: tile offset %d is not in [0, tile stride %d)", o->tile_offset,
                        o->tile_stride);
  }
  int w = scene->camera.width, h = scene->camera.height;
  if (!o->crop[0] && !o->crop[1] && !o->crop[2] && !o->crop[3]) {
    crop[0] = 0;
    crop[1] = 0;
    crop[2] = w;
    crop[3] = h;
    return SS_OK;
  }
  memcpy(crop, o->crop, 4 * sizeof *crop);
  if (crop[0] < 0 || crop[1] < 0 || crop[2] > w || crop[3] > h || crop[0] >= crop[2] ||
      crop[1] >= crop[3]) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "render: crop %d,%d,%d,%d is not a non-empty window of the %d x %d image",
                        crop[0], crop[1], crop[2], crop[3], w, h);
  }
  return SS_OK;
}

struct ss_render_prepared {
  const ss_scene *scene;
  const ss_integrator_ops *ops;
  void *state;
  int count;
  double seconds;
};

static ss_status find_integrator(const ss_scene *scene, const ss_integrator_ops **ops,
                                 ss_error *err) {
  *ops = ss_integrator_find(scene->integrator.name);
  if (!*ops) {
    char names[256];
    ss_integrator_names(names, sizeof names);
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "render: unknown integrator '%s' (known: %s)",
                        scene->integrator.name, names);
  }
  return SS_OK;
}

ss_status ss_render_prepare(const ss_scene *scene, ss_render_prepared **out, ss_error *err) {
  *out = NULL;
  if (!scene->committed) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "render: the scene is not committed");
  }
  ss_render_prepared *p = calloc(1, sizeof *p);
  if (!p) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "render: out of memory");
  }
  p->scene = scene;
  ss_status st = find_integrator(scene, &p->ops, err);
  if (st == SS_OK && p->ops->prepare) {
    double t0 = ss_seconds();
    st = p->ops->prepare(scene, &p->state, err);
    p->seconds = ss_seconds() - t0;
    p->count = 1;
  }
  if (st != SS_OK) {
    ss_render_prepared_destroy(p);
    return st;
  }
  *out = p;
  return SS_OK;
}

void ss_render_prepared_destroy(ss_render_prepared *p) {
  if (p && p->ops && p->ops->release) {
    p->ops->release(p->state);
  }
  free(p);
}

int ss_render_prepared_count(const ss_render_prepared *p) { return p->count; }

double ss_render_prepared_seconds(const ss_render_prepared *p) { return p->seconds; }

typedef struct {
  const ss_scene *scene;
  const ss_integrator_ops *ops;
  const void *state;
  ss_film *film;
  int crop[4];
  int tiles_x;
  int tile_stride, tile_offset; /* the tiles this render owns (render.h) */
  int owned;                    /* their number */
  uint64_t seed;
} job;

/* The number of the k-th tile this render owns, k < j->owned. */
static int owned_tile(const job *j, int k) {
  return j->tile_stride <= 1 ? k : j->tile_offset + k * j->tile_stride;
}

/* Pixels of the window in the tiles this render owns. */
static uint64_t owned_pixels(const job *j) {
  uint64_t n = 0;
  for (int k = 0; k < j->owned; ++k) {
    int t = owned_tile(j, k);
    int x0 = j->crop[0] + (t % j->tiles_x) * SS_RENDER_TILE,
        y0 = j->crop[1] + (t / j->tiles_x) * SS_RENDER_TILE;
    int x1 = x0 + SS_RENDER_TILE < j->crop[2] ? x0 + SS_RENDER_TILE : j->crop[2];
    int y1 = y0 + SS_RENDER_TILE < j->crop[3] ? y0 + SS_RENDER_TILE : j->crop[3];
    n += (uint64_t)(x1 - x0) * (uint64_t)(y1 - y0);
  }
  return n;
}

/* A new film, or the one to resume when it has the window's size. */
static ss_status start_film(const ss_render_options *o, int w, int h, ss_film **film,
                            ss_error *err) {
  if (!o->resume) {
    return ss_film_create(w, h, film, err);
  }
  if (ss_film_width(o->resume) != w || ss_film_height(o->resume) != h) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "render: the film to resume is %d x %d, the window %d x %d",
                        ss_film_width(o->resume), ss_film_height(o->resume), w, h);
  }
  *film = o->resume;
  return SS_OK;
}

static void render_tile(const job *j, int tile, uint32_t sample, ss_path_stats *stats) {
  int tx = tile % j->tiles_x, ty = tile / j->tiles_x;
  int x0 = j->crop[0] + tx * SS_RENDER_TILE, y0 = j->crop[1] + ty * SS_RENDER_TILE;
  int x1 = x0 + SS_RENDER_TILE < j->crop[2] ? x0 + SS_RENDER_TILE : j->crop[2];
  int y1 = y0 + SS_RENDER_TILE < j->crop[3] ? y0 + SS_RENDER_TILE : j->crop[3];
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      if (ss_film_pixel_drawn(j->film, x - j->crop[0], y - j->crop[1]) > sample) {
        continue; /* a resumed film already holds this sample */
      }
      ss_rgb v = ss_render_sample(j->scene, j->ops, j->state, x, y, sample, j->seed, stats);
      ss_film_add_sample(j->film, x - j->crop[0], y - j->crop[1], v);
    }
  }
}

static ss_status render(const ss_scene *scene, const ss_render_options *o, ss_film **film_out,
                        ss_render_stats *stats, ss_error *err);

ss_status ss_render(const ss_scene *scene, const ss_render_options *o, ss_film **film_out,
                    ss_render_stats *stats, ss_error *err) {
  ss_status st = render(scene, o, film_out, stats, err);
  if (!*film_out) {
    ss_film_destroy(o->resume); /* taken over, also on error */
  }
  return st;
}

/* Sets *stop (1: time limit, 2: cancelled) when the render must end;
 * returns it. */
static int check_stop(const ss_render_options *o, double start, int *stop) {
  int halt;
#pragma omp atomic read
  halt = *stop;
  if (halt) {
    return halt;
  }
  if (o->cancel && *o->cancel) {
    halt = 2;
  } else if (o->time_limit > 0.0 && ss_seconds() - start > o->time_limit) {
    halt = 1;
  }
  if (halt) {
#pragma omp atomic write
    *stop = halt;
  }
  return halt;
}

/* Passes per parallel region: enough for about REGION_SECONDS of work, so
 * that a render of many fast passes does not meet a barrier per pass
 * (where the threads spin while one of them is descheduled on a loaded
 * machine), and no more than the time limit or the next checkpoint leave. */
static int region_passes(const ss_render_options *o, double pass_seconds, double elapsed,
                         double since_checkpoint) {
  double target = REGION_SECONDS;
  if (o->time_limit > 0.0) {
    target = fmin(target, o->time_limit - elapsed);
  }
  if (o->checkpoint) {
    target = fmin(target, o->checkpoint_interval - since_checkpoint);
  }
  double k = pass_seconds > 0.0 ? floor(target / pass_seconds) : 1024.0;
  return k < 1.0 ? 1 : k > 1024.0 ? 1024 : (int)k;
}

static ss_status render(const ss_scene *scene, const ss_render_options *o, ss_film **film_out,
                        ss_render_stats *stats, ss_error *err) {
  memset(stats, 0, sizeof *stats);
  *film_out = NULL;
  job j;
  memset(&j, 0, sizeof j);
  ss_status st = check_options(scene, o, j.crop, err);
  if (st != SS_OK) {
    return st;
  }
  if ((st = find_integrator(scene, &j.ops, err)) != SS_OK) {
    return st;
  }
  const ss_render_prepared *given = o->prepared;
  if (given && (given->scene != scene || given->ops != j.ops)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "render: the prepared state is of another scene or integrator");
  }
  uint64_t window = (uint64_t)(j.crop[2] - j.crop[0]) * (uint64_t)(j.crop[3] - j.crop[1]);
  if ((uint64_t)o->spp * window * REFINE_TRIANGLES_PER_SAMPLE >=
          ss_accel_triangle_count(scene->accel) &&
      (st = ss_accel_refine(scene->accel, err)) != SS_OK) {
    return st;
  }
  ss_render_prepared *own = NULL;
  if (!given && (st = ss_render_prepare(scene, &own, err)) != SS_OK) {
    return st;
  }
  if (own) {
    stats->prepares = own->count;
    stats->prepare_seconds = own->seconds;
  }
  void *state = given ? given->state : own->state;
  int fw = j.crop[2] - j.crop[0], fh = j.crop[3] - j.crop[1];
  if ((st = start_film(o, fw, fh, &j.film, err)) != SS_OK) {
    ss_render_prepared_destroy(own);
    return st;
  }
  j.scene = scene;
  j.state = state;
  j.seed = o->seed;
  j.tiles_x = (fw + SS_RENDER_TILE - 1) / SS_RENDER_TILE;
  j.tile_stride = o->tile_stride;
  j.tile_offset = o->tile_offset;
  int tiles = j.tiles_x * ((fh + SS_RENDER_TILE - 1) / SS_RENDER_TILE);
  j.owned =
      j.tile_stride <= 1 ? tiles : (tiles - j.tile_offset + j.tile_stride - 1) / j.tile_stride;
  int threads = ss_threads_team(o->threads);
  /* More threads than tiles would only wait at the region's end. */
  int team = threads < j.owned ? threads : j.owned;

  uint64_t total = (uint64_t)o->spp * owned_pixels(&j);
  uint64_t done = ss_film_sample_count(j.film) + ss_film_nonfinite_count(j.film);
  double start = ss_seconds(), saved = start;
  int stop = 0;  /* 1: time limit, 2: cancelled */
  int group = 1; /* passes per parallel region (region_passes) */
  for (int s = (int)ss_film_min_drawn(j.film); s < o->spp && j.owned > 0 && !stop;) {
    if (o->checkpoint && s > 0 && ss_seconds() - saved >= o->checkpoint_interval) {
      o->checkpoint(o->checkpoint_ctx, j.film);
      saved = ss_seconds();
    }
    double t0 = ss_seconds();
    int end = o->spp - s < group ? o->spp : s + group;
    int handed = 0;    /* tiles handed out after each thread's first */
    int rendering = 0; /* threads that traced camera samples in this region */
#pragma omp parallel num_threads(team)
    {
      /* Thread i starts with the i-th tile, so that every thread of the
       * team renders one (a late-starting thread of a dynamic schedule may
       * find a small image's tiles all taken, and a test of 1 against 2
       * threads would then compare one thread with itself); the others go
       * to whichever thread is free first, one at a time, as with
       * schedule(dynamic, 1). */
      int n = omp_get_num_threads(), traced = 0;
      for (int k = omp_get_thread_num(); k < j.owned;) {
        ss_path_stats local;
        memset(&local, 0, sizeof local);
        for (int p = s; p < end && !check_stop(o, start, &stop); ++p) {
          render_tile(&j, owned_tile(&j, k), (uint32_t)p, &local);
        }
        traced |= local.camera_rays > 0;
#pragma omp critical(ss_render_stats)
        {
          ss_path_stats_add(&stats->work, &local);
          done += local.camera_rays;
          if (o->progress) {
            o->progress(o->progress_ctx, done, total);
          }
        }
        int next;
#pragma omp atomic capture
        next = handed++;
        k = n + next;
      }
      if (traced) {
#pragma omp atomic update
        rendering++;
      }
    }
    stats->threads = rendering > stats->threads ? rendering : stats->threads;
    double now = ss_seconds();
    group = region_passes(o, (now - t0) / (end - s), now - start, now - saved);
    s = end;
  }
  if (o->progress) {
    o->progress(o->progress_ctx, done, total);
  }
  ss_render_prepared_destroy(own);
  stats->seconds = ss_seconds() - start;
  stats->samples = stats->work.camera_rays;
  stats->nonfinite = ss_film_nonfinite_count(j.film);
  stats->min_spp = ss_film_min_samples(j.film);
  stats->stopped_by_time = stop == 1;
  stats->interrupted = stop == 2;
  *film_out = j.film;
  if (stop == 2) {
    return ss_error_set(err, SS_ERR_INTERRUPTED, "render: interrupted after %.1f s",
                        stats->seconds);
  }
  return SS_OK;
}
