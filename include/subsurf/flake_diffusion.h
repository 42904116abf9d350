/* Anisotropic diffusion by micro-flakes (Jakob2010 sec. 5.3): the
 * coefficients of the
 * anisotropic diffusion equation (eq. 35)
 *   div(M^-1 (grad phi - 3 Q1)) = mu0[sigma_a] phi / (4 pi) - Q0
 * for a medium of flakes of density a rho. The first moments V vanish for
 * flakes (section 5.3), so M and mu0 are all the equation needs.
 *
 * Conventions: `density` is a rho (ss_microflake's per-unit-density tables
 * times it give sigma_t(w)); a medium described as in microflake.h
 * (ss_medium_flakes next to sigma_s, sigma_a) has a rho = 2 (sigma_s +
 * sigma_a) (ss_flake_medium_density). Uniform flakes then give
 * M = 3 sigma_t' I and mu0 / (4 pi) = sigma_a: the isotropic diffusion
 * equation with D = 1 / (3 sigma_t'). */
#ifndef SUBSURF_FLAKE_DIFFUSION_H
#define SUBSURF_FLAKE_DIFFUSION_H

#include "subsurf/mat3.h"
#include "subsurf/microflake.h"

/* The second moment mu2[D] = int m m^T D(m) dm of the flake distribution
 * (eq. 16), by Gauss-Legendre quadrature over the sphere (segmented in the
 * polar angle about the axis where D peaks or has a kink, trapezoidal in the
 * azimuth, which is exact for the quadratic m m^T). Symmetric, trace 1. */
ss_mat3 ss_flake_second_moment(const ss_microflake *mf);

/* The albedo constants of eq. 29, 32 and 33: alpha_hat = int_0^pi
 * alpha(|cos|) |cos| sin, c1 = int_0^pi alpha |cos| sin^3, c2 = 2 int_0^pi
 * alpha |cos|^3 sin; alpha, alpha / 2 and alpha for a constant albedo, in
 * closed form for microflake.h's alpha(c) = alpha0 + (alpha1 - alpha0) c^k. */
typedef struct {
  double alpha_hat, c1, c2;
} ss_flake_albedo_moments;
ss_flake_albedo_moments ss_flake_albedo_constants(const ss_microflake *mf);

/* The diffusion matrix (eq. 31)
 *   M = (9 a rho / 8) ((1 + 2 c1 + 2 c2) mu2[D] + (1 - 2 c1) I),
 * for a constant albedo alpha (eq. 34)
 *   M = (9 a rho / 8) ((1 + 3 alpha) mu2[D] + (1 - alpha) I).
 * Symmetric positive definite for density > 0 (section 5.3). */
ss_mat3 ss_flake_diffusion_matrix(const ss_microflake *mf, double density);

/* The absorption term mu0[sigma_a] = 2 a rho pi (1 - alpha_hat) (eq. 28). */
double ss_flake_diffusion_mu0(const ss_microflake *mf, double density);

/* The first scattering events of light entering along the unit w, reduced
 * by the similarity relation as the isotropic diffusion source's sigma_t'
 * and alpha' are: with g = ss_microflake_scattered_mean_lookup(w) (the table
 * when built, as the fem integrator does) and the
 * collision albedo alpha(w), the light scattered on along w counts as not
 * yet scattered, so sigma_s' = sigma_s(w) (1 - w.g), the extinction
 *   sigma' = sigma_t(w) (1 - alpha(w) w.g)
 * and the albedo alpha' = alpha(w) (1 - w.g) / (1 - alpha(w) w.g) (eq. 11
 * with a rho = density; the similarity relation of Wyman1989). */
typedef struct {
  double sigma, albedo;
} ss_flake_first_event;
ss_flake_first_event ss_flake_reduced_first_event(const ss_microflake *mf, double density,
                                                  ss_vec3 w);

/* a rho of a medium given as sigma_s, sigma_a with flakes (microflake.h's
 * convention): 2 (sigma_s + sigma_a). */
double ss_flake_medium_density(double sigma_s, double sigma_a);

#endif
