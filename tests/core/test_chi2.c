/* The chi-square harness accepts correct samplers and rejects subtly wrong
 * ones: a density 2% off in one region (wrong sampler or wrong pdf), a pdf
 * that is not normalised, and samples where the pdf is zero.
 *
 * Power: with N samples and a 2% excess on a region of probability 1/4
 * (compensated elsewhere), Pearson's statistic gains the non-centrality
 * N (0.25 * 0.02^2 + 0.75 * (0.02/3)^2) = 1.3e-4 N, i.e. 267 for N = 2e6,
 * against a spread of sqrt(2 dof) = 20 for 200 cells: rejected with
 * certainty. (With 12800 cells the same defect moves the statistic by less
 * than two of its standard deviations: coarse cells are what resolve a
 * smooth, spread-out error.) */
#include "subsurf/chi2.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>

#define SAMPLES 2000000
#define EPS 0.02
/* Chi-square runs in this file that must pass; rejections are judged at the same level. */
#define NACCEPT 5

static double alpha(void) { return ss_chi2_sidak_alpha(0.01, NACCEPT); }

static void coarse_options(ss_chi2_sphere_options *o) {
  ss_chi2_sphere_options_default(o);
  o->theta_bins = 10;
  o->phi_bins = 20;
  o->samples = SAMPLES;
}

/* ---- sphere ---- */

/* The cap z > 1/2 holds a quarter of the sphere. */
static int biased_sphere_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *d) {
  double p_cap = 0.25 * (1.0 + EPS), z;
  if (u1 < p_cap) {
    z = 0.5 + 0.5 * (u1 / p_cap);
  } else {
    z = -1.0 + 1.5 * ((u1 - p_cap) / (1.0 - p_cap));
  }
  *d = ss_spherical_direction(z, 2.0 * SS_PI * u2);
  return 1;
}

static int sphere_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *d) {
  *d = ss_sample_uniform_sphere(u1, u2);
  return 1;
}

static double sphere_pdf(void *ctx, ss_vec3 d) { return SS_INV_4PI; }

static double scaled_sphere_pdf(void *ctx, ss_vec3 d) { return (1.0 + EPS) * SS_INV_4PI; }

/* The biased sampler's density, claimed by a correct sampler's test. */
static double biased_sphere_pdf(void *ctx, ss_vec3 d) {
  return d.z > 0.5 ? (1.0 + EPS) * SS_INV_4PI : (1.0 - EPS / 3.0) * SS_INV_4PI;
}

static double hemisphere_pdf(void *ctx, ss_vec3 d) { return d.z > 0.0 ? 0.5 * SS_INV_PI : 0.0; }

Test(chi2, accepts_a_correct_sphere_sampler) {
  ss_chi2_sphere_options o;
  coarse_options(&o);
  ss_chi2_result res;
  ss_chi2_test_sphere(sphere_sample, sphere_pdf, NULL, &o, &res);
  cr_assert_gt(res.p_value, alpha(), "%s", res.message);
  cr_assert_float_eq(res.pdf_integral, 1.0, 1e-6);
  /* Fine default cells, too. */
  ss_chi2_sphere_options_default(&o);
  ss_chi2_test_sphere(sphere_sample, sphere_pdf, NULL, &o, &res);
  cr_assert_gt(res.p_value, alpha(), "%s", res.message);
}

Test(chi2, accepts_the_biased_sampler_against_its_true_pdf) {
  ss_chi2_sphere_options o;
  coarse_options(&o);
  /* A theta edge at 60 degrees (z = 1/2) so no cell straddles the step. */
  o.theta_bins = 9;
  ss_chi2_result res;
  ss_chi2_test_sphere(biased_sphere_sample, biased_sphere_pdf, NULL, &o, &res);
  cr_assert_gt(res.p_value, alpha(), "%s", res.message);
  cr_assert_float_eq(res.pdf_integral, 1.0, 1e-6);
}

Test(chi2, rejects_a_sampler_two_percent_off_in_one_region) {
  ss_chi2_sphere_options o;
  coarse_options(&o);
  ss_chi2_result res;
  ss_chi2_test_sphere(biased_sphere_sample, sphere_pdf, NULL, &o, &res);
  cr_assert_lt(res.p_value, alpha(), "not rejected: %s", res.message);
}

Test(chi2, rejects_a_pdf_two_percent_off_in_one_region) {
  ss_chi2_sphere_options o;
  coarse_options(&o);
  o.theta_bins = 9;
  ss_chi2_result res;
  ss_chi2_test_sphere(sphere_sample, biased_sphere_pdf, NULL, &o, &res);
  cr_assert_lt(res.p_value, alpha(), "not rejected: %s", res.message);
  cr_assert_float_eq(res.pdf_integral, 1.0, 1e-6, "this pdf is normalised, just wrong");
}

