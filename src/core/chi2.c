#include "subsurf/chi2.h"

#include "subsurf/sampling.h"

#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Gauss-Legendre nodes and weights on [0, 1], 5 points: integrates the pdf
 * over each cell exactly for polynomials of degree 9. */
static const double gl_x[5] = {0.04691007703066800, 0.23076534494715845, 0.5, 0.76923465505284155,
                               0.95308992296933200};
static const double gl_w[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                               0.23931433524968324, 0.11846344252809454};

static int compare_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Pearson's statistic with pooling of cells expected below 5 (pbrt-v4). */
static void chi2_finish(const double *observed, const double *expected, size_t n, uint64_t samples,
                        ss_chi2_result *res) {
  double *pairs = malloc(2 * n * sizeof *pairs);
  if (!pairs) {
    res->p_value = 0.0;
    snprintf(res->message, sizeof res->message, "out of memory");
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    pairs[2 * i] = expected[i];
    pairs[2 * i + 1] = observed[i];
  }
  qsort(pairs, n, 2 * sizeof *pairs, compare_double);
  double stat = 0.0, pool_e = 0.0, pool_o = 0.0;
  int dof = 0;
  for (size_t i = 0; i < n; ++i) {
    double e = pairs[2 * i], o = pairs[2 * i + 1];
    if (e == 0.0) {
      if (o > (double)samples * 1e-5) {
        res->p_value = 0.0;
        snprintf(res->message, sizeof res->message,
                 "%.0f samples fell in a cell where the pdf integrates to zero", o);
        free(pairs);
        return;
      }
      continue;
    }
    if (e < 5.0) {
      pool_e += e;
      pool_o += o;
      continue;
    }
    stat += (o - e) * (o - e) / e;
    ++dof;
  }
  if (pool_e > 0.0) {
    stat += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
    ++dof;
  }
  dof -= 1;
  res->statistic = stat;
  res->dof = dof;
  res->p_value = dof > 0 ? gsl_cdf_chisq_Q(stat, dof) : 1.0;
  snprintf(res->message, sizeof res->message, "chi2 = %.2f, dof = %d, p = %.4g, pdf integral %.6f",
           stat, dof, res->p_value, res->pdf_integral);
  free(pairs);
}

/* Zeroed observed/expected cell counts and a reset result; 0 when out of
 * memory (the result then says so and fails). */
static int cells_alloc(size_t n, double **observed, double **expected, ss_chi2_result *res) {
  *observed = calloc(n, sizeof **observed);
  *expected = calloc(n, sizeof **expected);
  res->invalid = 0;
  res->pdf_integral = 0.0;
  if (!*observed || !*expected) {
    free(*observed);
    free(*expected);
    res->p_value = 0.0;
    snprintf(res->message, sizeof res->message, "out of memory");
    return 0;
  }
  return 1;
}

static void cells_finish(double *observed, double *expected, size_t n, uint64_t samples,
                         ss_chi2_result *res) {
  chi2_finish(observed, expected, n, samples, res);
  free(observed);
  free(expected);
}

void ss_chi2_sphere_options_default(ss_chi2_sphere_options *o) {
  o->theta_bins = 80;
  o->phi_bins = 160;
  o->theta_max = SS_PI;
  o->theta_power = 1.0;
  o->samples = 1000000;
  o->seed = 1;
}

static double theta_edge(const ss_chi2_sphere_options *o, size_t k) {
  return o->theta_max * pow((double)k / (double)o->theta_bins, o->theta_power);
}

