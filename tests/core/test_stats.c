/* Welford's running statistics equal the two-pass formulas, merging equals
 * sequential accumulation, and the batch tally's standard error estimates the
 * true standard error of its mean. */
#include "subsurf/rng.h"
#include "subsurf/stats.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

static double two_pass_mean(const double *x, size_t n) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    s += x[i];
  }
  return s / (double)n;
}

static double two_pass_variance(const double *x, size_t n) {
  double m = two_pass_mean(x, n), s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    s += (x[i] - m) * (x[i] - m);
  }
  return s / (double)(n - 1);
}

/* A large offset makes the naive sum-of-squares formula lose every digit;
 * Welford keeps them. */
Test(stats, welford_matches_two_pass_even_with_a_large_offset) {
  enum { N = 10000 };
  static double x[N];
  ss_rng rng;
  ss_rng_seed(&rng, 11u, 0u);
  const double offsets[2] = {0.0, 1e9};
  for (int k = 0; k < 2; ++k) {
    ss_running_stats s;
    ss_running_stats_init(&s);
    for (int i = 0; i < N; ++i) {
      x[i] = offsets[k] + ss_rng_uniform(&rng);
      ss_running_stats_add(&s, x[i]);
    }
    double var = two_pass_variance(x, N);
    cr_assert_eq(s.n, (uint64_t)N);
    cr_assert_float_eq(s.mean, two_pass_mean(x, N), 1e-12 * fmax(1.0, offsets[k]));
    cr_assert_float_eq(ss_running_stats_variance(&s), var, 1e-6 * var, "offset %g: %.10g vs %.10g",
                       offsets[k], ss_running_stats_variance(&s), var);
    cr_assert_float_eq(ss_running_stats_stderr(&s), sqrt(var / N), 1e-6 * sqrt(var / N));
  }
}

Test(stats, merge_equals_sequential) {
  ss_rng rng;
  ss_rng_seed(&rng, 12u, 0u);
  ss_running_stats all, a, b, empty;
  ss_running_stats_init(&all);
  ss_running_stats_init(&a);
  ss_running_stats_init(&b);
  ss_running_stats_init(&empty);
  for (int i = 0; i < 3000; ++i) {
    double v = 5.0 + 3.0 * ss_rng_uniform(&rng) * ss_rng_uniform(&rng);
    ss_running_stats_add(&all, v);
    ss_running_stats_add(i < 1000 ? &a : &b, v);
  }
  ss_running_stats_merge(&a, &b);
  cr_assert_eq(a.n, all.n);
  cr_assert_float_eq(a.mean, all.mean, 1e-13);
  cr_assert_float_eq(a.m2, all.m2, 1e-10 * all.m2);
  /* Merging an empty accumulator changes nothing; merging into one copies. */
  ss_running_stats_merge(&a, &empty);
  cr_assert_eq(a.n, all.n);
  ss_running_stats_merge(&empty, &all);
  cr_assert_eq(empty.n, all.n);
  cr_assert_float_eq(empty.mean, all.mean, 1e-15);
  cr_assert_float_eq(empty.m2, all.m2, 1e-12 * all.m2);
}

Test(stats, degenerate_counts_have_zero_spread) {
  ss_running_stats s;
  ss_running_stats_init(&s);
  cr_assert_eq(ss_running_stats_variance(&s), 0.0);
  ss_running_stats_add(&s, 4.0);
  cr_assert_eq(s.mean, 4.0);
  cr_assert_eq(ss_running_stats_variance(&s), 0.0);
  cr_assert_eq(ss_running_stats_stderr(&s), 0.0);
}

/* Each path scores K ~ Poisson(lambda) hits of weight w in bin 0 (one path
 * adds to the bin many times) and one uniform value in bin 1. Per-path sums
 * have mean w lambda and variance w^2 lambda, and mean 1/2 and variance 1/12. */
