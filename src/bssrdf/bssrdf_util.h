/* Helpers shared by the BSSRDF models (private to src/bssrdf): fixed
 * Gauss-Legendre panels, Fresnel transmission factors, the dipole source
 * terms and a radial sampler made of a mixture of area exponentials. */
#ifndef SUBSURF_BSSRDF_UTIL_H
#define SUBSURF_BSSRDF_UTIL_H

#include "subsurf/bssrdf.h"
#include "subsurf/fresnel.h"
#include "subsurf/quadrature.h" /* ss_gl_integrate; handle.h has the three-channel rules */
#include "subsurf/sampling.h"

#include <math.h>

/* 1 for a radius the wrappers answer 0 without asking the model: NaN, or
 * not below SS_BSSRDF_TAIL_RADIUS. */
static inline int ss_bssrdf_in_tail(double r) { return !(fabs(r) < SS_BSSRDF_TAIL_RADIUS); }

/* out = 0 and acc += v on per-channel values. */
static inline void ss_channels_zero(double out[SS_BSSRDF_CHANNELS]) {
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = 0.0;
  }
}
static inline void ss_channels_add(double acc[SS_BSSRDF_CHANNELS],
                                   const double v[SS_BSSRDF_CHANNELS]) {
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    acc[c] += v[c];
  }
}

/* Fresnel transmittance for light arriving from the outside at cos > 0
 * (0 for cos <= 0). */
static inline double ss_ft_outside(double cos_theta, double eta) {
  return cos_theta > 0.0 ? 1.0 - ss_fresnel_dielectric(cos_theta, eta) : 0.0;
}
/* Fresnel transmittance for light leaving the medium, cos > 0 measured
 * against the inward normal (1 - Fr with total internal reflection). */
static inline double ss_ft_inside(double cos_theta, double eta) {
  return cos_theta > 0.0 ? 1.0 - ss_fresnel_dielectric(-cos_theta, eta) : 0.0;
}
/* (1/pi) int Ft(eta, w) cos(theta) dw over the outside hemisphere:
 * 1 - 2 C1(1/eta), the fraction of a Lambertian exit distribution that
 * a Ft(w_o)/pi lobe carries (the normalisation C_n of Frisvad et al. 2014). */
double ss_fresnel_transmission_out(double eta);

/* One dipole source at signed height z below the surface (d = sqrt(r^2+z^2)):
 * z (1 + sigma d) e^{-sigma d} / d^3, the flux term of Jensen et al. 2001,
 * eq. 4 and Donner & Jensen 2005, eq. 12-13. */
static inline double ss_dipole_source(double z, double r2, double sigma_tr) {
  double d = sqrt(r2 + z * z);
  if (z == 0.0) {
    return 0.0; /* a source on the face: no flux through it except at r = 0 */
  }
  return z * (1.0 + sigma_tr * d) * exp(-sigma_tr * d) / (d * d * d);
}
/* Its integral over the whole plane, 2 pi int r (...) dr = 2 pi sgn(z) e^{-sigma |z|}. */
static inline double ss_dipole_source_total(double z, double sigma_tr) {
  return 2.0 * SS_PI * copysign(exp(-sigma_tr * fabs(z)), z);
}

/* Area density p(r) = sum_k w_k sigma_k^2 e^{-sigma_k r} / (2 pi): each
 * component's radius is Gamma(2, sigma_k), so the density per unit area is
 * finite at r = 0 like the profiles it stands for. */
#define SS_RADIAL_MIX_MAX 3
typedef struct {
  int n;
  double sigma[SS_RADIAL_MIX_MAX];
  double weight[SS_RADIAL_MIX_MAX]; /* sum to 1 */
} ss_radial_mix;

/* Builds a mixture from rates (non-positive or non-finite ones skipped) and
 * weights (renormalised). */
void ss_radial_mix_init(ss_radial_mix *m, int n, const double *sigma, const double *weight);
/* The diffusion models' mixture: 3/4 at the profile's tail rate sigma_tr (at
 * least 1e-3 sigma_t', so that a medium without absorption keeps a finite
 * radius) and 1/4 at its core rate sigma_t'. */
void ss_radial_mix_init_diffusion(ss_radial_mix *m, double sigma_tr, double sigma_t_prime);
/* The inverse of the Gamma(2) cdf 1 - (1 + x) e^{-x} at u in [0, 1) (by Halley
 * steps: thread-safe, no library error state). */
double ss_gamma2_inverse(double u);
/* u1 picks the component and then the radius (rescaled), u2 the azimuth. */
void ss_radial_mix_sample(const ss_radial_mix *m, double u1, double u2, ss_bssrdf_entry *e);
double ss_radial_mix_pdf(const ss_radial_mix *m, double r);
/* Radius below which the mixture puts 1 - 1e-4 of its mass. */
double ss_radial_mix_max_radius(const ss_radial_mix *m);

/* Standard parameter checks for a params struct (all channels). */
ss_status ss_bssrdf_params_check(const ss_bssrdf_params *p, const char *model, ss_error *err);
/* The same without refusing micro-flake media (models flagged
 * SS_BSSRDF_FLAKES). */
ss_status ss_bssrdf_params_check_medium(const ss_bssrdf_params *p, const char *model,
                                        ss_error *err);

#endif