static size_t find_bin(const double *edges, size_t n, double x) {
  size_t lo = 0, hi = n;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (edges[mid] <= x) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

/* The sphere test is the 2D test in (theta, phi), with the solid-angle pdf
 * times sin(theta) as the density per unit theta * phi. */
typedef struct {
  ss_chi2_sample_dir_fn sample;
  ss_chi2_pdf_dir_fn pdf;
  void *ctx;
} sphere_adapter;

static int sphere_sample(void *c, double u1, double u2, double u3, double *theta, double *phi) {
  const sphere_adapter *s = c;
  ss_vec3 d;
  if (!s->sample(s->ctx, u1, u2, u3, &d)) {
    return 0;
  }
  *theta = acos(fmax(-1.0, fmin(1.0, d.z / ss_vec3_length(d))));
  *phi = atan2(d.y, d.x);
  if (*phi < 0.0) {
    *phi += 2.0 * SS_PI;
  }
  return 1;
}

static double sphere_pdf(void *c, double theta, double phi) {
  const sphere_adapter *s = c;
  return s->pdf(s->ctx, ss_spherical_direction(cos(theta), phi)) * sin(theta);
}

void ss_chi2_test_sphere(ss_chi2_sample_dir_fn sample, ss_chi2_pdf_dir_fn pdf, void *ctx,
                         const ss_chi2_sphere_options *opt, ss_chi2_result *res) {
  size_t nt = opt->theta_bins, np = opt->phi_bins;
  double *theta_edges = malloc((nt + 1) * sizeof *theta_edges);
  double *phi_edges = malloc((np + 1) * sizeof *phi_edges);
  if (!theta_edges || !phi_edges) {
    res->p_value = 0.0;
    snprintf(res->message, sizeof res->message, "out of memory");
  } else {
    for (size_t k = 0; k <= nt; ++k) {
      theta_edges[k] = theta_edge(opt, k);
    }
    for (size_t k = 0; k <= np; ++k) {
      phi_edges[k] = 2.0 * SS_PI * (double)k / (double)np;
    }
    sphere_adapter adapter = {sample, pdf, ctx};
    ss_chi2_test_2d(sphere_sample, sphere_pdf, &adapter, theta_edges, nt, phi_edges, np,
                    opt->samples, opt->seed, res);
  }
  free(theta_edges);
  free(phi_edges);
}

void ss_chi2_test_1d(ss_chi2_sample_1d_fn sample, ss_chi2_pdf_1d_fn pdf, void *ctx,
                     const double *edges, size_t n, uint64_t samples, uint64_t seed,
                     ss_chi2_result *res) {
  double *observed, *expected;
  if (!cells_alloc(n, &observed, &expected, res)) {
    return;
  }
  ss_rng rng;
  ss_rng_seed(&rng, seed, 0x1d);
  for (uint64_t i = 0; i < samples; ++i) {
    double x;
    if (!sample(ctx, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &x) || !(x >= edges[0]) ||
        !(x < edges[n])) {
      res->invalid++;
      continue;
    }
    observed[find_bin(edges, n, x)] += 1.0;
  }
  for (size_t i = 0; i < n; ++i) {
    double dx = edges[i + 1] - edges[i], sum = 0.0;
    /* 4 x 5 Gauss-Legendre points per cell: pdfs with kinks inside a cell
     * (piecewise tables) are still integrated to ~1e-7. */
    for (int s = 0; s < 4; ++s) {
      for (int a = 0; a < 5; ++a) {
        sum += gl_w[a] * pdf(ctx, edges[i] + ((double)s + gl_x[a]) * 0.25 * dx);
      }
    }
    double integral = sum * 0.25 * dx;
    res->pdf_integral += integral;
    expected[i] = integral * (double)samples;
  }
  cells_finish(observed, expected, n, samples, res);
}

void ss_chi2_test_2d(ss_chi2_sample_2d_fn sample, ss_chi2_pdf_2d_fn pdf, void *ctx,
                     const double *x_edges, size_t nx, const double *y_edges, size_t ny,
                     uint64_t samples, uint64_t seed, ss_chi2_result *res) {
  size_t n = nx * ny;
  double *observed, *expected;
  if (!cells_alloc(n, &observed, &expected, res)) {
    return;
  }
  ss_rng rng;
  ss_rng_seed(&rng, seed, 0x2d);
  for (uint64_t i = 0; i < samples; ++i) {
    double x, y;
    double u1 = ss_rng_uniform(&rng), u2 = ss_rng_uniform(&rng), u3 = ss_rng_uniform(&rng);
    if (!sample(ctx, u1, u2, u3, &x, &y) || !(x >= x_edges[0]) || !(x < x_edges[nx]) ||
        !(y >= y_edges[0]) || !(y < y_edges[ny])) {
      res->invalid++;
      continue;
    }
    observed[find_bin(x_edges, nx, x) * ny + find_bin(y_edges, ny, y)] += 1.0;
  }
  for (size_t i = 0; i < nx; ++i) {
    double dx = x_edges[i + 1] - x_edges[i];
    for (size_t j = 0; j < ny; ++j) {
      double dy = y_edges[j + 1] - y_edges[j], sum = 0.0;
      for (int a = 0; a < 5; ++a) {
        for (int b = 0; b < 5; ++b) {
          sum += gl_w[a] * gl_w[b] * pdf(ctx, x_edges[i] + gl_x[a] * dx, y_edges[j] + gl_x[b] * dy);
        }
      }
      double integral = sum * dx * dy;
      res->pdf_integral += integral;
      expected[i * ny + j] = integral * (double)samples;
    }
  }
  cells_finish(observed, expected, n, samples, res);
}

double ss_chi2_sidak_alpha(double alpha, int tests) {
  return 1.0 - pow(1.0 - alpha, 1.0 / (double)tests);
}
