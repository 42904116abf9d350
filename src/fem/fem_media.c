/* The per-element coefficients (M, mu0) of the diffusion equation for the
 * media the finite elements take: isotropic, and micro-flakes. */
#include "subsurf/fem.h"
#include "subsurf/flake_diffusion.h"
#include "subsurf/sampling.h"

ss_fem_coeffs ss_fem_coeffs_isotropic(double sigma_s_prime, double sigma_a) {
  /* Jakob2010 sec. 5: M^-1 = I/(3 sigma_t'); mu0[sigma_a] = 4 pi sigma_a */
  double st = sigma_s_prime + sigma_a;
  ss_fem_coeffs c = {.M = {3.0 * st, 0, 0, 0, 3.0 * st, 0, 0, 0, 3.0 * st},
                     .mu0 = 4.0 * SS_PI * sigma_a};
  return c;
}

ss_fem_coeffs ss_fem_coeffs_flakes(const ss_microflake *mf, double density) {
  /* Jakob2010 eq. 31 (34 for a constant albedo) and eq. 28 */
  ss_mat3 M = ss_flake_diffusion_matrix(mf, density);
  ss_fem_coeffs c = {.mu0 = ss_flake_diffusion_mu0(mf, density)};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      c.M[3 * i + j] = M.m[i][j];
    }
  }
  return c;
}
