/* Chandrasekhar's H-function for isotropic scattering (Radiative Transfer,
 * 1950, ch. V), solved independently of the code under test, for exact
 * half-space anchors. */
#ifndef SUBSURF_TESTS_CHANDRASEKHAR_H
#define SUBSURF_TESTS_CHANDRASEKHAR_H

#include <gsl/gsl_integration.h>
#include <math.h>

#define H_NODES 96

typedef struct {
  double albedo;
  double x[H_NODES], w[H_NODES], h[H_NODES];
} h_function;

/* 1/H(mu) = sqrt(1 - albedo) + (albedo/2) int_0^1 mu' H(mu') / (mu + mu') dmu'
 * (Chandrasekhar 1950, eq. V.(10) form), iterated to a fixed point. */
static inline double h_eval_with(const h_function *hf, double mu) {
  double s = 0.0;
  for (int j = 0; j < H_NODES; ++j) {
    s += hf->w[j] * hf->x[j] * hf->h[j] / (mu + hf->x[j]);
  }
  return 1.0 / (sqrt(1.0 - hf->albedo) + 0.5 * hf->albedo * s);
}

static inline void h_solve(h_function *hf, double albedo) {
  hf->albedo = albedo;
  gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(H_NODES);
  for (int j = 0; j < H_NODES; ++j) {
    gsl_integration_glfixed_point(0.0, 1.0, (size_t)j, &hf->x[j], &hf->w[j], t);
    hf->h[j] = 1.0;
  }
  gsl_integration_glfixed_table_free(t);
  for (int it = 0; it < 2000; ++it) {
    double change = 0.0, next[H_NODES];
    for (int j = 0; j < H_NODES; ++j) {
      next[j] = h_eval_with(hf, hf->x[j]);
      change = fmax(change, fabs(next[j] - hf->h[j]));
    }
    for (int j = 0; j < H_NODES; ++j) {
      hf->h[j] = next[j];
    }
    if (change < 1e-14) {
      break;
    }
  }
}

/* Diffuse albedo of an index-matched half-space lit by a beam at mu0. */
static inline double h_albedo(const h_function *hf, double mu0) {
  return 1.0 - h_eval_with(hf, mu0) * sqrt(1.0 - hf->albedo);
}

/* int L(x, mu) dA per unit incident power (Chandrasekhar's S function for
 * isotropic scattering: I = (F/4) albedo mu0 H(mu) H(mu0) / (mu + mu0) for an
 * incident flux pi F mu0 per unit area). */
static inline double h_radiance(const h_function *hf, double mu, double mu0) {
  return hf->albedo * h_eval_with(hf, mu) * h_eval_with(hf, mu0) / (4.0 * M_PI * (mu + mu0));
}

#endif
