/* Every warp of sampling.h draws from the density it claims: chi-square
 * tests on the sphere, in 2D and in 1D, with the claimed pdf integrating to 1
 * over its domain. Alpha is Sidak-corrected over the tests of this file. */
#include "subsurf/chi2.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>

#define NTESTS 10 /* chi-square tests in this file */
#define SAMPLES 1000000

static double alpha(void) { return ss_chi2_sidak_alpha(0.01, NTESTS); }

static void assert_passes(const ss_chi2_result *res, const char *what) {
  cr_assert_gt(res->p_value, alpha(), "%s: %s", what, res->message);
  cr_assert_float_eq(res->pdf_integral, 1.0, 1e-4, "%s: pdf integrates to %.6f", what,
                     res->pdf_integral);
}

/* ---- directions ---- */

static int sphere_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *d) {
  *d = ss_sample_uniform_sphere(u1, u2);
  return 1;
}
static double sphere_pdf(void *ctx, ss_vec3 d) { return ss_pdf_uniform_sphere(); }

static int hemi_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *d) {
  *d = ss_sample_uniform_hemisphere(u1, u2);
  return 1;
}
static double hemi_pdf(void *ctx, ss_vec3 d) {
  return d.z >= 0.0 ? ss_pdf_uniform_hemisphere() : 0.0;
}

static int cosine_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *d) {
  *d = ss_sample_cosine_hemisphere(u1, u2);
  return 1;
}
static double cosine_pdf(void *ctx, ss_vec3 d) { return ss_pdf_cosine_hemisphere(d.z); }

static int cone_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *d) {
  *d = ss_sample_uniform_cone(u1, u2, *(const double *)ctx);
  return 1;
}
static double cone_pdf(void *ctx, ss_vec3 d) {
  double cos_max = *(const double *)ctx;
  return d.z >= cos_max ? ss_pdf_uniform_cone(cos_max) : 0.0;
}

Test(sampling, uniform_sphere_matches_its_pdf) {
  ss_chi2_sphere_options o;
  ss_chi2_sphere_options_default(&o);
  o.samples = SAMPLES;
  ss_chi2_result res;
  ss_chi2_test_sphere(sphere_sample, sphere_pdf, NULL, &o, &res);
  assert_passes(&res, "uniform sphere");
}

Test(sampling, uniform_hemisphere_matches_its_pdf) {
  ss_chi2_sphere_options o;
  ss_chi2_sphere_options_default(&o);
  o.samples = SAMPLES;
  o.theta_max = 0.5 * SS_PI;
  ss_chi2_result res;
  ss_chi2_test_sphere(hemi_sample, hemi_pdf, NULL, &o, &res);
  assert_passes(&res, "uniform hemisphere");
  cr_assert_eq(res.invalid, 0u, "no sample below the horizon");
}

Test(sampling, cosine_hemisphere_matches_its_pdf) {
  ss_chi2_sphere_options o;
  ss_chi2_sphere_options_default(&o);
  o.samples = SAMPLES;
  o.theta_max = 0.5 * SS_PI;
  ss_chi2_result res;
  ss_chi2_test_sphere(cosine_sample, cosine_pdf, NULL, &o, &res);
  assert_passes(&res, "cosine hemisphere");
  cr_assert_eq(res.invalid, 0u, "no sample below the horizon");
}

/* The binned domain is exactly the cone, so cells never straddle its edge. */
Test(sampling, uniform_cone_matches_its_pdf) {
  const double cos_maxes[2] = {0.3, 0.95};
  for (int k = 0; k < 2; ++k) {
    double cos_max = cos_maxes[k];
    ss_chi2_sphere_options o;
    ss_chi2_sphere_options_default(&o);
    o.samples = SAMPLES;
    o.theta_bins = 40;
    o.theta_max = acos(cos_max);
    ss_chi2_result res;
    ss_chi2_test_sphere(cone_sample, cone_pdf, &cos_max, &o, &res);
    assert_passes(&res, k ? "narrow cone" : "wide cone");
    cr_assert_lt(res.invalid, 3u, "samples outside the cone: %llu",
                 (unsigned long long)res.invalid);
  }
}

/* ---- 2D warps, tested through exact changes of variables so that no cell
 * straddles a discontinuity of the density ---- */

