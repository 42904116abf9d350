/* Surface colour + mean free path -> coefficients (albedo_inversion.h). */
#include "subsurf/albedo_inversion.h"

#include "subsurf/albedo_table.h"
#include "subsurf/fresnel.h"
#include "subsurf/pbd.h"

#include <math.h>
#include <string.h>

static const char *const names[] = {"exact", "dipole", "pbd", "burley"};

int ss_albedo_inversion_from_name(const char *name, ss_albedo_inversion *out) {
  for (int i = 0; i < (int)(sizeof names / sizeof names[0]); ++i) {
    if (!strcmp(name, names[i])) {
      *out = (ss_albedo_inversion)i;
      return 1;
    }
  }
  return 0;
}

const char *ss_albedo_inversion_name(ss_albedo_inversion m) { return names[m]; }

/* The single-scattering albedo of reduced albedo alpha' for mean cosine g
 * (inverse of alpha' = (1 - g) alpha / (1 - g alpha), the similarity
 * relation). */
static double unreduce(double alpha_reduced, double g) {
  return alpha_reduced / (1.0 - g + g * alpha_reduced);
}

/* The shipped half-space albedo table, when it covers g and eta. */
static ss_status exact_table(double g, double eta, const ss_albedo_table **t, ss_error *err) {
  ss_status st = ss_albedo_table_builtin(t, err);
  return st == SS_OK ? ss_albedo_table_check(*t, g, eta, err) : st;
}

/* Jensen et al. 2001, sec. 2.4: R_d = alpha'/2 (1 + e^{-4/3 A s}) e^{-s},
 * s = sqrt(3 (1 - alpha')). */
static double dipole_rd(double alpha_reduced, double A) {
  double s = sqrt(3.0 * (1.0 - alpha_reduced));
  return 0.5 * alpha_reduced * (1.0 + exp(-4.0 / 3.0 * A * s)) * exp(-s);
}

typedef struct {
  double A;   /* dipole */
  ss_pbd pbd; /* pbd */
  double g;
} forward_ctx;

static double forward(ss_albedo_inversion m, forward_ctx *c, double alpha_reduced) {
  if (m == SS_ALBEDO_INVERSION_DIPOLE) {
    return dipole_rd(alpha_reduced, c->A);
  }
  double alpha = unreduce(alpha_reduced, c->g);
  ss_pbd_set_albedo(&c->pbd, alpha, 1.0 - alpha);
  return ss_pbd_effective_albedo(&c->pbd);
}

/* Both models' albedos increase with alpha' and are smooth in u = sqrt(1 -
 * alpha') up to alpha' = 1: the root of f(u) = forward(1 - u^2) - albedo, which
 * decreases from f(0) to f(1) = -albedo, by regula falsi with the Illinois
 * modification (superlinear; about ten evaluations of pbd's rho_eff). An
 * albedo above forward(1) gives alpha' = 1. */
static double solve(ss_albedo_inversion m, forward_ctx *c, double albedo) {
  double lo = 0.0, hi = 1.0, f_lo = forward(m, c, 1.0) - albedo, f_hi = -albedo;
  if (!(f_lo > 0.0)) {
    return 1.0;
  }
  int side = 0;
  for (int i = 0; i < 100 && hi - lo > 1e-13; ++i) {
    double u = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(u > lo && u < hi)) {
      u = 0.5 * (lo + hi);
    }
    double f = forward(m, c, 1.0 - u * u) - albedo;
    if (f == 0.0) {
      return 1.0 - u * u;
    }
    if (f > 0.0) {
      lo = u, f_lo = f;
      f_hi *= side == 1 ? 0.5 : 1.0;
      side = 1;
    } else {
      hi = u, f_hi = f;
      f_lo *= side == -1 ? 0.5 : 1.0;
      side = -1;
    }
    if (fabs(f) < 1e-14) {
      break;
    }
  }
  double u = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
  return 1.0 - u * u;
}

ss_status ss_albedo_invert(ss_albedo_inversion m, double albedo, double g, double eta,
                           double *alpha_reduced, ss_error *err) {
  if (!(albedo > 0.0 && albedo < 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "albedo must lie in (0, 1), got %g", albedo);
  }
  if (!(fabs(g) < 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "g must lie in (-1, 1), got %g", g);
  }
  if (!(eta > 0.0 && isfinite(eta))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "eta must be finite and > 0, got %g", eta);
  }
  switch (m) {
  case SS_ALBEDO_INVERSION_EXACT: {
    const ss_albedo_table *t;
    ss_status st = exact_table(g, eta, &t, err);
    if (st != SS_OK) {
      return st;
    }
    double top = ss_albedo_max(eta);
    if (!(albedo < top)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "albedo %g is above %.6g, the most a boundary of eta %g lets through "
                          "(1 - F(0), a medium without absorption)",
                          albedo, top, eta);
    }
    *alpha_reduced = ss_albedo_table_invert(t, albedo, g, eta);
    return SS_OK;
  }
  case SS_ALBEDO_INVERSION_BURLEY: {
    /* ChristensenBurley2015 sec. 6: s = sqrt(1 - alpha'). */
    double C = albedo;
    double s = 4.09712 + 4.20863 * C - sqrt(9.59217 + 41.6808 * C + 17.7126 * C * C);
    *alpha_reduced = 1.0 - s * s;
    return SS_OK;
  }
  case SS_ALBEDO_INVERSION_DIPOLE: {
    forward_ctx c = {.A = ss_fresnel_A(eta), .g = g};
    *alpha_reduced = solve(m, &c, albedo);
    return SS_OK;
  }
  case SS_ALBEDO_INVERSION_PBD: {
    forward_ctx c = {.g = g};
    ss_status st = ss_pbd_init(&c.pbd, 0.5, 0.5, g, eta, 34, err);
    if (st != SS_OK) {
      return st;
    }
    *alpha_reduced = solve(m, &c, albedo);
    return SS_OK;
  }
  }
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "unknown albedo inversion %d", (int)m);
}

ss_status ss_albedo_to_coefficients(ss_albedo_inversion m, double albedo, double mfp, double g,
                                    double eta, double *sigma_s, double *sigma_a, ss_error *err) {
  if (!(mfp > 0.0 && isfinite(mfp))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "mfp must be finite and > 0, got %g", mfp);
  }
  double ar;
  ss_status st = ss_albedo_invert(m, albedo, g, eta, &ar, err);
  if (st != SS_OK) {
    return st;
  }
  double alpha = unreduce(ar, g), sigma_t = 1.0 / mfp;
  *sigma_s = alpha * sigma_t;
  *sigma_a = (1.0 - alpha) * sigma_t;
  return SS_OK;
}

ss_status ss_albedo_exact(double alpha, double g, double eta, double *albedo, ss_error *err) {
  const ss_albedo_table *t;
  ss_status st = exact_table(g, eta, &t, err);
  if (st != SS_OK) {
    return st;
  }
  /* alpha' = (1 - g) alpha / (1 - g alpha) (similarity relation). */
  double ar = (1.0 - g) * alpha / (1.0 - g * alpha);
  *albedo = ss_albedo_table_albedo(t, ar, g, eta, NULL);
  return SS_OK;
}
