/* The white furnace of rough boundaries whose roughness is a texture:
 * with the energy compensation interpolated from the tables
 * over alpha, a lossless translucent sphere under a sky of radiance 1
 * returns 1 within 4.5 standard errors (20 000 paths; to 0.5 % in
 * test_furnace_textured_rough_slow.c), and without it comes out darker. */
#include "render/furnace.h"

static const ss_microfacet_type types[] = {SS_MICROFACET_BECKMANN, SS_MICROFACET_GGX};
static const char *const patterns[] = {"checker", "noise"};

Test(furnace_textured_rough, compensated_textured_alpha_returns_environment) {
  for (int t = 0; t < 2; ++t) {
    for (int p = 0; p < 2; ++p) {
      ss_running_stats st;
      rough_furnace_alpha(types[t], 0.1, alpha_texture(p), 1.5, 1, 1, 20000, &st);
      double se = ss_running_stats_stderr(&st);
      cr_expect(fabs(st.mean - 1.0) <= 4.5 * se, "%s, %s alpha in [0.1, 0.7]: %.5f +- %.5f",
                ss_microfacet_type_name(types[t]), patterns[p], st.mean, se);
    }
  }
}

Test(furnace_textured_rough, uncompensated_textured_alpha_is_dark) {
  ss_running_stats comp, lossy;
  rough_furnace_alpha(SS_MICROFACET_GGX, 0.1, alpha_texture(0), 1.5, 1, 1, 20000, &comp);
  rough_furnace_alpha(SS_MICROFACET_GGX, 0.1, alpha_texture(0), 1.5, 0, 1, 20000, &lossy);
  double se = hypot(ss_running_stats_stderr(&comp), ss_running_stats_stderr(&lossy));
  cr_expect(comp.mean - lossy.mean > 4.5 * se,
            "compensated %.5f, single scattering %.5f (+- %.5f): the texture must be compensated",
            comp.mean, lossy.mean, se);
}
