/* The forward scattering propagator (Frederickx2017
 * eq. 9-18). See fwddip_propagator.h for the conventions. */
#include "bssrdf/fwddip_propagator.h"

#include "subsurf/sampling.h"

#include <math.h>

/* Below this ps, ps - tanh(ps) is taken from its series. */
#define PS_SERIES 0.25
/* Above this Z, Z/(e^Z - 1) = Z e^{-Z} to double precision. */
#define Z_LARGE 50.0

/* (x - tanh x)/x^3 = sum_k c_k x^{2k} (tanh's Taylor coefficients, from the
 * Bernoulli numbers); ten terms reach double precision for x <= 1/4. */
static double x_minus_tanh_over_x3(double x) {
  static const double c[] = {1.0 / 3.0,
                             -2.0 / 15.0,
                             17.0 / 315.0,
                             -62.0 / 2835.0,
                             1382.0 / 155925.0,
                             -21844.0 / 6081075.0,
                             929569.0 / 638512875.0,
                             -6404582.0 / 10854718875.0,
                             443861162.0 / 1856156927625.0,
                             -18888466084.0 / 194896477400625.0};
  double x2 = x * x, sum = 0.0;
  for (int i = (int)(sizeof c / sizeof c[0]) - 1; i >= 0; --i) {
    sum = sum * x2 + c[i];
  }
  return sum;
}

/* log(Z/(e^Z - 1)), finite for every Z >= 0. */
static double log_z_over_expm1(double z) {
  if (z < 1e-12) {
    return -0.5 * z;
  }
  if (z > Z_LARGE) {
    return log(z) - z;
  }
  return log(z / expm1(z));
}

ss_fwddip_medium ss_fwddip_medium_make(double sigma_s_prime, double sigma_a) {
  ss_fwddip_medium m;
  m.p = 0.5 * sigma_s_prime;
  m.sigma_a = sigma_a;
  m.log_p3 = 3.0 * log(m.p);
  return m;
}

void ss_fwddip_coeffs_make(double ps, ss_fwddip_coeffs *k) {
  /* t = e^{-2ps}; below PS_SERIES 1 - t comes from expm1 (no cancellation),
   * above it t itself (full relative precision however small t is). */
  double t, one_minus_t;
  if (ps < PS_SERIES) {
    one_minus_t = -expm1(-2.0 * ps);
    t = 1.0 - one_minus_t;
  } else {
    t = exp(-2.0 * ps);
    one_minus_t = 1.0 - t;
  }
  double one_plus_t = 1.0 + t, tanh_ps = one_minus_t / one_plus_t;
  double ps_minus_tanh = ps < PS_SERIES ? ps * ps * ps * x_minus_tanh_over_x3(ps) : ps - tanh_ps;
  k->ps = ps;
  /* Frederickx & Dutré 2017, eq. 9: A, B, E, F. */
  k->A = 1.0 / ps_minus_tanh;
  k->B = 0.5 * tanh_ps;
  k->E = 3.0 * k->A * k->B;
  k->F = 1.5 * k->A;
  /* Z = E^2/F - 2D = 3/sinh(2ps) = 6t/(1 - t^2) (docs/fwddip.md); then eq. 9's
   * D = 3AB^2 - 3/(2 sinh 2ps) = 3AB^2 - Z/2, free of overflow. */
  k->Z = 6.0 * t / (one_minus_t * one_plus_t);
  k->D = 3.0 * k->A * k->B * k->B - 0.5 * k->Z;
  /* docs/fwddip.md: N e^{-C} = p^3 F^{3/2} Z e^{-D} / (4 pi^{5/2} (e^Z - 1)). */
  double log_f = log(k->F);
  double common = log_z_over_expm1(k->Z) - k->D - log(4.0 * SS_PI * SS_PI * sqrt(SS_PI));
  k->log_norm = 1.5 * log_f + common;
  /* Eq. 17: pi N e^{-C} / (p^2 F) = p pi F^{1/2} Z e^{-D} / (4 pi^{5/2} (e^Z - 1)). */
  k->log_planar = 0.5 * log_f + log(SS_PI) + common;
}

/* The exponent of eq. 9 without -C (cancelled by N's e^C) and -sigma_a s. */
static double gf_exponent(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, ss_vec3 x,
                          ss_vec3 w, ss_vec3 xp, ss_vec3 wp) {
  ss_vec3 r = ss_vec3_scale(ss_vec3_sub(x, xp), m->p);
  return -k->D * ss_vec3_dot(w, wp) + k->E * ss_vec3_dot(r, ss_vec3_add(w, wp)) -
         k->F * ss_vec3_length2(r);
}

double ss_fwddip_log_gf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, ss_vec3 x,
                        ss_vec3 w, ss_vec3 xp, ss_vec3 wp) {
  /* Frederickx & Dutré 2017, eq. 9. */
  return m->log_p3 + k->log_norm + gf_exponent(m, k, x, w, xp, wp) - m->sigma_a * s;
}

