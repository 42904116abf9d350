/* The random walk for layered surfaces (layer.h, ss_layer_mc).
 *
 * The layers are invariant along the surface, so the walk needs the depth
 * alone (the 1D scattering equation, PharrHanrahan2000 eq. 3.4, whose
 * integral it samples: the depth of the next event from the exponential
 * attenuation, the new direction from the phase function). Depth is optical
 * depth t from the top face (the layers' optical depths add), a path carries
 * power per unit area of the surface (the beam brings 1 - F(mu0)), and
 * absorption is by weight with Russian roulette.
 *
 * f at an exact direction: a scattering event of power W in a layer of albedo
 * a emits W a p(cos Theta) per unit optical depth and steradian, so it adds
 * W a p exp(-t / mu) / mu to the radiance reaching the top along the inside
 * cosine mu, and its image through the far face W a p' R exp(-(2 tau - t) /
 * mu) / mu; outside, the face's transmittance, radiance / n^2 and the
 * specular bounces between the faces, 1 / (1 - R_top R_bottom exp(-2 tau /
 * mu)). With E cos theta_i = 1 that radiance is f. The base of albedo A hit
 * with power W reflects radiance W A / pi. */
#include "subsurf/batch_runner.h"
#include "subsurf/layer.h"
#include "subsurf/walk.h"

#include "transport/batch_stop.h"

#include <math.h>
#include <omp.h>
#include <string.h>

/* Bins of a path: the totals, then brdf and btdf per direction. */
enum { BIN_R, BIN_RU, BIN_T, BIN_TU, BIN_A, BIN_F };
#define CHECK_INTERVAL 256

/* One requested direction inside: propagation, cosine and the factor from
 * inside radiance to f (0: no light leaves that way). */
typedef struct {
  ss_vec3 dir;
  double mu, factor;
} exit_dir;

typedef struct {
  const ss_layer_params *p;
  double tau, bound[SS_LAYER_MAX_LAYERS + 1];
  double t_in; /* 1 - F(mu0): the power that enters */
  ss_vec3 beam;
  exit_dir up[SS_LAYER_MAX_DIRECTIONS], down[SS_LAYER_MAX_DIRECTIONS];
  size_t nbins;
} walk;

typedef struct {
  const walk *w;
  uint64_t bsize;
  ss_batch_stop halt;
} run_state;

static double face_reflectance(const ss_layer_params *p, double mu, int bottom) {
  if (bottom && p->bottom != SS_LAYER_BOTTOM_SAME) {
    return 0.0;
  }
  return p->eta == 1.0 ? 0.0 : ss_fresnel_dielectric(-mu, p->eta);
}

static double bounces(const walk *w, double mu) {
  const ss_layer_params *p = w->p;
  return 1.0 /
         (1.0 - face_reflectance(p, mu, 0) * face_reflectance(p, mu, 1) * exp(-2.0 * w->tau / mu));
}

/* The inside image of the outside direction (sin_o, 0, +-cos_o) behind the
 * face, or the direction itself in the medium below an open bottom. */
static exit_dir exit_through(const walk *w, double theta_o, int up) {
  const ss_layer_params *p = w->p;
  exit_dir e = {ss_vec3_make(0.0, 0.0, 0.0), 0.0, 0.0};
  double s = sin(theta_o), c = cos(theta_o);
  if (!up && p->bottom == SS_LAYER_BOTTOM_DIFFUSE) {
    return e;
  }
  int face = up || p->bottom == SS_LAYER_BOTTOM_SAME;
  double si = face ? s / p->eta : s;
  if (si * si >= 1.0) {
    return e;
  }
  e.mu = face ? sqrt(1.0 - si * si) : c;
  e.dir = ss_vec3_make(si, 0.0, up ? e.mu : -e.mu);
  double t = face && p->eta != 1.0 ? 1.0 - ss_fresnel_dielectric(c, p->eta) : 1.0;
  e.factor = (face ? t / (p->eta * p->eta) : 1.0) * bounces(w, e.mu);
  return e;
}

