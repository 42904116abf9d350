/* Per-pixel trimmed mean of independent render passes (trimmed_render.h). */
#include "subsurf/trimmed_render.h"

#include "subsurf/trimmed_mean.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static ss_status check_split(const ss_render_options *o, int passes, ss_error *err) {
  if (passes < 1 || o->spp < passes || o->spp % passes != 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "trimmed mean: %d passes must divide the samples per pixel (%d)", passes,
                        o->spp);
  }
  if (o->time_limit > 0.0 || o->resume || o->checkpoint) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "trimmed mean: passes take no time limit, checkpoint or film to resume");
  }
  return SS_OK;
}

static void window(const ss_scene *scene, const ss_render_options *o, int *w, int *h) {
  int crop = o->crop[2] > 0;
  *w = crop ? o->crop[2] - o->crop[0] : scene->camera.width;
  *h = crop ? o->crop[3] - o->crop[1] : scene->camera.height;
}

/* Every pixel's state after `skip` drawn samples, none of them kept (a
 * resumed film continues each pixel at its next sample). */
static void set_skipped(ss_film *film, uint32_t skip) {
  ss_film_pixel_state s;
  for (int y = 0; y < ss_film_height(film); ++y) {
    for (int x = 0; x < ss_film_width(film); ++x) {
      ss_film_get_pixel_state(film, x, y, &s);
      s.rejected -= skip;
      ss_film_set_pixel_state(film, x, y, &s);
    }
  }
}

static ss_status render_pass(const ss_scene *scene, const ss_render_options *o, int pass,
                             int passes, ss_film **film, ss_render_stats *stats, ss_error *err) {
  *film = NULL;
  int w, h;
  window(scene, o, &w, &h);
  uint32_t per = (uint32_t)(o->spp / passes), skip = (uint32_t)pass * per;
  ss_film *start;
  ss_status st = ss_film_create(w, h, &start, err);
  if (st != SS_OK) {
    return st;
  }
  ss_film_pixel_state s = {.n = 0, .rejected = skip};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_film_set_pixel_state(start, x, y, &s);
    }
  }
  ss_render_options po = *o;
  po.spp = (int)(skip + per);
  po.resume = start;
  st = ss_render(scene, &po, film, stats, err);
  if (*film) {
    set_skipped(*film, skip);
    stats->nonfinite = ss_film_nonfinite_count(*film);
  }
  return st;
}

ss_status ss_render_pass(const ss_scene *scene, const ss_render_options *o, int pass, int passes,
                         ss_film **film, ss_render_stats *stats, ss_error *err) {
  *film = NULL;
  memset(stats, 0, sizeof *stats);
  ss_status st = check_split(o, passes, err);
  if (st == SS_OK && (pass < 0 || pass >= passes)) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "trimmed mean: pass %d of %d", pass, passes);
  }
  return st != SS_OK ? st : render_pass(scene, o, pass, passes, film, stats, err);
}

/* One pixel: the trimmed mean of the pass means per channel, and the
 * variance of the mean of the pass means written as Welford's m2. */
static void combine_pixel(ss_film *const *passes, int k, double trim, int x, int y, double *v,
                          ss_film_pixel_state *out) {
  memset(out, 0, sizeof *out);
  ss_film_pixel_state s;
  for (int j = 0; j < k; ++j) {
    ss_film_get_pixel_state(passes[j], x, y, &s);
    out->n += s.n;
    out->rejected += s.rejected;
  }
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, sum2 = 0.0;
    for (int j = 0; j < k; ++j) {
      ss_film_get_pixel_state(passes[j], x, y, &s);
      v[j] = s.mean[c];
      sum += v[j];
      sum2 += v[j] * v[j];
    }
    double var_mean = k > 1 ? fmax(0.0, sum2 - sum * sum / k) / ((double)(k - 1) * (double)k) : 0.0;
    out->mean[c] = ss_trimmed_mean(v, (size_t)k, trim);
    out->m2[c] = out->n > 1 ? var_mean * (double)out->n * (double)(out->n - 1) : 0.0;
  }
}