static uint64_t poisson(ss_rng *rng, double lambda) {
  double l = exp(-lambda), p = 1.0;
  uint64_t k = 0;
  do {
    ++k;
    p *= ss_rng_uniform(rng);
  } while (p > l);
  return k - 1;
}

static void run_tally(ss_batch_tally *t, ss_rng *rng, int batches, int paths_lo, int paths_hi,
                      double lambda, double w) {
  for (int b = 0; b < batches; ++b) {
    int paths = paths_lo + (int)(ss_rng_uniform(rng) * (paths_hi - paths_lo + 1));
    double sum[2] = {0.0, 0.0};
    for (int p = 0; p < paths; ++p) {
      sum[0] += w * (double)poisson(rng, lambda);
      sum[1] += ss_rng_uniform(rng);
    }
    ss_batch_tally_add_batch(t, sum, (uint64_t)paths);
  }
}

Test(stats, batch_tally_stderr_is_within_ten_percent_of_truth) {
  const double lambda = 3.0, w = 0.7;
  ss_batch_tally t;
  cr_assert_eq(ss_batch_tally_init(&t, 2), 0);
  ss_rng rng;
  ss_rng_seed(&rng, 13u, 0u);
  /* 1000 batches of 50..150 paths: the stderr estimate has relative spread
   * about 1/sqrt(2 * 999) = 2.2%, so 10% is 4.5 sigma. */
  run_tally(&t, &rng, 1000, 50, 150, lambda, w);
  double n = (double)t.paths;
  cr_assert_eq(t.batches, 1000u);
  double se0 = w * sqrt(lambda / n), se1 = sqrt(1.0 / 12.0 / n);
  cr_assert_float_eq(ss_batch_tally_stderr(&t, 0), se0, 0.1 * se0, "bin 0: %g vs %g",
                     ss_batch_tally_stderr(&t, 0), se0);
  cr_assert_float_eq(ss_batch_tally_stderr(&t, 1), se1, 0.1 * se1, "bin 1: %g vs %g",
                     ss_batch_tally_stderr(&t, 1), se1);
  cr_assert_float_eq(ss_batch_tally_mean(&t, 0), w * lambda, 4.5 * se0);
  cr_assert_float_eq(ss_batch_tally_mean(&t, 1), 0.5, 4.5 * se1);
  ss_batch_tally_free(&t);
}

/* Over 400 independent tallies the interval mean +- 1.96 stderr covers the
 * true mean about 95% of the time: the count of misses is Binomial(400,
 * 0.05), mean 20, sd 4.4; accept 6..38 (beyond 3 sd either side, allowing the
 * t-distribution's slightly heavier tails with 40 batches). */
Test(stats, batch_tally_intervals_cover_the_true_mean) {
  const double lambda = 2.0, w = 1.0;
  ss_rng rng;
  ss_rng_seed(&rng, 14u, 0u);
  int misses = 0;
  for (int r = 0; r < 400; ++r) {
    ss_batch_tally t;
    cr_assert_eq(ss_batch_tally_init(&t, 2), 0);
    run_tally(&t, &rng, 40, 20, 30, lambda, w);
    double m = ss_batch_tally_mean(&t, 0), se = ss_batch_tally_stderr(&t, 0);
    misses += fabs(m - w * lambda) > 1.96 * se;
    ss_batch_tally_free(&t);
  }
  cr_assert(misses >= 6 && misses <= 38, "%d of 400 intervals miss", misses);
}

Test(stats, batch_tally_needs_two_batches_for_an_error) {
  ss_batch_tally t;
  cr_assert_eq(ss_batch_tally_init(&t, 1), 0);
  double one = 2.0;
  ss_batch_tally_add_batch(&t, &one, 4);
  cr_assert_float_eq(ss_batch_tally_mean(&t, 0), 0.5, 1e-15);
  cr_assert_eq(ss_batch_tally_stderr(&t, 0), 0.0);
  ss_batch_tally_add_batch(&t, &one, 0);
  cr_assert_eq(t.batches, 1u, "an empty batch is ignored");
  ss_batch_tally_free(&t);
}
