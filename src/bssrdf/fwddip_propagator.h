/* The forward scattering propagator of Frederickx2017,
 * private to src/bssrdf: the infinite-medium G_f (eq. 9), the
 * bounded dipole G^b_f (eq. 12-14) and its reciprocal form (eq. 15), and the
 * planar-source propagators G^p_f and G^pb_f (eq. 17-18).
 *
 * Conventions (docs/fwddip.md): in G_f(s, x, w, x', w') both w and w' are
 * propagation directions, w at the receiver x and w' at the source x'; s is
 * the path length. p = sigma_s'/2 and r = p (x - x'). The coefficients
 * A..F and the normalisation depend only on ps and are evaluated stably for
 * every ps > 0: series below ps = 1/4, closed forms in t = e^{-2ps} above
 * (without overflow for any ps), and the normalisation N e^{-C} taken in
 * logarithms together with the exponent, so that neither e^{C} nor
 * e^{E^2/F - D} is ever formed. */
#ifndef SUBSURF_BSSRDF_FWDDIP_PROPAGATOR_H
#define SUBSURF_BSSRDF_FWDDIP_PROPAGATOR_H

#include "subsurf/vec3.h"

#include <math.h>

/* exp(x), with the zero that exp rounds to below -746 (e^-745.14 is half the
 * least subnormal) returned without calling it: glibc's exp takes a slow
 * error path (errno ERANGE) on underflow, and the exitance integrals spend
 * most of their exponentials far out in the Gaussian tails of eq. 9. */
static inline double ss_fwddip_exp(double x) { return x < -746.0 ? 0.0 : exp(x); }

/* The dimensionless coefficients of eq. 9 at one value of ps. */
typedef struct {
  double ps;
  double A, B, D, E, F;
  double Z;          /* E^2/F - 2D = 6t/(1 - t^2) = 3/sinh(2ps) */
  double log_norm;   /* log(N e^{-C} / p^3) */
  double log_planar; /* log(pi N e^{-C} / (p^3 F)): G^p_f's prefactor over p */
} ss_fwddip_coeffs;

/* A medium as the propagator sees it: p = sigma_s'/2 > 0 and sigma_a >= 0. */
typedef struct {
  double p, sigma_a;
  double log_p3; /* 3 log p */
} ss_fwddip_medium;

ss_fwddip_medium ss_fwddip_medium_make(double sigma_s_prime, double sigma_a);

/* The coefficients at ps > 0 (ps = 0 and ps = inf are limits nothing samples). */
void ss_fwddip_coeffs_make(double ps, ss_fwddip_coeffs *k);

/* log G_f (eq. 9) with coefficients k made at p s: -inf where G_f underflows. */
double ss_fwddip_log_gf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, ss_vec3 x,
                        ss_vec3 w, ss_vec3 xp, ss_vec3 wp);
/* G_f(s, x, w, x', w') of eq. 9, per unit volume, solid angle and path length. */
double ss_fwddip_gf(const ss_fwddip_medium *m, double s, ss_vec3 x, ss_vec3 w, ss_vec3 xp,
                    ss_vec3 wp);

/* The dipole set-up of eq. 12-13 for a source at x_i with normal n_i. */
typedef struct {
  ss_vec3 n_star; /* the modified normal n*_i of eq. 12 */
  ss_vec3 x_v;    /* virtual source x_i + z_v n*_i (z_v = 2 A d_e) */
  ss_vec3 w_v;    /* mirrored source direction */
} ss_fwddip_dipole;

/* Fills the dipole; returns 0 when G^b_f vanishes: n_i parallel to
 * x_o - x_i (n* undefined) or w_i pointing out of the effective half-space
 * (w_i . n* >= 0). w_i is the propagation direction into the medium. */
int ss_fwddip_dipole_make(ss_vec3 x_o, ss_vec3 x_i, ss_vec3 n_i, ss_vec3 w_i, double z_v,
                          ss_fwddip_dipole *d);

/* G^b_f(s, x_o, w_o, x_i, w_i) of eq. 14 (real minus virtual source), with
 * w_o the propagation direction at x_o. May be negative where the virtual
 * source dominates; callers integrating over s clamp the integral. */
double ss_fwddip_gbf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, ss_vec3 x_o,
                     ss_vec3 w_o, ss_vec3 x_i, ss_vec3 n_i, ss_vec3 w_i, double z_v);
/* The same with the dipole that ss_fwddip_dipole_make made for (x_o, x_i,
 * n_i, w_i) (it returned 1): what an integral over s computes once. */
double ss_fwddip_gbf_dipole(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s,
                            ss_vec3 x_o, ss_vec3 w_o, ss_vec3 x_i, ss_vec3 w_i,
                            const ss_fwddip_dipole *d);
/* The reciprocal combination of eq. 15:
 * [G^b_f(s, x_o, w_o, x_i, w_i) + G^b_f(s, x_i, -w_i, x_o, -w_o)] / 2, the
 * second term with the dipole built at x_o (normal n_o). */
double ss_fwddip_gbf_reciprocal(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s,
                                ss_vec3 x_o, ss_vec3 n_o, ss_vec3 w_o, ss_vec3 x_i, ss_vec3 n_i,
                                ss_vec3 w_i, double z_v);

/* G^p_f of eq. 17 (docs/fwddip.md's form): G_f integrated over a source plane with
 * normal n whose offset from the receiver along n is h = (x - x') . n. */
double ss_fwddip_gpf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, double h,
                     ss_vec3 w, ss_vec3 wp, ss_vec3 n);
/* G^pb_f of eq. 18 (docs/fwddip.md's conventions): the surface plane (h = 0, source
 * direction w_i into the medium, w_i . n < 0) minus its image 2 A d_e
 * outside (h = -z_v, mirrored w_v); 0 when w_i . n >= 0. */
double ss_fwddip_gpbf(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, double s, ss_vec3 w_o,
                      ss_vec3 w_i, ss_vec3 n, double z_v);

#endif
