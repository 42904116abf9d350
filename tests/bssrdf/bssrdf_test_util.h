/* Helpers shared by the BSSRDF model tests (header-only, static). */
#ifndef SUBSURF_TESTS_BSSRDF_TEST_UTIL_H
#define SUBSURF_TESTS_BSSRDF_TEST_UTIL_H

#include "bssrdf/bssrdf_util.h"
#include "subsurf/bssrdf.h"
#include "subsurf/chi2.h"
#include "subsurf/fresnel.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

/* A gray medium with albedo alpha and extinction sigma_t. */
static inline ss_bssrdf *make_gray(const char *model, double alpha, double sigma_t, double eta,
                                   double g) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, alpha * sigma_t, (1.0 - alpha) * sigma_t, g);
  p.eta = eta;
  ss_bssrdf *b = NULL;
  ss_error err;
  ss_status st = ss_bssrdf_create(model, &p, &b, &err);
  cr_assert_eq(st, SS_OK, "%s: %s", model, err.message);
  return b;
}

typedef struct {
  const ss_bssrdf *b;
  int channel;
  ss_bssrdf_sample_ctx ctx;
} radius_chi2_ctx;

static inline ss_bssrdf_sample_ctx default_sample_ctx(void) {
  ss_bssrdf_sample_ctx c;
  c.x = ss_vec3_make(0, 0, 0);
  c.frame = ss_frame_from_normal(ss_vec3_make(0, 0, 1));
  c.w = ss_vec3_make(0, 0, 1);
  return c;
}

static int radius_sample(void *vctx, double u1, double u2, double *x) {
  radius_chi2_ctx *c = vctx;
  ss_bssrdf_entry e;
  if (!ss_bssrdf_sample_entry(c->b, &c->ctx, c->channel, u1, u2, &e)) {
    return 0;
  }
  *x = e.r;
  return 1;
}

/* Density of the radius: 2 pi r times the area density (radially symmetric). */
static double radius_pdf(void *vctx, double r) {
  radius_chi2_ctx *c = vctx;
  return 2.0 * SS_PI * r * ss_bssrdf_pdf_entry(c->b, &c->ctx, c->channel, r, 0.0);
}

/* A model's entry sampling in world units (ss_chi2_test_1d's callbacks for
 * the radius): each sample's pdf must be pdf_entry's at the sampled point,
 * and the density of r is 2 pi r pdf_entry at the azimuth phi. */
typedef struct {
  ss_bssrdf *b;
  int channel;
  double phi;
  ss_bssrdf_sample_ctx ctx;
} entry_chi2_ctx;

static inline int entry_radius_sample(void *vctx, double u1, double u2, double *x) {
  entry_chi2_ctx *c = vctx;
  ss_bssrdf_entry e;
  if (!ss_bssrdf_sample_entry(c->b, &c->ctx, c->channel, u1, u2, &e)) {
    return 0;
  }
  double pdf = ss_bssrdf_pdf_entry(c->b, &c->ctx, c->channel, e.r, e.phi);
  cr_assert_float_eq(e.pdf, pdf, 1e-9 * pdf);
  *x = e.r;
  return 1;
}

static inline double entry_radius_pdf(void *vctx, double r) {
  entry_chi2_ctx *c = vctx;
  return ss_bssrdf_pdf_entry(c->b, &c->ctx, c->channel, r, c->phi) * 2.0 * SS_PI * r;
}

/* Chi-square test of the radius marginal over the cells between `edges`,
 * plus the check that sample_entry's pdf equals pdf_entry. */
static inline void expect_radius_chi2_edges(const ss_bssrdf *b, int channel, uint64_t seed,
                                            const double *edges, int n) {
  radius_chi2_ctx c = {b, channel, default_sample_ctx()};
  ss_chi2_result res;
  ss_chi2_test_1d(radius_sample, radius_pdf, &c, edges, (size_t)n, 200000, seed, &res);
  cr_expect(res.p_value > ss_chi2_sidak_alpha(0.01, 20), "%s channel %d: %s (p %g)",
            ss_bssrdf_name(b), channel, res.message, res.p_value);
  cr_expect(fabs(res.pdf_integral - 1.0) < 2e-3, "%s: pdf integrates to %g", ss_bssrdf_name(b),
            res.pdf_integral);
  ss_bssrdf_entry e;
  for (int i = 0; i < 100; ++i) {
    double u1 = (i + 0.5) / 100.0, u2 = fmod(0.618034 * i, 1.0);
    if (ss_bssrdf_sample_entry(b, &c.ctx, channel, u1, u2, &e)) {
      double p = ss_bssrdf_pdf_entry(b, &c.ctx, channel, e.r, e.phi);
      cr_expect(fabs(e.pdf - p) <= 1e-9 * p, "sample pdf %g vs pdf_entry %g", e.pdf, p);
    }
  }
}

