/* The per-pixel trimmed mean (Frederickx2017 sec. 7.3). */
#include "subsurf/rng.h"
#include "subsurf/trimmed_mean.h"

#include <criterion/criterion.h>
#include <math.h>

Test(trimmed_mean, without_trimming_is_the_mean) {
  double v[] = {3.0, -1.0, 10.0, 4.0};
  cr_expect_float_eq(ss_trimmed_mean(v, 4, 0.0), 4.0, 1e-15);
  double w[] = {2.0, 9.0, 1.0, 5.0, 3.0};
  cr_expect_float_eq(ss_trimmed_mean(w, 5, 0.19), 4.0, 1e-15); /* floor(0.95) = 0 dropped */
}

Test(trimmed_mean, drops_floor_trim_k_from_each_end) {
  double v[] = {100.0, 1.0, 2.0, 3.0, -50.0, 4.0, 5.0, 6.0, 7.0, 8.0};
  cr_expect_eq(ss_trimmed_count(10, 0.1), 1);
  /* -50 and 100 dropped: mean of 1..8. */
  cr_expect_float_eq(ss_trimmed_mean(v, 10, 0.1), 4.5, 1e-15);
}

Test(trimmed_mean, refuses_a_trim_that_keeps_nothing) {
  double v[] = {1.0, 2.0};
  cr_expect(isnan(ss_trimmed_mean(v, 2, 0.5)));
  cr_expect(isnan(ss_trimmed_mean(v, 0, 0.0)));
  float a[1] = {1.0f}, out[1];
  const float *passes[] = {a};
  ss_error err;
  cr_expect_eq(ss_trimmed_mean_passes(passes, 1, 1, -0.1, out, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "trim") != NULL, "%s", err.message);
  cr_expect_eq(ss_trimmed_mean_passes(passes, 0, 1, 0.0, out, &err), SS_ERR_INVALID_ARGUMENT);
}

/* Per element over passes; an outlier pass at one pixel is removed. */
Test(trimmed_mean, works_per_element_over_passes) {
  enum { K = 20, N = 6 };
  float data[K][N];
  const float *passes[K];
  for (int k = 0; k < K; ++k) {
    for (int i = 0; i < N; ++i) {
      data[k][i] = (float)(i + 0.01 * (k - 9.5));
    }
    passes[k] = data[k];
  }
  data[7][3] = 1e6f;
  float out[N];
  cr_assert_eq(ss_trimmed_mean_passes(passes, K, N, 0.05, out, NULL), SS_OK);
  for (int i = 0; i < N; ++i) {
    cr_expect(fabs(out[i] - i) < (i == 3 ? 0.02 : 1e-6), "pixel %d: %g", i, out[i]);
  }
}

/* For a symmetric distribution the trimmed mean is unbiased, and with rare
 * large outliers its error is far below the mean's. Seeded; tolerances are
 * 4 standard errors of the mean over 2000 trials. */
Test(trimmed_mean, is_unbiased_for_symmetric_noise_and_robust_to_outliers) {
  ss_rng rng;
  ss_rng_seed(&rng, 7, 3);
  enum { TRIALS = 2000, K = 40 };
  double sum_t = 0.0, sum_t2 = 0.0, sq_plain = 0.0, sq_trim = 0.0;
  for (int t = 0; t < TRIALS; ++t) {
    double v[K], w[K], mean = 0.0;
    for (int k = 0; k < K; ++k) {
      double u = ss_rng_uniform(&rng) - 0.5; /* symmetric about 0 */
      v[k] = u;
      /* A heavy outlier in 1% of the passes (one sign, as from a rare path);
       * more than two in a trial (0.8% of trials) survive the trim. */
      w[k] = u + (ss_rng_uniform(&rng) < 0.01 ? 1e3 : 0.0);
      mean += w[k] / K;
    }
    double tv = ss_trimmed_mean(v, K, 0.05), tw = ss_trimmed_mean(w, K, 0.05);
    sum_t += tv;
    sum_t2 += tv * tv;
    sq_plain += mean * mean;
    sq_trim += tw * tw;
  }
  double m = sum_t / TRIALS, se = sqrt((sum_t2 / TRIALS - m * m) / TRIALS);
  cr_expect(fabs(m) < 4.0 * se, "bias %g (standard error %g)", m, se);
  cr_expect(sq_trim < 0.1 * sq_plain, "mean square %g vs untrimmed %g", sq_trim / TRIALS,
            sq_plain / TRIALS);
}
