/* The exact solution of the diffusion equation in the half-space z < 0 with
 * the Robin boundary condition phi = 2 A D dphi/dz at z = 0 (Jakob2010
 * eq. 36 when isotropic) for an isotropic point source of power P at depth
 * z0: by the Hankel transform of e^{-s r}/r = int_0^inf (k/kappa)
 * e^{-kappa |z|} J0(k rho) dk, kappa = sqrt(k^2 + s^2), the image term has
 * the reflection R(k) = (2 A D kappa - 1)/(2 A D kappa + 1). Returns the
 * exitance phi/(2A) at radius rho on the surface. */
#ifndef SUBSURF_TESTS_ROBIN_HALFSPACE_H
#define SUBSURF_TESTS_ROBIN_HALFSPACE_H

#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_bessel.h>
#include <math.h>

#include "subsurf/sampling.h"

typedef struct {
  double s, z0, A, D, rho;
} robin_params;

static double robin_integrand(double k, void *p) {
  const robin_params *r = p;
  double ka = sqrt(k * k + r->s * r->s), c = 2.0 * r->A * r->D * ka;
  double R = (c - 1.0) / (c + 1.0);
  return k / ka * exp(-ka * r->z0) * (1.0 + R) * gsl_sf_bessel_J0(k * r->rho);
}

static double robin_halfspace_exitance(double P, double z0, double sigma_s_prime, double sigma_a,
                                       double A, double rho) {
  double D = 1.0 / (3.0 * (sigma_s_prime + sigma_a));
  robin_params rp = {.s = sqrt(sigma_a / D), .z0 = z0, .A = A, .D = D, .rho = rho};
  gsl_function F = {robin_integrand, &rp};
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(10000);
  double v = 0.0, e = 0.0;
  /* the integrand decays as exp(-k z0): cut where it is below 1e-16 */
  gsl_integration_qag(&F, 0.0, 37.0 / z0, 0.0, 1e-10, 10000, GSL_INTEG_GAUSS61, w, &v, &e);
  gsl_integration_workspace_free(w);
  return P / (4.0 * SS_PI * D) * v / (2.0 * A);
}

#endif
