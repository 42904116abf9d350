/* The piecewise-constant 2D distribution: its samples follow the density it
 * reports (chi-square over cells finer than its own), black rows and
 * columns are never sampled, and the density integrates to one. */
#include "subsurf/chi2.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>

#define NU 12
#define NV 7

/* A lopsided function with a black row and a black column. */
static double func_at(size_t u, size_t v) {
  if (v == 2 || u == 5) {
    return 0.0;
  }
  return 0.1 + (double)((u * 7 + v * 3) % 11) + (u == 9 && v == 4 ? 40.0 : 0.0);
}

static int sample(void *ctx, double u1, double u2, double u3, double *x, double *y) {
  (void)u3;
  double pdf;
  ss_distribution2d_sample(ctx, u1, u2, x, y, &pdf);
  return pdf > 0.0;
}

static double pdf(void *ctx, double x, double y) { return ss_distribution2d_pdf(ctx, x, y); }

Test(distribution2d, samples_follow_the_reported_density) {
  double func[NU * NV];
  for (size_t v = 0; v < NV; ++v) {
    for (size_t u = 0; u < NU; ++u) {
      func[v * NU + u] = func_at(u, v);
    }
  }
  ss_distribution2d d;
  cr_assert_eq(ss_distribution2d_init(&d, func, NU, NV), 0);
  /* Three bins per cell in u, two in v: a density off by a cell shows. */
  double xe[3 * NU + 1], ye[2 * NV + 1];
  for (size_t i = 0; i <= 3 * NU; ++i) {
    xe[i] = (double)i / (3 * NU);
  }
  for (size_t i = 0; i <= 2 * NV; ++i) {
    ye[i] = (double)i / (2 * NV);
  }
  ss_chi2_result res;
  ss_chi2_test_2d(sample, pdf, &d, xe, 3 * NU, ye, 2 * NV, 400000, 11, &res);
  cr_expect_gt(res.p_value, 0.01, "%s", res.message);
  cr_expect_float_eq(res.pdf_integral, 1.0, 1e-9, "integral %.12f", res.pdf_integral);
  cr_expect_eq(res.invalid, 0);
  ss_rng rng;
  ss_rng_seed(&rng, 5, 6);
  for (int i = 0; i < 100000; ++i) {
    double u, v, p;
    ss_distribution2d_sample(&d, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &u, &v, &p);
    size_t cu = (size_t)(u * NU), cv = (size_t)(v * NV);
    cr_assert(cu < NU && cv < NV && func_at(cu, cv) > 0.0, "sampled a black cell (%zu, %zu)", cu,
              cv);
    cr_assert_float_eq(p, ss_distribution2d_pdf(&d, u, v), 1e-12 * p);
  }
  ss_distribution2d_free(&d);
}

Test(distribution2d, refuses_an_all_black_function) {
  double func[6] = {0, 0, 0, 0, 0, 0};
  ss_distribution2d d;
  cr_expect_eq(ss_distribution2d_init(&d, func, 3, 2), -1);
  cr_expect_null(d.rows);
}
