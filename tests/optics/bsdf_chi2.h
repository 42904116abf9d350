/* The chi-square callbacks of BSDF sampling shared by the optics tests: a
 * BSDF seen from wo, whose samples must agree with eval() and pdf(). */
#ifndef SUBSURF_TESTS_OPTICS_BSDF_CHI2_H
#define SUBSURF_TESTS_OPTICS_BSDF_CHI2_H

#include "subsurf/bsdf.h"
#include "subsurf/chi2.h"

#include <criterion/criterion.h>
#include <math.h>

typedef struct {
  const ss_bsdf *b;
  ss_vec3 wo;
  double max_weight_error;
} bsdf_ctx;

static int sample_bsdf(void *p, double u1, double u2, double u3, ss_vec3 *dir) {
  bsdf_ctx *c = p;
  ss_bsdf_sample s;
  if (!ss_bsdf_sample_dir(c->b, c->wo, u1, u2, u3, &s)) {
    return 0;
  }
  /* sample() must agree with eval() and pdf() for the direction it returns. */
  double f = ss_bsdf_eval(c->b, c->wo, s.wi).x, pdf = ss_bsdf_pdf(c->b, c->wo, s.wi);
  double e = fabs(f / pdf - s.f.x / s.pdf) / (f / pdf);
  if (e > c->max_weight_error) {
    c->max_weight_error = e;
  }
  *dir = s.wi;
  return 1;
}

static double pdf_bsdf(void *p, ss_vec3 dir) {
  const bsdf_ctx *c = p;
  return ss_bsdf_pdf(c->b, c->wo, dir);
}

/* A rough BSDF seen from wo against its pdf over 50 x 100 cells of the
 * sphere, `samples` draws at `seed`: p-value above `level`; the samples it
 * refuses (below the horizon) exactly the pdf mass it misses (3e-3); every
 * sample's weight f / pdf that of eval() and pdf() (1e-9). */
static inline void expect_rough_bsdf_chi2(const ss_bsdf *b, ss_vec3 wo, uint64_t samples,
                                          uint64_t seed, double level, const char *what) {
  bsdf_ctx c = {b, wo, 0.0};
  ss_chi2_sphere_options opt;
  ss_chi2_sphere_options_default(&opt);
  opt.theta_bins = 50;
  opt.phi_bins = 100;
  opt.samples = samples;
  opt.seed = seed;
  ss_chi2_result res;
  ss_chi2_test_sphere(sample_bsdf, pdf_bsdf, &c, &opt, &res);
  cr_assert_gt(res.p_value, level, "%s: %s", what, res.message);
  double accepted = 1.0 - (double)res.invalid / (double)opt.samples;
  cr_assert_float_eq(res.pdf_integral, accepted, 3e-3, "%s: %s (accepted %g)", what, res.message,
                     accepted);
  cr_assert_lt(c.max_weight_error, 1e-9, "%s", what);
}

#endif
