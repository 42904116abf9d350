/* The white furnace of rough boundaries with a textured roughness to 0.5 %:
 * a lossless translucent sphere (albedo 1, isotropic medium)
 * whose alpha is a checker or a noise texture with values in [0.1, 0.7]
 * renders to radiance 1 within 0.5 % under a sky of radiance 1, for
 * Beckmann and GGX at eta 1.33 and 1.5, with 500 000 paths per case
 * (standard error below 0.15 %). */
#include "render/furnace.h"

Test(furnace_textured_rough_slow, textured_alpha_returns_environment_within_half_percent,
     .timeout = 1800) {
  const ss_microfacet_type types[] = {SS_MICROFACET_BECKMANN, SS_MICROFACET_GGX};
  const double etas[] = {1.33, 1.5};
  const char *const patterns[] = {"checker", "noise"};
  for (int t = 0; t < 2; ++t) {
    for (int p = 0; p < 2; ++p) {
      for (int e = 0; e < 2; ++e) {
        ss_running_stats st;
        rough_furnace_alpha(types[t], 0.1, alpha_texture(p), etas[e], 1, 1, 500000, &st);
        double se = ss_running_stats_stderr(&st);
        cr_log_info("%s, %s, eta %g: %.5f +- %.5f", ss_microfacet_type_name(types[t]), patterns[p],
                    etas[e], st.mean, se);
        cr_expect(fabs(st.mean - 1.0) <= 0.005 && se < 0.0015,
                  "%s, %s alpha in [0.1, 0.7], eta %g: %.5f +- %.5f, expected 1 within 0.5 %%",
                  ss_microfacet_type_name(types[t]), patterns[p], etas[e], st.mean, se);
      }
    }
  }
}
