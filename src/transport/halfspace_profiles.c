/* Radial exitance profiles of the half-space for many albedos at once
 * (halfspace_profiles.h). */
#include "subsurf/halfspace_profiles.h"

#include "subsurf/batch_runner.h"
#include "subsurf/fresnel.h"
#include "subsurf/rng.h"
#include "subsurf/stats.h"
#include "subsurf/walk.h"

#include "transport/batch_stop.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#define CHECK_INTERVAL 64

typedef struct {
  const ss_halfspace_profiles_params *p;
  ss_phase phase;
  double entry_weight; /* 1 - Fr at normal incidence */
  double log_alpha[SS_HALFSPACE_PROFILES_MAX_ALBEDOS];
  double log_scale[SS_HALFSPACE_PROFILES_MAX_ALBEDOS]; /* ln sigma_t' (sigma_t = 1) */
  double log_rmin, log_step;
  size_t stride, nbins; /* per albedo: reflectance, then the radial bins; then truncated */
  double t0;
  ss_batch_stop halt;
} tracer;

void ss_halfspace_profiles_params_default(ss_halfspace_profiles_params *p) {
  memset(p, 0, sizeof *p);
  p->eta = 1.3;
  p->rmin = 0.01;
  p->rmax = 300.0;
  p->rbins = 321;
  p->paths = 1000000;
  p->max_depth = 100000;
}

static ss_status validate(const ss_halfspace_profiles_params *p, ss_error *err) {
  if (!(p->eta >= SS_HALFSPACE_ETA_MIN && p->eta <= SS_HALFSPACE_ETA_MAX)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "eta: expected a number in [%g, %g], got %g",
                        SS_HALFSPACE_ETA_MIN, SS_HALFSPACE_ETA_MAX, p->eta);
  }
  if (!(fabs(p->g) < 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "g: expected |g| < 1, got %g", p->g);
  }
  if (p->n_albedo < 1 || p->n_albedo > SS_HALFSPACE_PROFILES_MAX_ALBEDOS) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "expected 1 to %d albedos, got %d",
                        SS_HALFSPACE_PROFILES_MAX_ALBEDOS, p->n_albedo);
  }
  for (int k = 0; k < p->n_albedo; ++k) {
    if (!(p->albedo[k] > 0.0 && p->albedo[k] <= 1.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "albedo %d: expected (0, 1], got %g", k,
                          p->albedo[k]);
    }
  }
  if (!(p->rmin > 0.0 && p->rmax > p->rmin && p->rmax <= SS_HALFSPACE_MAX_LENGTH) || p->rbins < 2 ||
      p->rbins > 100000) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "radial bins: expected 0 < rmin < rmax <= %g and 2 to 100000 bins",
                        SS_HALFSPACE_MAX_LENGTH);
  }
  if (p->paths < 1 || p->max_depth < 1) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "paths and max_depth must be >= 1");
  }
  return SS_OK;
}

static int radial_bin(const tracer *tr, double log_r) {
  if (log_r < tr->log_rmin) {
    return 0;
  }
  double b = (log_r - tr->log_rmin) / tr->log_step;
  return b < tr->p->rbins - 1 ? 1 + (int)b : -1;
}

/* One path without absorption: at its exit, n scattering events later, every
 * albedo's tally receives alpha^n (Kienle1996), in the radius scaled
 * to that albedo's 1/sigma_t'. */
static uint64_t trace_path(const tracer *tr, ss_rng *rng, double *t) {
  const ss_halfspace_profiles_params *p = tr->p;
  ss_vec3 pos = ss_vec3_make(0.0, 0.0, 0.0), dir = ss_vec3_make(0.0, 0.0, -1.0);
  const ss_vec3 up = ss_vec3_make(0.0, 0.0, 1.0);
  uint64_t events = 0;
  for (;;) {
    double s = ss_walk_free_flight(rng, 1.0);
    if (dir.z > 0.0 && s >= -pos.z / dir.z) {
      pos = ss_vec3_madd(pos, dir, -pos.z / dir.z);
      pos.z = 0.0;
      if (ss_walk_cross_boundary(&dir, up, p->eta, rng) == SS_WALK_REFLECTED) {
        continue;
      }
      double log_r = 0.5 * log(pos.x * pos.x + pos.y * pos.y);
      for (int k = 0; k < p->n_albedo; ++k) {
        double w = tr->entry_weight * exp((double)events * tr->log_alpha[k]);
        double *tk = t + (size_t)k * tr->stride;
        tk[0] += w;
        int rb = radial_bin(tr, log_r + tr->log_scale[k]);
        if (rb >= 0) {
          tk[1 + rb] += w;
        }
      }
      return events;
    }
    pos = ss_vec3_madd(pos, dir, s);
    if (events == p->max_depth) {
      t[tr->nbins - 1] += tr->entry_weight;
      return events;
    }
    ++events;
    dir = ss_walk_scatter(&tr->phase, dir, rng);
  }
}

static uint64_t batch_size_for(uint64_t paths) {
  uint64_t b = (paths + 1023) / 1024;
  return b < 16 ? 16 : b;
}

