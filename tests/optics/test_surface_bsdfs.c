/* The surface BSDFs beside diffuse and conductors: mirror, thin dielectric,
 * diffuse transmission, two-sided and mix. Each samples its own pdf
 * (chi-square) where it has a density, is reciprocal, and conserves energy
 * where it should (white furnace). Tolerances are 4.5 standard errors. */
#include <criterion/criterion.h>

#include "optics/bsdf_albedo.h"
#include "optics/bsdf_chi2.h"
#include "subsurf/bsdf.h"
#include "subsurf/fresnel.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/stats.h"

#include <math.h>
#include <stdio.h>

static ss_vec3 grey(double v) { return ss_vec3_make(v, v, v); }

static void expect_albedo(const ss_bsdf *b, ss_vec3 wo, int c, double expected, uint64_t seed,
                          const char *what) {
  ss_running_stats st;
  albedo_dir(b, wo, c, 40000, seed, &st);
  double se = ss_running_stats_stderr(&st);
  cr_expect(fabs(st.mean - expected) <= 4.5 * se + 1e-12, "%s: albedo %.6f +- %.6f, expected %.6f",
            what, st.mean, se, expected);
}

static ss_bsdf rough_conductor(double au, double av) {
  ss_microfacet m;
  ss_error err;
  cr_assert_eq(ss_microfacet_init_anisotropic(&m, SS_MICROFACET_GGX, au, av, &err), SS_OK);
  ss_bsdf b;
  cr_assert_eq(ss_bsdf_conductor_init(&b, grey(1.0), grey(1e4), &m, 1, &err), SS_OK, "%s",
               err.message);
  return b;
}

Test(mirror, reflects_its_reflectance_on_the_front_only) {
  ss_bsdf b;
  ss_error err;
  cr_assert_eq(ss_bsdf_mirror_init(&b, ss_vec3_make(0.9, 0.5, 0.1), &err), SS_OK);
  ss_vec3 wo = ss_vec3_normalize(ss_vec3_make(0.3, -0.4, 0.7));
  ss_bsdf_sample s;
  cr_assert(ss_bsdf_sample_dir(&b, wo, 0.5, 0.5, 0.5, &s));
  cr_expect(s.lobe == (SS_BSDF_REFLECTION | SS_BSDF_DELTA));
  cr_expect_float_eq(s.f.y * s.wi.z / s.pdf, 0.5, 1e-12);
  cr_expect_float_eq(s.wi.x, -wo.x, 1e-15);
  cr_expect_not(ss_bsdf_sample_dir(&b, ss_vec3_neg(wo), 0.5, 0.5, 0.5, &s));
  cr_expect_neq(ss_bsdf_mirror_init(&b, grey(1.5), &err), SS_OK);
}

/* The sheet's reflectance is the sum of the series of internal bounces,
 * it transmits the rest straight on, and it looks the same from both
 * sides. */
Test(thin_dielectric, sums_the_internal_reflections_and_conserves_energy) {
  ss_bsdf b;
  ss_error err;
  cr_assert_eq(ss_bsdf_thin_dielectric_init(&b, 1.5, &err), SS_OK);
  const double mus[] = {1.0, 0.6, 0.2};
  for (int m = 0; m < 3; ++m) {
    double r = ss_fresnel_dielectric(mus[m], 1.5), t = 1.0 - r, series = r, bounce = t * t * r;
    for (int k = 0; k < 60; ++k, bounce *= r * r) {
      series += bounce;
    }
    for (int side = 0; side < 2; ++side) {
      ss_vec3 wo = ss_spherical_direction(side ? -mus[m] : mus[m], 0.4);
      ss_bsdf_sample s;
      cr_assert(ss_bsdf_sample_dir(&b, wo, 0.0, 0.5, 0.5, &s));
      cr_expect(s.lobe & SS_BSDF_REFLECTION);
      cr_expect_float_eq(s.pdf, series, 1e-12, "mu %g: %g vs series %g", mus[m], s.pdf, series);
      cr_expect_float_eq(s.f.x * fabs(s.wi.z) / s.pdf, 1.0, 1e-12);
      cr_assert(ss_bsdf_sample_dir(&b, wo, nextafter(1.0, 0.0), 0.5, 0.5, &s));
      cr_expect(s.lobe == (SS_BSDF_TRANSMISSION | SS_BSDF_DELTA));
      cr_expect_float_eq(s.wi.x, -wo.x, 1e-15);
      cr_expect_float_eq(s.wi.z, -wo.z, 1e-15);
      cr_expect_float_eq(s.eta, 1.0, 0.0);
      cr_expect_float_eq(s.pdf, 1.0 - series, 1e-12);
      expect_albedo(&b, wo, 0, 1.0, (uint64_t)(m + 3 * side), "thin dielectric");
    }
  }
}

