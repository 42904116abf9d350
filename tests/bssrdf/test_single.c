#include "bssrdf/bssrdf_test_util.h"

/* Index matched, isotropic, normal incidence: the single-scattering albedo is
 * alpha int_0^1 mu / (1 + mu) dmu / 2 = alpha (1 - ln 2) / 2 (Chandrasekhar's
 * first-order term). */
Test(single, index_matched_isotropic_total_has_closed_form) {
  const double albedos[] = {0.3, 0.9, 1.0};
  for (int i = 0; i < 3; ++i) {
    ss_bssrdf *b = make_gray("single", albedos[i], 2.0, 1.0, 0.0);
    double tot[3];
    ss_bssrdf_total_reflectance(b, 1.0, tot);
    double exact = albedos[i] * (1.0 - log(2.0)) / 2.0;
    cr_expect(fabs(tot[0] - exact) < 1e-6, "albedo %g: %.8f vs %.8f", albedos[i], tot[0], exact);
    ss_bssrdf_destroy(b);
  }
}

Test(single, exitance_integrates_to_the_brdf_total) {
  const double etas[] = {1.0, 1.33};
  for (int j = 0; j < 2; ++j) {
    ss_bssrdf *b = make_gray("single", 0.8, 1.0, etas[j], 0.3);
    for (int k = 0; k < 2; ++k) {
      double cos_i = k ? 0.5 : 1.0, tot[3], num[3];
      ss_bssrdf_total_reflectance(b, cos_i, tot);
      integrate_exitance(b, cos_i, num);
      cr_expect(fabs(tot[0] - num[0]) < 2e-3 * tot[0], "eta %g cos %g: brdf %.6f exitance %.6f",
                etas[j], cos_i, tot[0], num[0]);
    }
    ss_bssrdf_destroy(b);
  }
}

/* int dx (int L dy) = int L dA = f_r(w_i, w_o) for a unit-power beam. */
Test(single, radiance_line_integrates_to_the_brdf) {
  ss_bssrdf *b = make_gray("single", 0.9, 1.0, 1.33, 0.5);
  const double thetas_o[] = {-50.0, 0.0, 30.0, 70.0};
  for (int k = 0; k < 2; ++k) {
    double cos_i = k ? cos(60.0 * SS_PI / 180.0) : 1.0;
    double sin_i = sqrt(1.0 - cos_i * cos_i);
    for (int j = 0; j < 4; ++j) {
      double t = thetas_o[j] * SS_PI / 180.0;
      ss_vec3 w_o = ss_vec3_make(sin(t), 0.0, cos(t));
      double f[3], avg[3], sum = 0.0;
      ss_bssrdf_brdf(b, ss_vec3_make(-sin_i, 0.0, cos_i), w_o, f);
      for (double x = -40.0; x < 40.0; x += 1.0) {
        ss_bssrdf_direction_average(b, cos_i, w_o, x, x + 1.0, avg);
        sum += avg[0];
      }
      cr_expect(fabs(sum - f[0]) < 1e-4 * f[0], "cos_i %g theta_o %g: %.7f vs %.7f", cos_i,
                thetas_o[j], sum, f[0]);
    }
  }
  ss_bssrdf_destroy(b);
}

Test(single, brdf_is_reciprocal) {
  ss_bssrdf *b = make_gray("single", 0.7, 1.0, 1.5, 0.6);
  ss_rng rng;
  ss_rng_seed(&rng, 3, 0);
  for (int i = 0; i < 100; ++i) {
    ss_vec3 a = ss_sample_uniform_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    ss_vec3 c = ss_sample_uniform_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    double f1[3], f2[3];
    ss_bssrdf_brdf(b, a, c, f1);
    ss_bssrdf_brdf(b, c, a, f2);
    cr_expect(fabs(f1[0] - f2[0]) <= 1e-12 * f1[0], "%g vs %g", f1[0], f2[0]);
  }
  ss_bssrdf_destroy(b);
}
