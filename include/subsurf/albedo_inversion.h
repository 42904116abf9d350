/* Translucent materials given as users give them: a surface
 * colour `albedo` and a distance `mfp` per channel, converted to the
 * coefficients every integrator and model takes (docs/albedo.md).
 *
 * - albedo: in (0, 1), the diffuse reflectance at normal incidence per unit
 *   incident power, specular reflection excluded (equivalently the radiance
 *   of a thick slab's face seen head-on under a uniform environment of
 *   radiance 1, specular excluded). At most 1 - F(0) behind a boundary eta.
 * - mfp: the mean free path 1/sigma_t in scene units (not a diffusion
 *   "radius"): sigma_t = 1/mfp, sigma_s = alpha sigma_t,
 *   sigma_a = (1 - alpha) sigma_t for the single-scattering albedo alpha
 *   the inversion finds. Every inversion keeps mfp exactly.
 *
 * Inversions (the reduced albedo alpha' from which alpha = alpha' /
 * (1 - g + g alpha') follows):
 *   exact   the half-space Monte Carlo table (albedo_table.h): volpath and
 *           the exact transport reproduce `albedo` (the default);
 *   dipole  Jensen's closed-form R_d(alpha', eta) = albedo (Jensen & Buhler
 *           2002; per unit power entering, no Fresnel transmission);
 *   pbd     PBD's effective albedo rho_eff(alpha', eta, g) = albedo (pbrt-v3's
 *           SubsurfaceFromDiffuse);
 *   burley  ChristensenBurley2015's closed-form fit for random walks,
 *           index matched: u = sqrt(1 - alpha') =
 *           4.09712 + 4.20863 C - sqrt(9.59217 + 41.6808 C + 17.7126 C^2).
 * This is the per-point conversion: a textured material calls it at each
 * shading point (bench/RESULTS.md, loaded machine: exact 0.3 us, burley
 * 16 ns, dipole 0.5 us; pbd about 40 ms, regula falsi on rho_eff, too slow
 * per point).
 */
#ifndef SUBSURF_ALBEDO_INVERSION_H
#define SUBSURF_ALBEDO_INVERSION_H

#include "subsurf/status.h"

typedef enum {
  SS_ALBEDO_INVERSION_EXACT,
  SS_ALBEDO_INVERSION_DIPOLE,
  SS_ALBEDO_INVERSION_PBD,
  SS_ALBEDO_INVERSION_BURLEY,
} ss_albedo_inversion;

#define SS_ALBEDO_INVERSION_NAMES "exact, dipole, pbd, burley"

/* 1 and *out set for a known name, else 0. */
int ss_albedo_inversion_from_name(const char *name, ss_albedo_inversion *out);
const char *ss_albedo_inversion_name(ss_albedo_inversion m);

/* The reduced albedo alpha' in [0, 1] of one channel for `albedo`, by
 * method m. Fails (the message names the value and its range) for an albedo
 * outside (0, 1) or above 1 - F(0) (exact only), a g or eta outside the
 * exact table's range (exact only), |g| >= 1 or eta <= 0. */
ss_status ss_albedo_invert(ss_albedo_inversion m, double albedo, double g, double eta,
                           double *alpha_reduced, ss_error *err);

/* One channel's coefficients: (albedo, mfp, g, eta) -> (sigma_s, sigma_a);
 * also fails for mfp not finite and > 0. */
ss_status ss_albedo_to_coefficients(ss_albedo_inversion m, double albedo, double mfp, double g,
                                    double eta, double *sigma_s, double *sigma_a, ss_error *err);

/* The other way (for the burley model and tests): the exact albedo of a
 * medium of single-scattering albedo alpha (sigma_s / sigma_t), HG g, behind
 * eta; fails outside the table's range. */
ss_status ss_albedo_exact(double alpha, double g, double eta, double *albedo, ss_error *err);

#endif