Test(diffuse_transmission, samples_its_pdf_is_reciprocal_and_conserves_energy) {
  ss_bsdf b;
  ss_error err;
  ss_vec3 r = ss_vec3_make(0.3, 0.6, 0.1), t = ss_vec3_make(0.7, 0.4, 0.9);
  cr_assert_eq(ss_bsdf_diffuse_transmission_init(&b, r, t, &err), SS_OK, "%s", err.message);
  double level = ss_chi2_sidak_alpha(0.01, 2);
  expect_rough_bsdf_chi2(&b, ss_spherical_direction(0.7, 1.0), 150000, 41, level, "from outside");
  expect_rough_bsdf_chi2(&b, ss_spherical_direction(-0.3, 2.0), 150000, 42, level, "from inside");
  for (int c = 0; c < 3; ++c) {
    expect_albedo(&b, ss_spherical_direction(0.4, 0.3), c, 1.0, (uint64_t)(50 + c), "R + T = 1");
  }
  ss_rng rng;
  ss_rng_seed(&rng, 2, 2);
  for (int i = 0; i < 100; ++i) {
    ss_vec3 wo = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    ss_vec3 wi = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    cr_expect_float_eq(ss_bsdf_eval(&b, wo, wi).y, ss_bsdf_eval(&b, wi, wo).y, 1e-15);
  }
  cr_expect_neq(ss_bsdf_diffuse_transmission_init(&b, grey(0.6), grey(0.6), &err), SS_OK);
}

/* A one-sided rough conductor wrapped two-sided: from inside it is the
 * front mirrored, samples its pdf and (F = 1, compensated) reflects
 * everything. */
Test(two_sided, mirrors_the_front_to_the_back) {
  ss_bsdf front = rough_conductor(0.2, 0.5), b;
  ss_error err;
  cr_assert_eq(ss_bsdf_two_sided_init(&b, &front, &err), SS_OK);
  ss_vec3 wo = ss_spherical_direction(0.6, 0.7), wi = ss_spherical_direction(0.3, 2.5);
  ss_vec3 wo_b = ss_vec3_make(wo.x, wo.y, -wo.z), wi_b = ss_vec3_make(wi.x, wi.y, -wi.z);
  cr_expect_float_eq(ss_bsdf_eval(&b, wo_b, wi_b).x, ss_bsdf_eval(&front, wo, wi).x, 1e-15);
  cr_expect_float_eq(ss_bsdf_eval(&front, wo_b, wi_b).x, 0.0, 0.0);
  expect_rough_bsdf_chi2(&b, wo_b, 150000, 61, 0.01, "two-sided from inside");
  expect_albedo(&b, wo_b, 1, 1.0, 62, "two-sided furnace");
}

/* A mix of a rough conductor and diffuse transmission samples its pdf and
 * is reciprocal; a mix of energy-conserving parts conserves energy; a mix
 * with a mirror (a delta lobe) has the weighted albedo of its parts. */
Test(mix, samples_its_pdf_and_weights_its_parts) {
  ss_bsdf metal = rough_conductor(0.3, 0.3), dt, mirror, m;
  ss_error err;
  cr_assert_eq(ss_bsdf_diffuse_transmission_init(&dt, grey(0.5), grey(0.5), &err), SS_OK);
  cr_assert_eq(ss_bsdf_mix_init(&m, &metal, &dt, 0.3, &err), SS_OK);
  cr_expect_not(m.lobes & SS_BSDF_DELTA);
  double level = ss_chi2_sidak_alpha(0.01, 2);
  expect_rough_bsdf_chi2(&m, ss_spherical_direction(0.8, 0.2), 150000, 71, level, "outside");
  expect_rough_bsdf_chi2(&m, ss_spherical_direction(-0.5, 0.2), 150000, 72, level, "inside");
  expect_albedo(&m, ss_spherical_direction(0.5, 1.1), 0, 1.0, 73, "mix furnace");
  ss_vec3 wo = ss_spherical_direction(0.45, 0.3), wi = ss_spherical_direction(0.8, 2.0);
  cr_expect_float_eq(ss_bsdf_eval(&m, wo, wi).x, ss_bsdf_eval(&m, wi, wo).x,
                     1e-9 * ss_bsdf_eval(&m, wo, wi).x);
  cr_expect_float_eq(ss_bsdf_eval(&m, wo, wi).x,
                     0.3 * ss_bsdf_eval(&metal, wo, wi).x + 0.7 * ss_bsdf_eval(&dt, wo, wi).x,
                     1e-15);
  ss_bsdf diffuse;
  cr_assert_eq(ss_bsdf_mirror_init(&mirror, grey(0.8), &err), SS_OK);
  cr_assert_eq(ss_bsdf_diffuse_init(&diffuse, grey(0.4), &err), SS_OK);
  cr_assert_eq(ss_bsdf_mix_init(&m, &mirror, &diffuse, 0.25, &err), SS_OK);
  cr_expect_not(m.lobes & SS_BSDF_DELTA, "a mix with a density is not a delta BSDF");
  expect_albedo(&m, ss_spherical_direction(0.7, 0.0), 0, 0.25 * 0.8 + 0.75 * 0.4, 74,
                "mirror and diffuse");
  cr_expect_neq(ss_bsdf_mix_init(&m, &mirror, &diffuse, 1.5, &err), SS_OK);
}

