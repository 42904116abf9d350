/* Catmull-Rom splines: interpolation, exact integration, sampling against the
 * chi-square harness, inversion, and tensor weights in 2D/3D. */
#include "subsurf/catmull_rom.h"
#include "subsurf/chi2.h"

#include <criterion/criterion.h>
#include <math.h>

/* Non-uniform nodes like the BSSRDF radius grid (geometric growth). */
static void geometric_nodes(double *x, size_t n) {
  x[0] = 0.0;
  x[1] = 0.05;
  for (size_t i = 2; i < n; ++i) {
    x[i] = x[i - 1] * 1.3;
  }
}

Test(catmull_rom, weights_partition_unity_and_reproduce_linear_functions) {
  double x[12];
  geometric_nodes(x, 12);
  float f[12];
  for (size_t i = 0; i < 12; ++i) {
    f[i] = (float)(2.0 - 0.75 * x[i]);
  }
  for (double q = 0.0; q <= x[11]; q += x[11] / 97.0) {
    long off;
    double w[4];
    cr_assert(ss_cr_weights(12, x, q, &off, w));
    cr_assert_float_eq(w[0] + w[1] + w[2] + w[3], 1.0, 1e-12);
    /* Finite-difference derivatives are exact for lines, so is the spline. */
    cr_assert_float_eq(ss_cr_eval(12, x, f, 1, q), 2.0 - 0.75 * q, 1e-5, "at %g", q);
  }
  long off;
  double w[4];
  cr_assert_not(ss_cr_weights(12, x, -1e-9, &off, w));
  cr_assert_not(ss_cr_weights(12, x, x[11] * 1.0001, &off, w));
  cr_assert_not(ss_cr_weights(12, x, NAN, &off, w));
}

Test(catmull_rom, interpolates_the_nodes_exactly) {
  double x[10];
  geometric_nodes(x, 10);
  float f[10];
  for (size_t i = 0; i < 10; ++i) {
    f[i] = (float)exp(-x[i]) * (float)(1 + i % 3);
  }
  for (size_t i = 0; i < 10; ++i) {
    cr_assert_float_eq(ss_cr_eval(10, x, f, 1, x[i]), f[i], 1e-12);
  }
}

Test(catmull_rom, integral_is_exact_for_the_spline) {
  double x[16];
  geometric_nodes(x, 16);
  float f[32]; /* stride 2: the second slot holds garbage that must be ignored */
  for (size_t i = 0; i < 16; ++i) {
    f[2 * i] = (float)(x[i] * exp(-x[i]));
    f[2 * i + 1] = 1e30f;
  }
  double F[16];
  double total = ss_cr_integrate(16, x, f, 2, F);
  /* Simpson's rule is exact for cubics, and each sub-panel lies inside one
   * cubic piece. */
  for (size_t i = 0; i + 1 < 16; ++i) {
    double a = x[i], b = x[i + 1], sum = 0.0;
    int m = 8;
    for (int k = 0; k < m; ++k) {
      double u = a + (b - a) * k / m, v = a + (b - a) * (k + 1) / m;
      double fu = ss_cr_eval(16, x, f, 2, u), fv = ss_cr_eval(16, x, f, 2, v);
      sum += (v - u) / 6.0 * (fu + 4.0 * ss_cr_eval(16, x, f, 2, 0.5 * (u + v)) + fv);
    }
    cr_assert_float_eq(F[i + 1] - F[i], sum, 1e-9 * fabs(total));
  }
  cr_assert_float_eq(total, F[15], 0.0);
}

typedef struct {
  const double *x;
  size_t n;
  const float *f, *F;
  ss_cr_mix mix;
} sample_ctx;

static int sample_mix(void *c, double u1, double u2, double *x) {
  const sample_ctx *s = c;
  (void)u2;
  double pdf;
  *x = ss_cr_sample_mix(s->n, s->x, &s->mix, s->f, 1, s->F, u1, NULL, &pdf);
  return isfinite(*x) && pdf > 0.0;
}

static double pdf_mix(void *c, double x) {
  const sample_ctx *s = c;
  double total = ss_cr_mix_at(&s->mix, s->F, s->n, 1, s->n - 1), v = 0.0;
  for (int j = 0; j < s->mix.count; ++j) {
    v += s->mix.w[j] * ss_cr_eval(s->n, s->x, s->f + s->mix.row[j] * s->n, 1, x);
  }
  return v / total;
}

/* Two rows of a radial-profile-like table, sampled alone and mixed with
 * Catmull-Rom-like weights (one negative) as a 2D table lookup does. */