/* The concentric map in polar coordinates (r, phi): uniform on the disk means
 * density r / pi per unit r*phi on [0, 1) x [0, 2 pi). */
static int disk_sample(void *ctx, double u1, double u2, double u3, double *r, double *phi) {
  double x, y;
  ss_sample_concentric_disk(u1, u2, &x, &y);
  *r = sqrt(x * x + y * y);
  *phi = atan2(y, x);
  if (*phi < 0.0) {
    *phi += 2.0 * SS_PI;
  }
  return 1;
}
static double disk_pdf(void *ctx, double r, double phi) { return r * SS_INV_PI; }

Test(sampling, concentric_disk_is_uniform) {
  enum { NR = 40, NPHI = 64 };
  double re[NR + 1], pe[NPHI + 1];
  for (int i = 0; i <= NR; ++i) {
    re[i] = (double)i / NR;
  }
  /* Slightly past 1 so that r = 1 from u = 0 or 1 lands in the last cell. */
  re[NR] = 1.0 + 1e-12;
  for (int j = 0; j <= NPHI; ++j) {
    pe[j] = 2.0 * SS_PI * j / NPHI;
  }
  pe[NPHI] = 2.0 * SS_PI + 1e-12;
  ss_chi2_result res;
  ss_chi2_test_2d(disk_sample, disk_pdf, NULL, re, NR, pe, NPHI, SAMPLES, 3, &res);
  assert_passes(&res, "concentric disk");
  cr_assert_eq(res.invalid, 0u);
}

/* Uniform barycentrics (b0, b1) on the triangle b0 + b1 <= 1 mean s = b0 + b1
 * with density 2 s and t = b0 / s uniform, independent: (s^2, t) is uniform
 * on the unit square. */
static int triangle_sample(void *ctx, double u1, double u2, double u3, double *x, double *y) {
  double b0, b1;
  ss_sample_uniform_triangle(u1, u2, &b0, &b1);
  if (b0 < 0.0 || b1 < 0.0 || b0 + b1 > 1.0) {
    return 0;
  }
  double s = b0 + b1;
  *x = s * s;
  *y = s > 0.0 ? b0 / s : 0.5;
  return 1;
}
static double triangle_pdf(void *ctx, double x, double y) { return 1.0; }

Test(sampling, triangle_barycentrics_are_uniform) {
  enum { N = 50 };
  double e[N + 1];
  for (int i = 0; i <= N; ++i) {
    e[i] = (double)i / N;
  }
  e[N] = 1.0 + 1e-12;
  ss_chi2_result res;
  ss_chi2_test_2d(triangle_sample, triangle_pdf, NULL, e, N, e, N, SAMPLES, 4, &res);
  assert_passes(&res, "triangle");
  cr_assert_eq(res.invalid, 0u, "every sample lies in the triangle");
}

/* ---- 1D ---- */

static int exp_sample(void *ctx, double u1, double u2, double *x) {
  *x = ss_sample_exponential(u1, *(const double *)ctx);
  return 1;
}
static double exp_pdf(void *ctx, double x) {
  double sigma = *(const double *)ctx;
  return x >= 0.0 ? sigma * exp(-sigma * x) : 0.0;
}

Test(sampling, exponential_matches_its_pdf) {
  enum { N = 200 };
  double sigma = 2.5, e[N + 1];
  /* Up to 14 mean free paths: the tail beyond holds exp(-14) ~ 1e-6 of the
   * mass, about one sample, which counts as "invalid" (outside the cells). */
  for (int i = 0; i <= N; ++i) {
    e[i] = 14.0 / sigma * i / N;
  }
  ss_chi2_result res;
  ss_chi2_test_1d(exp_sample, exp_pdf, &sigma, e, N, SAMPLES, 5, &res);
  cr_assert_gt(res.p_value, alpha(), "%s", res.message);
  cr_assert_float_eq(res.pdf_integral, 1.0 - exp(-14.0), 1e-6, "%.8f", res.pdf_integral);
  cr_assert_lt(res.invalid, 10u);
}

/* A piecewise-constant function with a zero cell; test cells are aligned with
 * the function's cells, 8 per cell. */
static const double func[8] = {1.0, 3.0, 0.0, 0.5, 2.0, 7.0, 0.25, 1.5};