static void walk_init(walk *w, const ss_layer_params *p) {
  memset(w, 0, sizeof *w);
  w->p = p;
  for (int l = 0; l < p->n_layers; ++l) {
    w->bound[l + 1] = w->bound[l] + p->layers[l].tau;
  }
  w->tau = w->bound[p->n_layers];
  double mu0 = cos(p->theta_i), si = sin(p->theta_i) / p->eta;
  w->t_in = p->eta == 1.0 ? 1.0 : 1.0 - ss_fresnel_dielectric(mu0, p->eta);
  w->beam = ss_vec3_make(si, 0.0, si < 1.0 ? -sqrt(1.0 - si * si) : 0.0);
  if (si >= 1.0) {
    w->t_in = 0.0;
  }
  for (int k = 0; k < p->n_theta_o; ++k) {
    w->up[k] = exit_through(w, p->theta_o[k], 1);
    w->down[k] = exit_through(w, p->theta_o[k], 0);
  }
  w->nbins = BIN_F + 2 * (size_t)p->n_theta_o;
}

static ss_vec3 mirror(ss_vec3 d) { return ss_vec3_make(d.x, d.y, -d.z); }

/* Next-event estimates of a scattering event of power wa at depth t. */
static void scatter_estimate(const walk *w, const ss_phase *ph, ss_vec3 d, double t, double wa,
                             double *sums) {
  const ss_layer_params *p = w->p;
  double tau = w->tau;
  for (int k = 0; k < p->n_theta_o; ++k) {
    const exit_dir *u = &w->up[k], *v = &w->down[k];
    if (u->factor > 0.0) {
      double direct = ss_phase_eval(ph, ss_vec3_dot(d, u->dir)) * exp(-t / u->mu);
      double image = face_reflectance(p, u->mu, 1) * exp(-(2.0 * tau - t) / u->mu) *
                     ss_phase_eval(ph, ss_vec3_dot(d, mirror(u->dir)));
      sums[BIN_F + k] += wa * u->factor * (direct + image) / u->mu;
    }
    if (v->factor > 0.0) {
      double direct = ss_phase_eval(ph, ss_vec3_dot(d, v->dir)) * exp(-(tau - t) / v->mu);
      double image = face_reflectance(p, v->mu, 0) * exp(-(tau + t) / v->mu) *
                     ss_phase_eval(ph, ss_vec3_dot(d, mirror(v->dir)));
      sums[BIN_F + p->n_theta_o + k] += wa * v->factor * (direct + image) / v->mu;
    }
  }
}

/* The base lit by power w_base reflects radiance w_base A / pi. */
static void base_estimate(const walk *w, double w_base, double *sums) {
  const ss_layer_params *p = w->p;
  for (int k = 0; k < p->n_theta_o; ++k) {
    const exit_dir *u = &w->up[k];
    if (u->factor > 0.0) {
      sums[BIN_F + k] += w_base * p->bottom_albedo * SS_INV_PI * exp(-w->tau / u->mu) * u->factor;
    }
  }
}

static int layer_at(const walk *w, double t) {
  int l = 0;
  while (l + 1 < w->p->n_layers && t > w->bound[l + 1]) {
    ++l;
  }
  return l;
}

/* Crosses a face at the depth `bottom` says with direction *d: 1 when the
 * path leaves, 0 when it is reflected back (d mirrored). */
static int meets_face(const walk *w, ss_vec3 *d, int bottom, ss_rng *rng) {
  double r = face_reflectance(w->p, fabs(d->z), bottom);
  if (r > 0.0 && ss_rng_uniform(rng) < r) {
    *d = mirror(*d);
    return 0;
  }
  return 1;
}

/* One path; returns its scattering events. */
static uint64_t trace(const walk *w, ss_rng *rng, double *sums) {
  const ss_layer_params *p = w->p;
  double weight = w->t_in, t = 0.0, left = 0.0;
  const double threshold = 0.1 * w->t_in;
  ss_vec3 d = w->beam;
  int scattered = 0;
  uint64_t events = 0;
  while (weight > 0.0) {
    double next = t - ss_walk_free_flight(rng, 1.0) * d.z;
    if (next >= w->tau && p->bottom == SS_LAYER_BOTTOM_DIFFUSE) {
      t = w->tau;
      base_estimate(w, weight, sums);
      weight *= p->bottom_albedo;
      ss_vec3 c = ss_sample_cosine_hemisphere(ss_rng_uniform(rng), ss_rng_uniform(rng));
      d = ss_vec3_make(c.x, c.y, fabs(c.z));
      scattered = 1;
    } else if (next >= w->tau || next <= 0.0) {
      int bottom = next >= w->tau;
      t = bottom ? w->tau : 0.0;
      if (meets_face(w, &d, bottom, rng)) {
        sums[(bottom ? BIN_T : BIN_R) + !scattered] += weight;
        left = weight;
        break;
      }
      continue;
    } else {
      t = next;
      const ss_layer_medium *m = &p->layers[layer_at(w, t)];
      weight *= m->albedo;
      scatter_estimate(w, &m->phase, d, t, weight, sums);
      d = ss_walk_scatter(&m->phase, d, rng);
      scattered = 1;
      ++events;
    }
    if (weight < threshold) {
      /* Russian roulette, unbiased: survivors carry the threshold. */
      weight = ss_rng_uniform(rng) * threshold < weight ? threshold : 0.0;
    }
  }
  sums[BIN_A] += w->t_in - left;
  return events;
}