static ss_status check_trim(int k, double trim, ss_error *err) {
  if (k < 1 || !(trim >= 0.0 && trim < 0.5) || 2 * ss_trimmed_count((size_t)k, trim) >= (size_t)k) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "trimmed mean: the fraction must lie in [0, 0.5) and keep one of %d "
                        "passes, got %g",
                        k, trim);
  }
  return SS_OK;
}

ss_status ss_film_trimmed_combine(ss_film *const *passes, int k, double trim, ss_film **out,
                                  ss_error *err) {
  *out = NULL;
  ss_status st = check_trim(k, trim, err);
  if (st != SS_OK) {
    return st;
  }
  int w = ss_film_width(passes[0]), h = ss_film_height(passes[0]);
  for (int j = 1; j < k; ++j) {
    if (ss_film_width(passes[j]) != w || ss_film_height(passes[j]) != h) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "trimmed mean: passes of different sizes");
    }
  }
  double *v = malloc((size_t)k * sizeof *v);
  st = v ? ss_film_create(w, h, out, err)
         : ss_error_set(err, SS_ERR_NO_MEMORY, "trimmed mean: out of memory");
  for (int y = 0; st == SS_OK && y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_film_pixel_state s;
      combine_pixel(passes, k, trim, x, y, v, &s);
      ss_film_set_pixel_state(*out, x, y, &s);
    }
  }
  free(v);
  return st;
}

/* Progress of one pass reported against the whole render: a pass's
 * reports count from its first sample index, pass x per x pixels. */
typedef struct {
  ss_progress_fn fn;
  void *ctx;
  uint64_t total;
} progress_relay;

static void relay(void *ctx, uint64_t done, uint64_t total) {
  (void)total;
  const progress_relay *r = ctx;
  r->fn(r->ctx, done, r->total);
}

static void add_stats(ss_render_stats *sum, const ss_render_stats *s) {
  sum->seconds += s->seconds;
  sum->samples += s->samples;
  sum->nonfinite += s->nonfinite;
  ss_path_stats_add(&sum->work, &s->work);
  sum->interrupted |= s->interrupted;
  sum->threads = s->threads > sum->threads ? s->threads : sum->threads;
}

ss_status ss_render_trimmed(const ss_scene *scene, const ss_render_options *o, int passes,
                            double trim, ss_film **film, ss_render_stats *stats, ss_error *err) {
  *film = NULL;
  memset(stats, 0, sizeof *stats);
  ss_status st = check_split(o, passes, err);
  if (st == SS_OK) {
    st = check_trim(passes, trim, err);
  }
  ss_film **done = st == SS_OK ? calloc((size_t)passes, sizeof *done) : NULL;
  if (st == SS_OK && !done) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "trimmed mean: out of memory");
  }
  int w, h, k = 0;
  window(scene, o, &w, &h);
  progress_relay r = {o->progress, o->progress_ctx, (uint64_t)o->spp * (uint64_t)w * (uint64_t)h};
  ss_render_options po = *o;
  po.progress = o->progress ? relay : NULL;
  po.progress_ctx = &r;
  ss_film *partial = NULL;
  while (st == SS_OK && k < passes) {
    ss_render_stats ps;
    ss_film *f;
    st = render_pass(scene, &po, k, passes, &f, &ps, err);
    add_stats(stats, &ps);
    if (st == SS_OK) {
      done[k++] = f;
    } else {
      partial = f;
    }
  }
  if (st == SS_OK || (st == SS_ERR_INTERRUPTED && k > 0)) {
    ss_error cerr;
    ss_status cst = ss_film_trimmed_combine(done, k, k == passes ? trim : 0.0, film, &cerr);
    if (cst != SS_OK) {
      st = cst;
      *err = cerr;
    }
    ss_film_destroy(partial);
  } else if (st == SS_ERR_INTERRUPTED) {
    *film = partial;
  }
  for (int j = 0; j < k; ++j) {
    ss_film_destroy(done[j]);
  }
  free(done);
  if (*film) {
    stats->min_spp = ss_film_min_samples(*film);
  }
  return st;
}