static int dist_sample(void *ctx, double u1, double u2, double *x) {
  double pdf;
  *x = ss_distribution1d_sample_continuous(ctx, u1, &pdf);
  const ss_distribution1d *d = ctx;
  size_t cell = (size_t)(*x * (double)d->n);
  return cell < d->n && fabs(pdf - d->func[cell] / d->integral) < 1e-12;
}
static double dist_pdf(void *ctx, double x) {
  const ss_distribution1d *d = ctx;
  size_t cell = (size_t)(x * (double)d->n);
  return cell < d->n ? d->func[cell] / d->integral : 0.0;
}

Test(sampling, distribution1d_continuous_matches_its_pdf) {
  ss_distribution1d d;
  cr_assert_eq(ss_distribution1d_init(&d, func, 8), 0);
  double sum = 0.0;
  for (int i = 0; i < 8; ++i) {
    sum += func[i];
  }
  cr_assert_float_eq(d.integral, sum / 8.0, 1e-15, "integral over [0, 1]");
  enum { N = 64 };
  double e[N + 1];
  for (int i = 0; i <= N; ++i) {
    e[i] = (double)i / N;
  }
  ss_chi2_result res;
  ss_chi2_test_1d(dist_sample, dist_pdf, &d, e, N, SAMPLES, 6, &res);
  assert_passes(&res, "distribution1d continuous");
  cr_assert_eq(res.invalid, 0u, "the returned pdf is the cell's density");
  /* Nothing may land in the zero cell, not even a few samples. */
  ss_rng rng;
  ss_rng_seed(&rng, 1u, 2u);
  for (int i = 0; i < 100000; ++i) {
    double x = ss_distribution1d_sample_continuous(&d, ss_rng_uniform(&rng), NULL);
    cr_assert(!(x >= 0.25 && x < 0.375), "sample %g in the zero cell", x);
  }
  ss_distribution1d_free(&d);
}

static int discrete_sample(void *ctx, double u1, double u2, double *x) {
  double prob;
  size_t i = ss_distribution1d_sample_discrete(ctx, u1, &prob);
  *x = (double)i + 0.5;
  return fabs(prob - func[i] / 15.25) < 1e-12;
}
static double discrete_pdf(void *ctx, double x) {
  size_t i = (size_t)x;
  return i < 8 ? func[i] / 15.25 : 0.0;
}

Test(sampling, distribution1d_discrete_matches_its_probabilities) {
  ss_distribution1d d;
  cr_assert_eq(ss_distribution1d_init(&d, func, 8), 0);
  double e[9];
  for (int i = 0; i <= 8; ++i) {
    e[i] = i;
  }
  ss_chi2_result res;
  ss_chi2_test_1d(discrete_sample, discrete_pdf, &d, e, 8, SAMPLES, 7, &res);
  assert_passes(&res, "distribution1d discrete");
  cr_assert_eq(res.invalid, 0u, "the returned probability is func[i] / sum");
  ss_distribution1d_free(&d);
}

Test(sampling, distribution1d_rejects_all_zero_input) {
  const double zeros[3] = {0.0, 0.0, 0.0};
  ss_distribution1d d;
  cr_assert_eq(ss_distribution1d_init(&d, zeros, 3), -1);
  cr_assert_eq(ss_distribution1d_init(&d, func, 0), -1);
}

Test(sampling, closed_form_pdfs_integrate_to_one) {
  /* Solid-angle integrals of the constant and cosine densities, by midpoint
   * quadrature in cos(theta). */
  enum { N = 100000 };
  double cos_max = 0.4, cone = 0.0, cosine = 0.0;
  for (int i = 0; i < N; ++i) {
    double mu = (i + 0.5) / N;
    cosine += ss_pdf_cosine_hemisphere(mu) * 2.0 * SS_PI / N;
    cone += ss_pdf_uniform_cone(cos_max) * 2.0 * SS_PI * (1.0 - cos_max) / N;
  }
  cr_assert_float_eq(cosine, 1.0, 1e-9);
  cr_assert_float_eq(cone, 1.0, 1e-9);
  cr_assert_float_eq(ss_pdf_uniform_sphere() * 4.0 * SS_PI, 1.0, 1e-15);
  cr_assert_float_eq(ss_pdf_uniform_hemisphere() * 2.0 * SS_PI, 1.0, 1e-15);
  cr_assert_eq(ss_pdf_cosine_hemisphere(-0.5), 0.0, "no density below the horizon");
}