static void two_row_table(double *x, float *f, float *F, size_t n) {
  geometric_nodes(x, n);
  double Fd[64];
  for (size_t i = 0; i < n; ++i) {
    f[i] = (float)(x[i] * exp(-2.0 * x[i]));
    f[n + i] = (float)(x[i] * exp(-0.7 * x[i]) * (1.0 + 0.5 * sin(x[i])));
  }
  for (size_t row = 0; row < 2; ++row) {
    ss_cr_integrate(n, x, f + row * n, 1, Fd);
    for (size_t i = 0; i < n; ++i) {
      F[row * n + i] = (float)Fd[i];
    }
  }
}

Test(catmull_rom, sampling_matches_its_pdf_chi2) {
  enum { N = 24 };
  double x[N];
  float f[2 * N], F[2 * N];
  two_row_table(x, f, F, N);
  /* Cells aligned with the spline pieces (two per piece), so that the
   * harness's Gauss-Legendre cell integrals are exact for the cubics. */
  double edges[2 * (N - 1) + 1];
  for (int i = 0; i < N - 1; ++i) {
    edges[2 * i] = x[i];
    edges[2 * i + 1] = 0.5 * (x[i] + x[i + 1]);
  }
  edges[2 * (N - 1)] = x[N - 1] * (1.0 + 1e-12);
  double alpha = ss_chi2_sidak_alpha(0.01, 2);
  sample_ctx single = {x, N, f, F, {.count = 1, .row = {0}, .w = {1.0}}};
  ss_chi2_result res;
  ss_chi2_test_1d(sample_mix, pdf_mix, &single, edges, 2 * (N - 1), 200000, 7, &res);
  cr_assert(res.p_value > alpha, "single row: %s", res.message);
  cr_assert_eq(res.invalid, 0);
  cr_assert_float_eq(res.pdf_integral, 1.0, 1e-6, "%.9f", res.pdf_integral);

  sample_ctx mixed = {x, N, f, F, {.count = 2, .row = {0, 1}, .w = {-0.1, 1.1}}};
  ss_chi2_test_1d(sample_mix, pdf_mix, &mixed, edges, 2 * (N - 1), 200000, 8, &res);
  cr_assert(res.p_value > alpha, "mixed rows: %s", res.message);
  cr_assert_float_eq(res.pdf_integral, 1.0, 1e-6, "%.9f", res.pdf_integral);
}

Test(catmull_rom, sample_returns_spline_value_and_pdf) {
  enum { N = 20 };
  double x[N];
  float f[2 * N], F[2 * N];
  two_row_table(x, f, F, N);
  for (double u = 0.01; u < 1.0; u += 0.0973) {
    double fval, pdf;
    double s = ss_cr_sample(N, x, f, 1, F, u, &fval, &pdf);
    cr_assert_float_eq(fval, ss_cr_eval(N, x, f, 1, s), 1e-9);
    cr_assert_float_eq(pdf, fval / F[N - 1], 1e-9);
  }
}

Test(catmull_rom, invert_undoes_eval_of_monotone_data) {
  double x[30], v[30];
  float vf[30];
  for (size_t i = 0; i < 30; ++i) {
    x[i] = i / 29.0;
    v[i] = 1.0 - exp(-4.0 * x[i]) + 0.1 * x[i];
    vf[i] = (float)v[i];
  }
  for (double q = 0.013; q < 1.0; q += 0.0417) {
    double y = ss_cr_eval(30, x, vf, 1, q);
    cr_assert_float_eq(ss_cr_invert(30, x, v, y), q, 1e-6, "q = %g", q);
  }
  cr_assert_eq(ss_cr_invert(30, x, v, -1.0), x[0]);
  cr_assert_eq(ss_cr_invert(30, x, v, 5.0), x[29]);
}

