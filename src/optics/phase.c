#include "subsurf/phase.h"

#include "subsurf/sampling.h"

#include <math.h>
#include <string.h>

/* g = coth(1/mu) - mu (Frederickx & Dutre 2017, below eq. 5). For small mu,
 * coth(1/mu) = 1 to double precision; for large mu use the series
 * coth(x) - 1/x = x/3 - x^3/45 + 2x^5/945 with x = 1/mu. */
double ss_gauss_g_from_mu(double mu) {
  if (mu > 10.0) {
    double x = 1.0 / mu, x2 = x * x;
    return x / 3.0 - x * x2 / 45.0 + 2.0 * x * x2 * x2 / 945.0;
  }
  if (mu < 0.01) {
    return 1.0 - mu;
  }
  return 1.0 / tanh(1.0 / mu) - mu;
}

/* g(mu) decreases monotonically from 1 (mu -> 0) to 0 (mu -> inf): bisect
 * in log(mu). */
double ss_gauss_mu_from_g(double g) {
  double lo = log(1e-12), hi = log(1e12);
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    if (ss_gauss_g_from_mu(exp(mid)) > g) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return exp(0.5 * (lo + hi));
}

ss_status ss_phase_init(ss_phase *p, ss_phase_type type, double g, ss_error *err) {
  memset(p, 0, sizeof *p);
  p->type = type;
  if (!isfinite(g) || g <= -1.0 || g >= 1.0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "g must satisfy -1 < g < 1 (got %g)", g);
  }
  switch (type) {
  case SS_PHASE_ISOTROPIC:
    if (g != 0.0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "the isotropic phase function has g = 0 (got %g)", g);
    }
    break;
  case SS_PHASE_HG:
    break;
  case SS_PHASE_GAUSS:
    /* g = 0 is the isotropic limit mu -> inf: the bisection stops at
     * mu = 1e12, where the lobe is flat to 1e-12. */
    if (!(g >= 0.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "the Gaussian phase function needs 0 <= g < 1 (got %g)", g);
    }
    p->mu = ss_gauss_mu_from_g(g);
    p->one_minus_e = -expm1(-2.0 / p->mu);
    /* Frederickx & Dutre 2017, eq. 5: N = 1 / (2 pi mu (1 - exp(-2/mu))). */
    p->norm = 1.0 / (2.0 * SS_PI * p->mu * p->one_minus_e);
    break;
  default:
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "unknown phase function type %d", type);
  }
  p->g = g;
  return SS_OK;
}

double ss_phase_eval(const ss_phase *p, double cos_theta) {
  switch (p->type) {
  case SS_PHASE_HG: {
    /* Henyey & Greenstein 1941. */
    double g = p->g, denom = 1.0 + g * g - 2.0 * g * cos_theta;
    return SS_INV_4PI * (1.0 - g * g) / (denom * sqrt(denom));
  }
  case SS_PHASE_GAUSS:
    /* Frederickx & Dutre 2017, eq. 5. */
    return p->norm * exp(-(1.0 - cos_theta) / p->mu);
  case SS_PHASE_ISOTROPIC:
  default:
    return SS_INV_4PI;
  }
}

ss_vec3 ss_phase_sample(const ss_phase *p, ss_vec3 dir, double u1, double u2) {
  double cos_theta = ss_phase_sample_cos(p, u1);
  ss_vec3 local = ss_spherical_direction(cos_theta, 2.0 * SS_PI * u2);
  return ss_frame_to_world(ss_frame_from_normal(dir), local);
}

int ss_phase_type_from_name(const char *name, ss_phase_type *type) {
  if (!strcmp(name, "iso") || !strcmp(name, "isotropic")) {
    *type = SS_PHASE_ISOTROPIC;
  } else if (!strcmp(name, "hg")) {
    *type = SS_PHASE_HG;
  } else if (!strcmp(name, "gauss") || !strcmp(name, "gaussian")) {
    *type = SS_PHASE_GAUSS;
  } else {
    return 0;
  }
  return 1;
}

const char *ss_phase_type_name(ss_phase_type type) {
  switch (type) {
  case SS_PHASE_HG:
    return "hg";
  case SS_PHASE_GAUSS:
    return "gauss";
  case SS_PHASE_ISOTROPIC:
  default:
    return "iso";
  }
}
