/* PCG32 streams: the reference sequence, determinism, distinct and
 * uncorrelated streams, O(log k) advance equal to k draws, and uniformity. */
#include "subsurf/chi2.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>

/* O'Neill's pcg32-demo seeds pcg32_srandom_r(&rng, 42, 54) and prints these
 * first six outputs. */
Test(rng, matches_the_pcg32_reference_sequence) {
  const uint32_t expected[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                                0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
  ss_rng rng;
  ss_rng_seed(&rng, 42u, 54u);
  for (int i = 0; i < 6; ++i) {
    uint32_t v = ss_rng_next_u32(&rng);
    cr_assert_eq(v, expected[i], "output %d: 0x%08x, expected 0x%08x", i, v, expected[i]);
  }
}

Test(rng, seeding_is_deterministic) {
  ss_rng a, b, c;
  ss_rng_seed(&a, 7u, 3u);
  ss_rng_seed(&b, 7u, 3u);
  ss_rng_seed(&c, 8u, 3u);
  int same_as_other_seed = 0;
  for (int i = 0; i < 1000; ++i) {
    uint32_t x = ss_rng_next_u32(&a), y = ss_rng_next_u32(&b), z = ss_rng_next_u32(&c);
    cr_assert_eq(x, y, "draw %d differs for the same seed and stream", i);
    same_as_other_seed += x == z;
  }
  cr_assert_lt(same_as_other_seed, 3, "another seed gives another sequence");
}

/* No stream is a shifted copy of another (lags up to 64), and draws of
 * neighbouring streams are uncorrelated: the sample correlation of n pairs is
 * about N(0, 1/n), tested at 4.5 sigma. */
#define STREAMS 16
#define DRAWS 20000

Test(rng, streams_are_distinct_and_uncorrelated) {
  static uint32_t seq[STREAMS][DRAWS];
  for (int s = 0; s < STREAMS; ++s) {
    ss_rng rng;
    ss_rng_seed(&rng, 1234u, (uint64_t)s);
    for (int i = 0; i < DRAWS; ++i) {
      seq[s][i] = ss_rng_next_u32(&rng);
    }
  }
  for (int a = 0; a < STREAMS; ++a) {
    for (int b = a + 1; b < STREAMS; ++b) {
      for (int lag = -64; lag <= 64; ++lag) {
        int equal = 0;
        for (int i = 64; i < 64 + 256; ++i) {
          equal += seq[a][i] == seq[b][i + lag];
        }
        cr_assert_lt(equal, 4, "stream %d equals stream %d shifted by %d", a, b, lag);
      }
    }
  }
  for (int a = 0; a + 1 < STREAMS; ++a) {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (int i = 0; i < DRAWS; ++i) {
      double x = seq[a][i] * 0x1p-32, y = seq[a + 1][i] * 0x1p-32;
      sx += x;
      sy += y;
      sxx += x * x;
      syy += y * y;
      sxy += x * y;
    }
    double n = DRAWS;
    double r = (sxy - sx * sy / n) / sqrt((sxx - sx * sx / n) * (syy - sy * sy / n));
    cr_assert_lt(fabs(r), 4.5 / sqrt(n), "streams %d and %d correlate: r = %g", a, a + 1, r);
  }
}

Test(rng, advance_by_k_equals_k_draws) {
  const uint64_t ks[] = {0, 1, 2, 3, 7, 64, 1000, 123457};
  for (size_t j = 0; j < sizeof ks / sizeof ks[0]; ++j) {
    ss_rng a, b;
    ss_rng_seed(&a, 99u, 5u);
    ss_rng_seed(&b, 99u, 5u);
    for (uint64_t i = 0; i < ks[j]; ++i) {
      ss_rng_next_u32(&a);
    }
    ss_rng_advance(&b, ks[j]);
    cr_assert_eq(a.state, b.state, "state after %llu steps", (unsigned long long)ks[j]);
    for (int i = 0; i < 4; ++i) {
      cr_assert_eq(ss_rng_next_u32(&a), ss_rng_next_u32(&b));
    }
  }
}

Test(rng, advance_wraps_around_the_period) {
  /* Advancing by 2^64 returns to the same state (period of the LCG). */
  ss_rng a, b;
  ss_rng_seed(&a, 3u, 11u);
  b = a;
  ss_rng_advance(&b, UINT64_C(1) << 63);
  cr_assert_neq(a.state, b.state);
  ss_rng_advance(&b, UINT64_C(1) << 63);
  cr_assert_eq(a.state, b.state);
}

static int draw_uniform(void *ctx, double u1, double u2, double *x) {
  *x = ss_rng_uniform(ctx);
  return 1;
}

static double pdf_uniform(void *ctx, double x) { return x >= 0.0 && x < 1.0 ? 1.0 : 0.0; }

Test(rng, uniform_is_uniform_on_the_unit_interval) {
  enum { BINS = 1000 };
  double edges[BINS + 1];
  for (int i = 0; i <= BINS; ++i) {
    edges[i] = (double)i / BINS;
  }
  ss_rng rng;
  ss_rng_seed(&rng, 2024u, 77u);
  ss_chi2_result res;
  ss_chi2_test_1d(draw_uniform, pdf_uniform, &rng, edges, BINS, 2000000, 1, &res);
  cr_assert_eq(res.invalid, 0u, "every draw lies in [0, 1)");
  cr_assert_gt(res.p_value, 0.01, "%s", res.message);
  /* Extremes: 2^-32 resolution, never 1. */
  ss_rng_seed(&rng, 5u, 0u);
  double lo = 1.0, hi = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    double u = ss_rng_uniform(&rng);
    lo = fmin(lo, u);
    hi = fmax(hi, u);
  }
  cr_assert(lo >= 0.0 && lo < 1e-5, "min %g", lo);
  cr_assert(hi < 1.0 && hi > 1.0 - 1e-5, "max %.17g", hi);
}

Test(rng, hash_spreads_consecutive_inputs) {
  /* Consecutive inputs flip about half of the 64 output bits. */
  double flips = 0.0;
  for (uint64_t i = 0; i < 10000; ++i) {
    flips += __builtin_popcountll(ss_hash64(i) ^ ss_hash64(i + 1));
  }
  cr_assert_float_eq(flips / 10000.0, 32.0, 0.3, "mean bit flips %g", flips / 10000.0);
}

Test(rng, item_generators_of_nearby_seeds_and_items_do_not_repeat) {
  /* Seeded directly with (seed, i), item i + 1 of seed s starts like item i
   * of seed s + 2; the items' generators must not repeat each other. */
  int same = 0;
  for (uint64_t s = 0; s < 8; ++s) {
    for (uint64_t i = 0; i < 1000; ++i) {
      ss_rng a, b;
      ss_rng_seed_item(&a, s, i + 1);
      ss_rng_seed_item(&b, s + 2, i);
      same += ss_rng_next_u32(&a) == ss_rng_next_u32(&b);
    }
  }
  cr_assert_leq(same, 2, "%d of 8000 first draws repeat", same);
}
