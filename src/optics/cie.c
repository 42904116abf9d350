/* CIE 1931 colour matching functions (Wyman2013) and linear sRGB. */
#include "subsurf/cie.h"

#include <math.h>

/* Wyman2013's piecewise Gaussian: different widths left and right of mu. */
static double lobe(double x, double mu, double sigma_left, double sigma_right) {
  double t = (x - mu) / (x < mu ? sigma_left : sigma_right);
  return exp(-0.5 * t * t);
}

ss_vec3 ss_cie_xyz(double l) {
  /* Wyman2013, the multi-lobe fit of the 1931 observer. */
  double x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
             0.065 * lobe(l, 501.1, 20.4, 26.2);
  double y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
  double z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
  return ss_vec3_make(x, y, z);
}

ss_vec3 ss_xyz_to_linear_srgb(ss_vec3 c) {
  /* IEC61966 (sRGB), the inverse of the primaries' matrix. */
  return ss_vec3_make(3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z,
                      -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
                      0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z);
}