static uint64_t run_batch(void *ctx, int64_t batch, double *sums, uint64_t *events) {
  run_state *rs = ctx;
  const ss_layer_params *p = rs->w->p;
  uint64_t first = (uint64_t)batch * rs->bsize;
  uint64_t count = p->paths - first < rs->bsize ? p->paths - first : rs->bsize, traced = 0;
  for (; traced < count; ++traced) {
    if (traced % CHECK_INTERVAL == 0 && ss_batch_stop_poll(&rs->halt, p->cancel, 0)) {
      break;
    }
    ss_rng rng;
    ss_rng_seed_item(&rng, p->seed, first + traced);
    *events += trace(rs->w, &rng, sums);
  }
  return traced;
}

static void on_merged(void *ctx, uint64_t done) {
  const ss_layer_params *p = ((const run_state *)ctx)->w->p;
  if (p->progress) {
    p->progress(p->progress_ctx, done, p->paths);
  }
}

static void fill(const walk *w, const ss_batch_tally *t, ss_layer_mc_result *out) {
  const ss_layer_params *p = w->p;
  double *value[] = {&out->value.reflectance, &out->value.reflectance_unscattered,
                     &out->value.transmittance, &out->value.transmittance_unscattered,
                     &out->value.absorbed};
  double *error[] = {&out->error.reflectance, &out->error.reflectance_unscattered,
                     &out->error.transmittance, &out->error.transmittance_unscattered,
                     &out->error.absorbed};
  for (int b = 0; b < BIN_F; ++b) {
    *value[b] = ss_batch_tally_mean(t, (size_t)b);
    *error[b] = ss_batch_tally_stderr(t, (size_t)b);
  }
  for (int k = 0; k < p->n_theta_o; ++k) {
    out->value.brdf[k] = ss_batch_tally_mean(t, BIN_F + (size_t)k);
    out->error.brdf[k] = ss_batch_tally_stderr(t, BIN_F + (size_t)k);
    out->value.btdf[k] = ss_batch_tally_mean(t, BIN_F + (size_t)(p->n_theta_o + k));
    out->error.btdf[k] = ss_batch_tally_stderr(t, BIN_F + (size_t)(p->n_theta_o + k));
  }
  out->value.specular = 1.0 - w->t_in;
}

ss_status ss_layer_mc(const ss_layer_params *p, ss_layer_mc_result *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  ss_status st = ss_layer_validate(p, err);
  if (st != SS_OK) {
    return st;
  }
  walk w;
  walk_init(&w, p);
  ss_batch_tally tally;
  if (ss_batch_tally_init(&tally, w.nbins) != 0) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for the walk's tallies");
  }
  /* Fixed batches (independent of the thread count): at most 1024. */
  run_state rs = {&w, (p->paths + 1023) / 1024, {0, 0}};
  rs.bsize = rs.bsize < 16 ? 16 : rs.bsize;
  double t0 = omp_get_wtime();
  int64_t nbatches = (int64_t)((p->paths + rs.bsize - 1) / rs.bsize);
  st = ss_batch_run(&tally, nbatches, p->threads, run_batch, on_merged, &rs, &out->scatter_events,
                    err);
  if (st == SS_OK) {
    out->paths = tally.paths;
    out->interrupted = rs.halt.interrupted;
    out->seconds = omp_get_wtime() - t0;
    fill(&w, &tally, out);
  }
  ss_batch_tally_free(&tally);
  return st;
}