Test(chi2, rejects_a_pdf_that_is_not_normalised) {
  ss_chi2_sphere_options o;
  coarse_options(&o);
  ss_chi2_result res;
  ss_chi2_test_sphere(sphere_sample, scaled_sphere_pdf, NULL, &o, &res);
  cr_assert_lt(res.p_value, alpha(), "not rejected: %s", res.message);
  cr_assert_float_eq(res.pdf_integral, 1.0 + EPS, 1e-6, "the integral reveals it");
}

Test(chi2, rejects_samples_where_the_pdf_is_zero) {
  ss_chi2_sphere_options o;
  coarse_options(&o);
  o.samples = 100000;
  ss_chi2_result res;
  ss_chi2_test_sphere(sphere_sample, hemisphere_pdf, NULL, &o, &res);
  cr_assert_eq(res.p_value, 0.0, "%s", res.message);
  cr_assert_not_null(strstr(res.message, "zero"), "message: %s", res.message);
}

Test(chi2, counts_refused_samples_as_invalid) {
  ss_chi2_sphere_options o;
  coarse_options(&o);
  o.samples = 1000;
  o.theta_max = 0.5 * SS_PI;
  ss_chi2_result res;
  /* Half the uniform-sphere samples lie below the binned hemisphere. */
  ss_chi2_test_sphere(sphere_sample, hemisphere_pdf, NULL, &o, &res);
  cr_assert(res.invalid > 400 && res.invalid < 600, "%llu invalid",
            (unsigned long long)res.invalid);
}

/* ---- 1D: uniform on [0, 1) claimed, 2% excess on [1/4, 1/2) taken from
 * [1/2, 1) ---- */

static int biased_1d_sample(void *ctx, double u1, double u2, double *x) {
  double a = 0.25, b = 0.25 * (1.0 + EPS) + a; /* cdf at 1/4 and at 1/2 */
  if (u1 < a) {
    *x = 0.25 * (u1 / a);
  } else if (u1 < b) {
    *x = 0.25 + 0.25 * (u1 - a) / (b - a);
  } else {
    *x = 0.5 + 0.5 * (u1 - b) / (1.0 - b);
  }
  return 1;
}

static int uniform_1d_sample(void *ctx, double u1, double u2, double *x) {
  *x = u1;
  return 1;
}

static double uniform_1d_pdf(void *ctx, double x) { return x >= 0.0 && x < 1.0 ? 1.0 : 0.0; }

Test(chi2, one_dimensional_harness_accepts_and_rejects) {
  enum { N = 200 };
  double e[N + 1];
  for (int i = 0; i <= N; ++i) {
    e[i] = (double)i / N;
  }
  ss_chi2_result res;
  ss_chi2_test_1d(uniform_1d_sample, uniform_1d_pdf, NULL, e, N, SAMPLES, 8, &res);
  cr_assert_gt(res.p_value, alpha(), "%s", res.message);
  ss_chi2_test_1d(biased_1d_sample, uniform_1d_pdf, NULL, e, N, SAMPLES, 8, &res);
  cr_assert_lt(res.p_value, alpha(), "not rejected: %s", res.message);
}

/* ---- 2D: uniform on the unit square claimed, 2% excess on one quadrant ---- */

static int uniform_2d_sample(void *ctx, double u1, double u2, double u3, double *x, double *y) {
  *x = u1;
  *y = u2;
  return 1;
}

static int biased_2d_sample(void *ctx, double u1, double u2, double u3, double *x, double *y) {
  /* x < 1/2 and y < 1/2 with probability 1.02/4; the quadrant is picked by
   * u3 and the point placed uniformly inside it by (u1, u2). */
  double p0 = 0.25 * (1.0 + EPS), rest = (1.0 - p0) / 3.0;
  int q = u3 < p0 ? 0 : 1 + (int)fmin(2.0, (u3 - p0) / rest);
  *x = 0.5 * (u1 + (double)(q & 1));
  *y = 0.5 * (u2 + (double)(q >> 1));
  return 1;
}

static double uniform_2d_pdf(void *ctx, double x, double y) { return 1.0; }

Test(chi2, two_dimensional_harness_accepts_and_rejects) {
  enum { N = 14 };
  double e[N + 1];
  for (int i = 0; i <= N; ++i) {
    e[i] = (double)i / N;
  }
  ss_chi2_result res;
  ss_chi2_test_2d(uniform_2d_sample, uniform_2d_pdf, NULL, e, N, e, N, SAMPLES, 9, &res);
  cr_assert_gt(res.p_value, alpha(), "%s", res.message);
  ss_chi2_test_2d(biased_2d_sample, uniform_2d_pdf, NULL, e, N, e, N, SAMPLES, 9, &res);
  cr_assert_lt(res.p_value, alpha(), "not rejected: %s", res.message);
}

Test(chi2, sidak_alpha_keeps_the_family_level) {
  double a = ss_chi2_sidak_alpha(0.01, 10);
  cr_assert_float_eq(1.0 - pow(1.0 - a, 10.0), 0.01, 1e-12);
  cr_assert_float_eq(ss_chi2_sidak_alpha(0.05, 1), 0.05, 1e-15);
}
