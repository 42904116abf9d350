/* Fresnel reflectance of an absorbing medium: the Fresnel equations with a
 * complex index of refraction. */
#include "subsurf/fresnel.h"

#include <complex.h>
#include <math.h>

double ss_fresnel_conductor(double cos_theta_i, double eta, double k) {
  double c = fmin(fabs(cos_theta_i), 1.0), sin2_i = 1.0 - c * c;
  double complex n = eta + k * I;
  /* BornWolf1999 sec. 14.2: Snell's law with the complex index, cos(theta_t)
   * on the principal branch (Re >= 0: the wave decays into the metal). */
  double complex cos_t = csqrt(1.0 - sin2_i / (n * n));
  /* BornWolf1999 sec. 1.5.2, the Fresnel formulae: amplitude ratios of the
   * two polarisations; unpolarised light averages their intensities. */
  double complex r_parallel = (n * c - cos_t) / (n * c + cos_t);
  double complex r_perpendicular = (c - n * cos_t) / (c + n * cos_t);
  double r =
      0.5 * (creal(r_parallel * conj(r_parallel)) + creal(r_perpendicular * conj(r_perpendicular)));
  return fmin(r, 1.0);
}