static uint64_t run_batch(void *ctx, int64_t batch, double *sums, uint64_t *events) {
  tracer *tr = ctx;
  const ss_halfspace_profiles_params *p = tr->p;
  uint64_t bsize = batch_size_for(p->paths), first = (uint64_t)batch * bsize;
  uint64_t count = p->paths - first < bsize ? p->paths - first : bsize, traced = 0;
  for (; traced < count; ++traced) {
    if (traced % CHECK_INTERVAL == 0 && ss_batch_stop_poll(&tr->halt, p->cancel, 0)) {
      break;
    }
    ss_rng rng;
    ss_rng_seed_item(&rng, p->seed, first + traced);
    *events += trace_path(tr, &rng, sums);
  }
  return traced;
}

static void on_merged(void *ctx, uint64_t done) {
  const tracer *tr = ctx;
  if (tr->p->progress) {
    tr->p->progress(tr->p->progress_ctx, done, tr->p->paths);
  }
}

void ss_halfspace_profiles_result_destroy(ss_halfspace_profiles_result *r) {
  if (r) {
    free(r->r_lo);
    free(r->r_hi);
    free(r->reflectance);
    free(r->radial);
    free(r);
  }
}

static ss_halfspace_profiles_result *result_create(const ss_halfspace_profiles_params *p) {
  ss_halfspace_profiles_result *r = calloc(1, sizeof *r);
  if (!r) {
    return NULL;
  }
  r->n_albedo = p->n_albedo;
  r->rbins = p->rbins;
  r->r_lo = malloc((size_t)p->rbins * sizeof *r->r_lo);
  r->r_hi = malloc((size_t)p->rbins * sizeof *r->r_hi);
  r->reflectance = calloc((size_t)p->n_albedo, sizeof *r->reflectance);
  r->radial = calloc((size_t)p->n_albedo * (size_t)p->rbins, sizeof *r->radial);
  if (!r->r_lo || !r->r_hi || !r->reflectance || !r->radial) {
    ss_halfspace_profiles_result_destroy(r);
    return NULL;
  }
  double step = (log(p->rmax) - log(p->rmin)) / (p->rbins - 1);
  for (int i = 0; i < p->rbins; ++i) {
    r->r_lo[i] = i == 0 ? 0.0 : p->rmin * exp(step * (i - 1));
    r->r_hi[i] = p->rmin * exp(step * i);
  }
  return r;
}

ss_status ss_halfspace_profiles_run(const ss_halfspace_profiles_params *p,
                                    ss_halfspace_profiles_result **out, ss_error *err) {
  *out = NULL;
  ss_status st = validate(p, err);
  if (st != SS_OK) {
    return st;
  }
  tracer tr;
  memset(&tr, 0, sizeof tr);
  tr.p = p;
  ss_phase_init(&tr.phase, SS_PHASE_HG, p->g, NULL);
  tr.entry_weight = 1.0 - ss_fresnel_dielectric(1.0, p->eta);
  for (int k = 0; k < p->n_albedo; ++k) {
    tr.log_alpha[k] = log(p->albedo[k]);
    tr.log_scale[k] = log(1.0 - p->g * p->albedo[k]);
  }
  tr.log_rmin = log(p->rmin);
  tr.log_step = (log(p->rmax) - tr.log_rmin) / (p->rbins - 1);
  tr.stride = 1 + (size_t)p->rbins;
  tr.nbins = tr.stride * (size_t)p->n_albedo + 1;
  ss_halfspace_profiles_result *r = result_create(p);
  ss_batch_tally tally;
  if (!r || ss_batch_tally_init(&tally, tr.nbins) != 0) {
    ss_halfspace_profiles_result_destroy(r);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for %zu tally bins", tr.nbins);
  }
  tr.t0 = omp_get_wtime();
  uint64_t bsize = batch_size_for(p->paths), events = 0;
  int64_t nbatches = (int64_t)((p->paths + bsize - 1) / bsize);
  st = ss_batch_run(&tally, nbatches, p->threads, run_batch, on_merged, &tr, &events, err);
  if (st != SS_OK) {
    ss_batch_tally_free(&tally);
    ss_halfspace_profiles_result_destroy(r);
    return st;
  }
  r->paths = tally.paths;
  r->scatter_events = events;
  r->seconds = omp_get_wtime() - tr.t0;
  r->interrupted = tr.halt.interrupted;
  r->truncated.value = ss_batch_tally_mean(&tally, tr.nbins - 1);
  r->truncated.error = ss_batch_tally_stderr(&tally, tr.nbins - 1);
  for (int k = 0; k < p->n_albedo; ++k) {
    size_t base = (size_t)k * tr.stride;
    r->reflectance[k].value = ss_batch_tally_mean(&tally, base);
    r->reflectance[k].error = ss_batch_tally_stderr(&tally, base);
    for (int i = 0; i < p->rbins; ++i) {
      double area = SS_PI * (r->r_hi[i] * r->r_hi[i] - r->r_lo[i] * r->r_lo[i]);
      ss_estimate *e = &r->radial[(size_t)k * (size_t)p->rbins + (size_t)i];
      e->value = ss_batch_tally_mean(&tally, base + 1 + (size_t)i) / area;
      e->error = ss_batch_tally_stderr(&tally, base + 1 + (size_t)i) / area;
    }
  }
  ss_batch_tally_free(&tally);
  *out = r;
  return SS_OK;
}
