/* The chi-square callbacks of BSDF sampling shared by the optics tests: a
 * BSDF seen from wo, whose samples must agree with eval() and pdf(). */
#ifndef SUBSURF_TESTS_OPTICS_BSDF_CHI2_H
#define SUBSURF_TESTS_OPTICS_BSDF_CHI2_H

#include "subsurf/bsdf.h"

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

#endif
