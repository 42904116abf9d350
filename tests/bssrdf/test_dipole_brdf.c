#include "bssrdf/bssrdf_test_util.h"

/* Jensen et al. 2001, sec. 2.4: f_r = f_r^(1) + Ft Ft R_d / pi. */
Test(dipole_brdf, is_single_scattering_plus_the_fresnel_weighted_dipole_total) {
  ss_bssrdf *b = make_gray("dipole-brdf", 0.95, 1.0, 1.3, 0.2);
  ss_bssrdf *s = make_gray("single", 0.95, 1.0, 1.3, 0.2);
  ss_bssrdf *d = make_gray("dipole", 0.95, 1.0, 1.3, 0.2);
  double rd[3];
  ss_bssrdf_rd(d, rd);
  ss_vec3 w_i = ss_vec3_normalize(ss_vec3_make(-0.3, 0.1, 0.8));
  ss_vec3 w_o = ss_vec3_normalize(ss_vec3_make(0.5, -0.2, 0.6));
  double f[3], fs[3];
  ss_bssrdf_brdf(b, w_i, w_o, f);
  ss_bssrdf_brdf(s, w_i, w_o, fs);
  double expect = fs[0] + (1.0 - ss_fresnel_dielectric(w_i.z, 1.3)) *
                              (1.0 - ss_fresnel_dielectric(w_o.z, 1.3)) * rd[0] / SS_PI;
  cr_expect(fabs(f[0] - expect) < 1e-12, "%g vs %g", f[0], expect);
  ss_bssrdf_destroy(b);
  ss_bssrdf_destroy(s);
  ss_bssrdf_destroy(d);
}

Test(dipole_brdf, total_is_the_hemispherical_integral_of_the_brdf_and_below_one) {
  const double albedos[] = {0.5, 0.99, 1.0};
  for (int i = 0; i < 3; ++i) {
    ss_bssrdf *b = make_gray("dipole-brdf", albedos[i], 1.0, 1.3, 0.0);
    for (int k = 0; k < 2; ++k) {
      double cos_i = k ? 0.5 : 1.0, sin_i = sqrt(1.0 - cos_i * cos_i), tot[3], sum = 0.0;
      ss_bssrdf_total_reflectance(b, cos_i, tot);
      /* midpoint quadrature over the hemisphere in (mu, phi) */
      const int n = 200;
      for (int a = 0; a < n; ++a) {
        for (int c = 0; c < 2 * n; ++c) {
          double mu = (a + 0.5) / n, phi = SS_PI * (c + 0.5) / n, f[3];
          ss_bssrdf_brdf(b, ss_vec3_make(-sin_i, 0, cos_i), ss_spherical_direction(mu, phi), f);
          sum += f[0] * mu * (1.0 / n) * (SS_PI / n);
        }
      }
      cr_expect(fabs(sum - tot[0]) < 1e-4, "albedo %g: %.6f vs %.6f", albedos[i], sum, tot[0]);
      /* Below the power that enters, except at albedo 1, where R_d = 1 and
       * the single-scattering term is counted a second time (sec. 2.4 adds
       * both without removing single scattering from R_d). */
      double entered = 1.0 - ss_fresnel_dielectric(cos_i, 1.3);
      if (albedos[i] < 1.0) {
        cr_expect(tot[0] < entered, "albedo %g: %g >= %g", albedos[i], tot[0], entered);
      } else {
        cr_expect(tot[0] > entered, "albedo 1: %g <= %g", tot[0], entered);
      }
    }
    ss_bssrdf_destroy(b);
  }
}

Test(dipole_brdf, all_exitance_leaves_in_the_bin_of_the_entry_point) {
  ss_bssrdf *b = make_gray("dipole-brdf", 0.9, 1.0, 1.3, 0.0);
  double tot[3], first[3], second[3];
  ss_bssrdf_total_reflectance(b, 1.0, tot);
  ss_bssrdf_radial_average(b, 1.0, 0.0, 0.1, first);
  ss_bssrdf_radial_average(b, 1.0, 0.1, 0.2, second);
  cr_expect(fabs(first[0] * SS_PI * 0.01 - tot[0]) < 1e-12);
  cr_expect_eq(second[0], 0.0);
  ss_bssrdf_entry e;
  ss_bssrdf_sample_ctx ctx = default_sample_ctx();
  cr_expect_eq(ss_bssrdf_sample_entry(b, &ctx, 0, 0.5, 0.5, &e), 0);
  ss_bssrdf_destroy(b);
}