double ss_fwddip_gf(const ss_fwddip_medium *m, double s, ss_vec3 x, ss_vec3 w, ss_vec3 xp,
                    ss_vec3 wp) {
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(m->p * s, &k);
  return exp(ss_fwddip_log_gf(m, &k, s, x, w, xp, wp));
}

int ss_fwddip_dipole_make(ss_vec3 x_o, ss_vec3 x_i, ss_vec3 n_i, ss_vec3 w_i, double z_v,
                          ss_fwddip_dipole *d) {
  ss_vec3 R = ss_vec3_sub(x_o, x_i);
  double r2 = ss_vec3_length2(R);
  /* Frederickx & Dutré 2017, eq. 12: n* = R^ x (n_i x R)/|n_i x R|, n_i at R = 0. */
  d->n_star = n_i;
  if (r2 > 0.0) {
    ss_vec3 nr = ss_vec3_cross(n_i, R);
    double l2 = ss_vec3_length2(nr);
    if (!(l2 > 1e-24 * r2)) {
      return 0;
    }
    d->n_star = ss_vec3_cross(ss_vec3_scale(R, 1.0 / sqrt(r2)), ss_vec3_scale(nr, 1.0 / sqrt(l2)));
  }
  double wn = ss_vec3_dot(w_i, d->n_star);
  /* Eq. 14: no transport when the source points out of the effective half-space. */
  if (wn >= 0.0) {
    return 0;
  }
  /* Eq. 13: the image source and direction. */
  d->x_v = ss_vec3_madd(x_i, d->n_star, z_v);
  d->w_v = ss_vec3_madd(w_i, d->n_star, -2.0 * wn);
  return 1;
}

double ss_fwddip_gbf_dipole(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s,
                            ss_vec3 x_o, ss_vec3 w_o, ss_vec3 x_i, ss_vec3 w_i,
                            const ss_fwddip_dipole *d) {
  /* Eq. 14: G_f(real) - G_f(virtual), one exponential of the common factor. */
  double base = m->log_p3 + k->log_norm - m->sigma_a * s;
  double real = gf_exponent(m, k, x_o, w_o, x_i, w_i);
  double virt = gf_exponent(m, k, x_o, w_o, d->x_v, d->w_v);
  return ss_fwddip_exp(base + real) - ss_fwddip_exp(base + virt);
}

double ss_fwddip_gbf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, ss_vec3 x_o,
                     ss_vec3 w_o, ss_vec3 x_i, ss_vec3 n_i, ss_vec3 w_i, double z_v) {
  ss_fwddip_dipole d;
  if (!ss_fwddip_dipole_make(x_o, x_i, n_i, w_i, z_v, &d)) {
    return 0.0;
  }
  return ss_fwddip_gbf_dipole(m, k, s, x_o, w_o, x_i, w_i, &d);
}

double ss_fwddip_gbf_reciprocal(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s,
                                ss_vec3 x_o, ss_vec3 n_o, ss_vec3 w_o, ss_vec3 x_i, ss_vec3 n_i,
                                ss_vec3 w_i, double z_v) {
  /* Frederickx & Dutré 2017, eq. 15. */
  double fwd = ss_fwddip_gbf(m, k, s, x_o, w_o, x_i, n_i, w_i, z_v);
  double rev = ss_fwddip_gbf(m, k, s, x_i, ss_vec3_neg(w_i), x_o, n_o, ss_vec3_neg(w_o), z_v);
  return 0.5 * (fwd + rev);
}

/* The exponent of eq. 17 (docs/fwddip.md's form) without -C and -sigma_a s. */
static double gpf_exponent(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double h,
                           ss_vec3 w, ss_vec3 wp, ss_vec3 n) {
  double ph = m->p * h, wwp = ss_vec3_dot(w, wp);
  double wn = ss_vec3_dot(w, n) + ss_vec3_dot(wp, n);
  return -k->D * wwp + k->E * ph * wn - k->F * ph * ph +
         k->E * k->E / (4.0 * k->F) * (2.0 + 2.0 * wwp - wn * wn);
}

double ss_fwddip_gpf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, double h,
                     ss_vec3 w, ss_vec3 wp, ss_vec3 n) {
  /* Frederickx & Dutré 2017, eq. 17. */
  return exp(log(m->p) + k->log_planar + gpf_exponent(m, k, h, w, wp, n) - m->sigma_a * s);
}

double ss_fwddip_gpbf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, ss_vec3 w_o,
                      ss_vec3 w_i, ss_vec3 n, double z_v) {
  double wn = ss_vec3_dot(w_i, n);
  if (wn >= 0.0) {
    return 0.0;
  }
  /* Eq. 18 with eq. 13's image plane 2 A d_e outside (docs/fwddip.md). */
  ss_vec3 w_v = ss_vec3_madd(w_i, n, -2.0 * wn);
  double base = log(m->p) + k->log_planar - m->sigma_a * s;
  return exp(base + gpf_exponent(m, k, 0.0, w_o, w_i, n)) -
         exp(base + gpf_exponent(m, k, -z_v, w_o, w_v, n));
}
