/* An isotropic medium as the finite elements' per-element callback, shared
 * by the fem tests and validations. */
#ifndef SUBSURF_TESTS_FEM_ISO_MEDIUM_H
#define SUBSURF_TESTS_FEM_ISO_MEDIUM_H

#include "subsurf/fem.h"

typedef struct {
  double sigma_s_prime, sigma_a;
} iso_medium;

static inline ss_status iso(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err) {
  (void)x;
  (void)err;
  const iso_medium *m = ctx;
  *out = ss_fem_coeffs_isotropic(m->sigma_s_prime, m->sigma_a);
  return SS_OK;
}

#endif