/* int M dA by the generic radial-average machinery over wide annuli. */
static inline void integrate_exitance(const ss_bssrdf *b, double cos_i, double out[3]) {
  double rmax = 0.0;
  for (int c = 0; c < 3; ++c) {
    rmax = fmax(rmax, ss_bssrdf_max_radius(b, c));
  }
  out[0] = out[1] = out[2] = 0.0;
  double lo = 0.0, hi = rmax * 1e-6;
  while (lo < 64.0 * rmax) {
    double avg[3];
    ss_bssrdf_radial_average(b, cos_i, lo, hi, avg);
    for (int c = 0; c < 3; ++c) {
      out[c] += avg[c] * SS_PI * (hi * hi - lo * lo);
    }
    lo = hi;
    hi *= 2.0;
  }
}

/* The query with its two ends exchanged: (x_o, n_o, w_o; x_i, n_i, w_i). */
static inline ss_bssrdf_query reversed_query(const ss_bssrdf_query *q) {
  ss_bssrdf_query r = *q;
  r.x_i = q->x_o;
  r.n_i = q->n_o;
  r.w_i = q->w_o;
  r.x_o = q->x_i;
  r.n_o = q->n_i;
  r.w_o = q->w_i;
  return r;
}

/* S(x_i, w_i; x_o, w_o) == S(x_o, w_o; x_i, w_i) on n random curved
 * configurations (different normals, the exit point off the entry's plane). */
static inline void expect_reciprocal_curved(const ss_bssrdf *b, int n, uint64_t seed,
                                            double rel_tol) {
  ss_rng rng;
  ss_rng_seed(&rng, 8, seed);
  for (int i = 0; i < n; ++i) {
    ss_bssrdf_query q = {.thickness = 0.0};
    q.x_i = ss_vec3_make(0.0, 0.0, 0.0);
    q.x_o =
        ss_vec3_make(2.0 * ss_rng_uniform(&rng), ss_rng_uniform(&rng), -0.3 * ss_rng_uniform(&rng));
    q.n_i = ss_vec3_normalize(ss_vec3_make(0.3 * ss_rng_uniform(&rng), 0.2, 1.0));
    q.n_o = ss_vec3_normalize(ss_vec3_make(-0.2, 0.4 * ss_rng_uniform(&rng), 1.0));
    q.w_i =
        ss_vec3_normalize(ss_vec3_add(q.n_i, ss_vec3_make(-0.6 * ss_rng_uniform(&rng), 0.1, 0.0)));
    q.w_o =
        ss_vec3_normalize(ss_vec3_add(q.n_o, ss_vec3_make(0.8 * ss_rng_uniform(&rng), -0.2, 0.0)));
    ss_bssrdf_query r = reversed_query(&q);
    double a[3], c[3];
    ss_bssrdf_eval(b, &q, a);
    ss_bssrdf_eval(b, &r, c);
    cr_expect(fabs(a[0] - c[0]) <= rel_tol * fmax(a[0], c[0]) + 1e-300, "%s %d: %g vs %g",
              ss_bssrdf_name(b), i, a[0], c[0]);
  }
}

/* S(x_i, w_i; x_o, w_o) == S(x_o, w_o; x_i, w_i) on random flat configurations. */
static inline void expect_reciprocal(const ss_bssrdf *b, double rel_tol) {
  ss_rng rng;
  ss_rng_seed(&rng, 7, 1);
  for (int i = 0; i < 200; ++i) {
    ss_bssrdf_query q = {.thickness = 0.0};
    q.x_i = ss_vec3_make(ss_rng_uniform(&rng) - 0.5, ss_rng_uniform(&rng) - 0.5, 0.0);
    q.x_o = ss_vec3_make(2.0 * ss_rng_uniform(&rng) - 1.0, 2.0 * ss_rng_uniform(&rng) - 1.0, 0.0);
    q.n_i = q.n_o = ss_vec3_make(0, 0, 1);
    q.w_i = ss_sample_uniform_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    q.w_o = ss_sample_uniform_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    ss_bssrdf_query s = reversed_query(&q);
    double a[3], c[3];
    ss_bssrdf_eval(b, &q, a);
    ss_bssrdf_eval(b, &s, c);
    for (int k = 0; k < 3; ++k) {
      cr_expect(fabs(a[k] - c[k]) <= rel_tol * fmax(fabs(a[k]), 1e-300), "%s: %g vs %g",
                ss_bssrdf_name(b), a[k], c[k]);
    }
  }
}

#endif
