/* Phase functions. Directions are propagation directions: cos_theta is the
 * cosine between the direction the light travelled before scattering and the
 * direction after, so g > 0 means forward scattering. Each phase function is
 * normalised over the sphere and samples exactly (pdf == eval). */
#ifndef SUBSURF_PHASE_H
#define SUBSURF_PHASE_H

#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <math.h>

typedef enum {
  SS_PHASE_ISOTROPIC,
  SS_PHASE_HG,    /* Henyey-Greenstein */
  SS_PHASE_GAUSS, /* forward-peaked Gaussian, Frederickx & Dutre 2017 eq. 5 */
} ss_phase_type;

typedef struct {
  ss_phase_type type;
  double g;           /* mean cosine */
  double mu;          /* Gaussian width (SS_PHASE_GAUSS) */
  double norm;        /* Gaussian normalisation N */
  double one_minus_e; /* 1 - exp(-2/mu) */
} ss_phase;

/* Validates g (|g| < 1; 0 for isotropic; 0 <= g < 1 for the Gaussian, which
 * cannot scatter backward on average) and precomputes constants. */
ss_status ss_phase_init(ss_phase *p, ss_phase_type type, double g, ss_error *err);

double ss_phase_eval(const ss_phase *p, double cos_theta);
static inline double ss_phase_pdf(const ss_phase *p, double cos_theta) {
  return ss_phase_eval(p, cos_theta);
}
/* Samples cos(theta) from the phase function's marginal (inline: it sits in
 * the innermost loop of every random walk). */
static inline double ss_phase_sample_cos(const ss_phase *p, double u) {
  switch (p->type) {
  case SS_PHASE_HG: {
    double g = p->g;
    if (fabs(g) < 1e-4) {
      return 1.0 - 2.0 * u;
    }
    /* Inverse of the HG marginal cdf in cos(theta). */
    double sq = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    double c = (1.0 + g * g - sq * sq) / (2.0 * g);
    return c < -1.0 ? -1.0 : (c > 1.0 ? 1.0 : c);
  }
  case SS_PHASE_GAUSS: {
    /* Frederickx & Dutre 2017, sec. 3 (inverse cdf of eq. 5). */
    double c = 1.0 + p->mu * log1p(-u * p->one_minus_e);
    return c < -1.0 ? -1.0 : c;
  }
  case SS_PHASE_ISOTROPIC:
  default:
    return 1.0 - 2.0 * u;
  }
}

/* Samples a new propagation direction given the old one `dir` (unit). */
ss_vec3 ss_phase_sample(const ss_phase *p, ss_vec3 dir, double u1, double u2);

/* The Gaussian's mean cosine g = coth(1/mu) - mu and its inverse. */
double ss_gauss_g_from_mu(double mu);
double ss_gauss_mu_from_g(double g);

/* Parses "iso"/"isotropic", "hg", "gauss"; returns 0 on an unknown name. */
int ss_phase_type_from_name(const char *name, ss_phase_type *type);
const char *ss_phase_type_name(ss_phase_type type);

#endif