/* ---- Coated diffuse. */

static ss_bsdf coated(ss_vec3 r, double eta) {
  ss_bsdf b;
  ss_error err;
  cr_assert_eq(ss_bsdf_coated_diffuse_init(&b, r, eta, &err), SS_OK, "%s", err.message);
  return b;
}

/* The cosine lobe alone (uc past the mirror's probability), its density
 * renormalised: the chi-square test of the non-delta part. */
typedef struct {
  const ss_bsdf *b;
  ss_vec3 wo;
} lobe_ctx;

static int sample_diffuse_lobe(void *p, double u1, double u2, double u3, ss_vec3 *dir) {
  const lobe_ctx *c = p;
  ss_bsdf_sample s;
  if (!ss_bsdf_sample_dir(c->b, c->wo, nextafter(1.0, 0.0), u2, u3, &s)) {
    return 0;
  }
  cr_assert_not(s.lobe & SS_BSDF_DELTA);
  *dir = s.wi;
  return 1;
}

static double pdf_diffuse_lobe(void *p, ss_vec3 dir) {
  const lobe_ctx *c = p;
  ss_bsdf_sample s;
  cr_assert(ss_bsdf_sample_dir(c->b, c->wo, nextafter(1.0, 0.0), 0.3, 0.3, &s));
  double p_lobe = s.pdf / ss_pdf_cosine_hemisphere(s.wi.z);
  return ss_bsdf_pdf(c->b, c->wo, dir) / p_lobe;
}

Test(coated_diffuse, white_base_conserves_energy_and_grey_matches_the_closed_form) {
  const double etas[] = {1.33, 1.5, 2.0}, mus[] = {0.1, 0.5, 0.95};
  for (int e = 0; e < 3; ++e) {
    /* F_avg = 2 int F mu dmu by the midpoint rule. */
    double f_avg = 0.0;
    for (int i = 0; i < 20000; ++i) {
      double mu = (i + 0.5) / 20000;
      f_avg += 2.0 * ss_fresnel_dielectric(mu, etas[e]) * mu / 20000;
    }
    ss_bsdf white = coated(grey(1.0), etas[e]);
    cr_expect_float_eq(white.coat_f_avg, f_avg, 1e-6, "eta %g: %g vs %g", etas[e], white.coat_f_avg,
                       f_avg);
    ss_bsdf g = coated(grey(0.5), etas[e]);
    double f_int = 1.0 - (1.0 - f_avg) / (etas[e] * etas[e]);
    for (int m = 0; m < 3; ++m) {
      ss_vec3 wo = ss_spherical_direction(mus[m], 0.8);
      expect_albedo(&white, wo, 1, 1.0, (uint64_t)(80 + 3 * e + m), "white coated diffuse");
      double f_o = ss_fresnel_dielectric(mus[m], etas[e]);
      double expected =
          f_o + (1.0 - f_o) * 0.5 / (1.0 - 0.5 * f_int) * (1.0 - f_avg) / (etas[e] * etas[e]);
      expect_albedo(&g, wo, 0, expected, (uint64_t)(90 + 3 * e + m), "grey coated diffuse");
    }
  }
}

Test(coated_diffuse, diffuse_lobe_samples_its_pdf_and_is_reciprocal) {
  ss_bsdf b = coated(ss_vec3_make(0.8, 0.4, 0.1), 1.5);
  double level = ss_chi2_sidak_alpha(0.01, 2);
  for (int k = 0; k < 2; ++k) {
    lobe_ctx c = {&b, ss_spherical_direction(k ? 0.2 : 0.9, 1.0)};
    ss_chi2_sphere_options opt;
    ss_chi2_sphere_options_default(&opt);
    opt.theta_bins = 40;
    opt.phi_bins = 80;
    opt.samples = 150000;
    opt.seed = (uint64_t)(95 + k);
    ss_chi2_result res;
    ss_chi2_test_sphere(sample_diffuse_lobe, pdf_diffuse_lobe, &c, &opt, &res);
    cr_expect_gt(res.p_value, level, "%s", res.message);
    cr_expect_float_eq(res.pdf_integral, 1.0, 3e-3, "%s", res.message);
  }
  ss_vec3 wo = ss_spherical_direction(0.3, 0.2), wi = ss_spherical_direction(0.85, 2.2);
  cr_expect_float_eq(ss_bsdf_eval(&b, wo, wi).y, ss_bsdf_eval(&b, wi, wo).y, 1e-15);
  cr_expect_float_eq(ss_bsdf_eval(&b, ss_vec3_neg(wo), wi).y, 0.0, 0.0, "one-sided");
  ss_bsdf bad;
  ss_error err;
  cr_expect_neq(ss_bsdf_coated_diffuse_init(&bad, grey(0.5), 1.0, &err), SS_OK);
}