Test(catmull_rom, tensor_weights_are_products_of_1d_weights_in_2d_and_3d) {
  double a[7], b[5], c[9];
  for (int i = 0; i < 7; ++i)
    a[i] = i * i * 0.1;
  for (int i = 0; i < 5; ++i)
    b[i] = i;
  geometric_nodes(c, 9);
  ss_cr_axis axes[3] = {{7, a}, {5, b}, {9, c}};
  /* A function linear in each coordinate is reproduced exactly. */
  float table[7 * 5 * 9];
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 9; ++k)
        table[(i * 5 + j) * 9 + k] = (float)(1.0 + a[i] - 0.5 * b[j] + 0.25 * c[k]);
  size_t idx[64];
  double w[64];
  double q[3] = {1.7, 2.2, 0.31};
  int count = ss_cr_tensor(3, axes, q, idx, w);
  cr_assert(count > 0 && count <= 64);
  double v = 0.0, wsum = 0.0;
  for (int m = 0; m < count; ++m) {
    v += w[m] * table[idx[m]];
    wsum += w[m];
  }
  cr_assert_float_eq(wsum, 1.0, 1e-12);
  cr_assert_float_eq(v, 1.0 + 1.7 - 0.5 * 2.2 + 0.25 * 0.31, 1e-5);

  /* 2D: the table's (a, c) slice at j = 0 equals the 1D evaluations. */
  float slice[7 * 9];
  for (int i = 0; i < 7; ++i)
    for (int k = 0; k < 9; ++k)
      slice[i * 9 + k] = (float)(sin(a[i]) * exp(-c[k]));
  ss_cr_axis ax2[2] = {{7, a}, {9, c}};
  double q2[2] = {0.05, 0.4};
  count = ss_cr_tensor(2, ax2, q2, idx, w);
  v = 0.0;
  for (int m = 0; m < count; ++m)
    v += w[m] * slice[idx[m]];
  long off;
  double wa[4];
  cr_assert(ss_cr_weights(7, a, q2[0], &off, wa));
  double expect = 0.0;
  for (int m = 0; m < 4; ++m) {
    if (wa[m] != 0.0)
      expect += wa[m] * ss_cr_eval(9, c, slice + (off + m) * 9, 1, q2[1]);
  }
  cr_assert_float_eq(v, expect, 1e-12);
  double out[3] = {10.0, 0.0, 0.0};
  cr_assert_eq(ss_cr_tensor(3, axes, out, idx, w), -1);
}

/* The prepared grid gives ss_cr_weights' spline (interval lookup by buckets
 * on geometric and uniform nodes, by bisection on others), its taps inside
 * the table, and with a mirror ghost the ghost's weight on node n - 3. */
Test(catmull_rom, prepared_grid_weights_equal_the_direct_weights) {
  double geo[40], uni[11], crowd[30];
  geometric_nodes(geo, 40);
  for (int i = 0; i < 11; ++i) {
    uni[i] = i * 0.1745329;
  }
  for (int i = 0; i < 30; ++i) {
    crowd[i] = 1.0 - exp(-0.3 * i); /* nodes crowding near 1: bisection */
  }
  struct {
    size_t n;
    const double *x;
    int ghost, buckets;
  } cases[] = {{40, geo, 0, 1}, {11, uni, 0, 1}, {11, uni, 1, 1}, {30, crowd, 0, 0}};
  for (int c = 0; c < 4; ++c) {
    ss_cr_grid g;
    size_t n = cases[c].n;
    const double *x = cases[c].x;
    cr_assert(ss_cr_grid_init(&g, n, x, cases[c].ghost));
    cr_assert_eq(g.bucket != NULL, cases[c].buckets, "case %d", c);
    double top = cases[c].ghost ? x[n - 2] : x[n - 1];
    for (int q = 0; q <= 5000; ++q) {
      double v = fmin(top, top * q / 5000.0) * (q % 7 == 3 ? 0.999999 : 1.0);
      if (q % 11 == 0) {
        v = x[(size_t)q / 11 % (cases[c].ghost ? n - 1 : n)];
      }
      cr_assert_eq(ss_cr_grid_find(&g, v), ss_cr_find_interval(n, x, v), "case %d x %g", c, v);
      long off;
      double w[4], gw[4], full[64] = {0}, gfull[64] = {0};
      size_t base;
      cr_assert(ss_cr_weights(n, x, v, &off, w), "case %d x %.17g", c, v);
      cr_assert(ss_cr_grid_weights(&g, v, &base, gw));
      cr_assert_leq(base + 4, cases[c].ghost ? n - 1 : n);
      for (int k = 0; k < 4; ++k) {
        if (w[k] != 0.0) {
          size_t j = (size_t)(off + k);
          full[cases[c].ghost && j == n - 1 ? n - 3 : j] += w[k];
        }
        gfull[base + (size_t)k] += gw[k];
      }
      for (size_t j = 0; j < n; ++j) {
        cr_assert_float_eq(gfull[j], full[j], 1e-12, "case %d x %g node %zu", c, v, j);
      }
    }
    cr_assert_not(ss_cr_grid_weights(&g, -1e-9, &(size_t){0}, (double[4]){0}));
    cr_assert_not(ss_cr_grid_weights(&g, top * 1.0001, &(size_t){0}, (double[4]){0}));
    cr_assert_not(ss_cr_grid_weights(&g, NAN, &(size_t){0}, (double[4]){0}));
    ss_cr_grid_free(&g);
  }
}
