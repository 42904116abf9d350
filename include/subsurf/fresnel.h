/* Dielectric Fresnel reflectance and its diffuse moments.
 *
 * Conventions: the normal points to the outside; eta = n_inside / n_outside.
 * cos_theta_i = dot(w_i, n) where w_i points back toward where the light
 * comes from: positive for light arriving from the outside, negative for light
 * arriving from the inside (where total internal reflection occurs if eta > 1). */
#ifndef SUBSURF_FRESNEL_H
#define SUBSURF_FRESNEL_H

#include "subsurf/vec3.h"

/* Unpolarised reflectance Fr, 1 under total internal reflection. */
double ss_fresnel_dielectric(double cos_theta_i, double eta);

/* Unpolarised reflectance of a conductor (or absorbing dielectric) of
 * complex index eta + i k relative to the outside, for light arriving from
 * the outside at cosine cos_theta_i (its absolute value is used): the
 * exact Fresnel equations with a complex index. k = 0 gives
 * ss_fresnel_dielectric; eta > 0, k >= 0. */
double ss_fresnel_conductor(double cos_theta_i, double eta, double k);

/* Refracts w_i (pointing away from the surface, on either side) through the
 * boundary with normal n (outward) and ratio eta. Returns 0 under total
 * internal reflection. *w_t points away from the surface on the other side. */
int ss_refract(ss_vec3 w_i, ss_vec3 n, double eta, ss_vec3 *w_t);

/* Mirror reflection of w_i about n. */
static inline ss_vec3 ss_reflect(ss_vec3 w_i, ss_vec3 n) {
  return ss_vec3_sub(ss_vec3_scale(n, 2.0 * ss_vec3_dot(w_i, n)), w_i);
}

/* Diffuse Fresnel reflectance of light inside the medium (Egan & Hilgeman
 * 1979 fit as quoted by Jensen et al. 2001, eq. 5 context). */
double ss_fresnel_diffuse_reflectance(double eta);
/* Jensen et al. 2001's rounding of the same fit for eta > 1. */
double ss_fresnel_diffuse_reflectance_jensen(double eta);
/* A = (1 + Fdr) / (1 - Fdr), the boundary mismatch term of the dipole. */
double ss_fresnel_A(double eta);

/* Fresnel moments C_n(eta) = int_0^1 Fr(-mu, eta) mu^n dmu: the angular
 * moments of the reflectance for light hitting the boundary from inside.
 * Computed by adaptive quadrature (n >= 0). */
double ss_fresnel_moment(int n, double eta);
/* The 5th-order polynomial fits of d'Eon & Irving 2011 for C1 and C2. */
double ss_fresnel_moment1_fit(double eta);
double ss_fresnel_moment2_fit(double eta);
/* C_phi = (1 - 2 C1)/4 and C_E = (1 - 3 C2)/2 (d'Eon & Irving 2011, eq. 16). */
double ss_fresnel_c_phi(double eta);
double ss_fresnel_c_e(double eta);

#endif
