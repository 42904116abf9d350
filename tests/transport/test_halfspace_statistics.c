/* The half-space reference's standard errors are honest: over many runs with
 * consecutive seeds, z = (R - exact) / stderr against Chandrasekhar's
 * index-matched isotropic albedo 1 - H(mu0) sqrt(1 - albedo) has mean 0 and
 * mean square 1. (With PCG32 seeded by the raw path index the errors were
 * 10-20 % too large: rms z 0.81 at albedo 0.5, 0.89 at 0.9.) */
#include "subsurf/halfspace.h"
#include "subsurf/sampling.h"

#include "transport/chandrasekhar.h"

#include <criterion/criterion.h>
#include <math.h>

#define PATHS 20000 /* 1000 batches of 20: z is normal to 0.1 % in variance */

typedef struct {
  double albedo, theta_deg;
  int runs;
} anchor;

/* Adds the z-scores of a.runs runs (seeds 0, 1, ...) at one anchor to
 * *sum_z and *sum_z2. */
static void add_z_scores(anchor a, double *sum_z, double *sum_z2) {
  h_function hf;
  h_solve(&hf, a.albedo);
  const double exact = h_albedo(&hf, cos(a.theta_deg * SS_PI / 180.0));
  for (int i = 0; i < a.runs; ++i) {
    ss_halfspace_params p;
    ss_halfspace_params_default(&p);
    p.medium.sigma_s = ss_rgb_gray(a.albedo);
    p.medium.sigma_a = ss_rgb_gray(1.0 - a.albedo);
    p.theta_i = a.theta_deg * SS_PI / 180.0;
    p.paths = PATHS;
    p.seed = (uint64_t)i;
    ss_halfspace_result *r = NULL;
    ss_error err;
    cr_assert_eq(ss_halfspace_run(&p, &r, &err), SS_OK, "%s", err.message);
    cr_assert_gt(r->reflectance.error, 0.0);
    double z = (r->reflectance.value - exact) / r->reflectance.error;
    *sum_z += z;
    *sum_z2 += z * z;
    ss_halfspace_result_destroy(r);
  }
}

/* Bounds at 3.5 standard deviations of the sample statistics for n normal
 * z-scores: mean z has sd 1/sqrt(n), mean z^2 has sd sqrt(2/n). */
Test(halfspace_statistics, z_scores_against_chandrasekhar_have_mean_zero_and_unit_variance) {
  const anchor anchors[] = {{0.5, 0.0, 600}, {0.9, 0.0, 400}};
  int n = 0;
  double sum_z = 0.0, sum_z2 = 0.0;
  for (int k = 0; k < 2; ++k) {
    add_z_scores(anchors[k], &sum_z, &sum_z2);
    n += anchors[k].runs;
  }
  double mean_z = sum_z / n, mean_z2 = sum_z2 / n;
  cr_expect(fabs(mean_z) < 3.5 / sqrt((double)n), "mean z %.4f over %d runs", mean_z, n);
  cr_log_info("mean z %.4f mean z2 %.4f rms %.4f", mean_z, mean_z2, sqrt(mean_z2));
  cr_expect(fabs(mean_z2 - 1.0) < 3.5 * sqrt(2.0 / n), "mean z^2 %.4f (rms z %.4f) over %d runs",
            mean_z2, sqrt(mean_z2), n);
}
