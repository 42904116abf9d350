/* The white furnace of rough boundaries with energy compensation (Kulla &
 * Conty 2017) to 0.5 %: a lossless translucent sphere (albedo 1,
 * isotropic medium) under a sky of radiance 1 renders to radiance 1 within
 * 0.5 % for Beckmann and GGX at alpha 0.1, 0.3, 0.7 and eta 1.33, 1.5, with
 * 500 000 paths per case (standard error below 0.15 %). Clear rough spheres
 * are checked statistically in test_furnace.c. */
#include "render/furnace.h"

Test(furnace_slow, compensated_rough_boundaries_return_environment_within_half_percent,
     .timeout = 1800) {
  const ss_microfacet_type types[] = {SS_MICROFACET_BECKMANN, SS_MICROFACET_GGX};
  const double alphas[] = {0.1, 0.3, 0.7}, etas[] = {1.33, 1.5};
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 3; ++a) {
      for (int e = 0; e < 2; ++e) {
        ss_running_stats st;
        rough_furnace(types[t], alphas[a], etas[e], 1, 1, 500000, &st);
        double se = ss_running_stats_stderr(&st);
        cr_expect(fabs(st.mean - 1.0) <= 0.005 && se < 0.0015,
                  "%s alpha %g eta %g: %.5f +- %.5f, expected 1 within 0.5 %%",
                  ss_microfacet_type_name(types[t]), alphas[a], etas[e], st.mean, se);
      }
    }
  }
}
