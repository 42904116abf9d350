#include "subsurf/catmull_rom.h"

#include <math.h>
#include <stdlib.h>

size_t ss_cr_find_interval(size_t n, const double *nodes, double x) {
  /* Largest i with nodes[i] <= x, clamped so that [i, i+1] is an interval;
   * branch-free halving (the comparisons are unpredictable). */
  size_t lo = 0, len = n - 1;
  while (len > 1) {
    size_t half = len / 2;
    lo += (nodes[lo + half] <= x) ? half : 0;
    len -= half;
  }
  return lo < n - 2 ? lo : n - 2;
}

/* Hermite data of interval i: end values and end derivatives (scaled to the
 * unit interval) from the finite differences of v = {f_{i-1}, f_i, f_{i+1},
 * f_{i+2}}; missing neighbours at the ends give one-sided differences.
 * PBR 3rd ed., eq. 8.24-8.25. */
typedef struct {
  double f0, f1, d0, d1;
} hermite;

static hermite hermite_make(size_t n, const double *x, size_t i, const double v[4]) {
  hermite h;
  double width = x[i + 1] - x[i];
  h.f0 = v[1];
  h.f1 = v[2];
  h.d0 = i > 0 ? width * (v[2] - v[0]) / (x[i + 1] - x[i - 1]) : v[2] - v[1];
  h.d1 = i + 2 < n ? width * (v[3] - v[1]) / (x[i + 2] - x[i]) : v[2] - v[1];
  return h;
}

static double hermite_value(const hermite *h, double t) {
  return h->f0 + t * (h->d0 + t * (-2.0 * h->d0 - h->d1 + 3.0 * (h->f1 - h->f0) +
                                   t * (h->d0 + h->d1 + 2.0 * (h->f0 - h->f1))));
}

/* Integral of the cubic from 0 to t, in units of the unit interval. */
static double hermite_integral(const hermite *h, double t) {
  return t *
         (h->f0 + t * (0.5 * h->d0 + t * ((-2.0 * h->d0 - h->d1) / 3.0 + h->f1 - h->f0 +
                                          t * (0.25 * (h->d0 + h->d1) + 0.5 * (h->f0 - h->f1)))));
}

int ss_cr_weights(size_t n, const double *nodes, double x, long *offset, double w[4]) {
  if (!(x >= nodes[0] && x <= nodes[n - 1])) {
    return 0;
  }
  size_t i = ss_cr_find_interval(n, nodes, x);
  double x0 = nodes[i], x1 = nodes[i + 1];
  double t = (x - x0) / (x1 - x0), t2 = t * t, t3 = t2 * t;
  /* The Hermite basis applied to the finite-difference derivatives, written
   * as weights on the four neighbouring values (PBR 3rd ed., sec. 8.8.1). */
  w[0] = 0.0;
  w[1] = 2.0 * t3 - 3.0 * t2 + 1.0;
  w[2] = -2.0 * t3 + 3.0 * t2;
  w[3] = 0.0;
  double h10 = t3 - 2.0 * t2 + t, h11 = t3 - t2;
  if (i > 0) {
    double a = h10 * (x1 - x0) / (x1 - nodes[i - 1]);
    w[0] = -a;
    w[2] += a;
  } else {
    w[1] -= h10;
    w[2] += h10;
  }
  if (i + 2 < n) {
    double b = h11 * (x1 - x0) / (nodes[i + 2] - x0);
    w[1] -= b;
    w[3] = b;
  } else {
    w[1] -= h11;
    w[2] += h11;
  }
  *offset = (long)i - 1;
  return 1;
}

int ss_cr_tensor(int dims, const ss_cr_axis *axes, const double *x, size_t *index, double *w) {
  long off[3];
  double wt[3][4];
  if (dims < 1 || dims > 3) {
    return -1;
  }
  for (int d = 0; d < dims; ++d) {
    if (!ss_cr_weights(axes[d].n, axes[d].nodes, x[d], &off[d], wt[d])) {
      return -1;
    }
  }
  /* Enumerate the 4^dims corners, skipping zero weights (which include every
   * corner outside the table). */
  int count = 0;
  int total = 1 << (2 * dims);
  for (int c = 0; c < total; ++c) {
    double weight = 1.0;
    size_t idx = 0;
    for (int d = 0; d < dims; ++d) {
      int k = (c >> (2 * (dims - 1 - d))) & 3;
      weight *= wt[d][k];
      idx = idx * axes[d].n + (size_t)(off[d] + k);
    }
    if (weight != 0.0) {
      index[count] = idx;
      w[count] = weight;
      ++count;
    }
  }
  return count;
}

static void gather_row(size_t n, const float *f, size_t stride, size_t i, double v[4]) {
  v[0] = i > 0 ? f[(i - 1) * stride] : 0.0;
  v[1] = f[i * stride];
  v[2] = f[(i + 1) * stride];
  v[3] = i + 2 < n ? f[(i + 2) * stride] : 0.0;
}

double ss_cr_eval(size_t n, const double *nodes, const float *f, size_t stride, double x) {
  long off;
  double w[4];
  if (!ss_cr_weights(n, nodes, x, &off, w)) {
    return 0.0;
  }
  double v = 0.0;
  for (int k = 0; k < 4; ++k) {
    if (w[k] != 0.0) {
      v += w[k] * f[(size_t)(off + k) * stride];
    }
  }
  return v;
}

double ss_cr_integrate(size_t n, const double *nodes, const float *f, size_t stride, double *F) {
  double sum = 0.0;
  F[0] = 0.0;
  for (size_t i = 0; i + 1 < n; ++i) {
    double v[4];
    gather_row(n, f, stride, i, v);
    hermite h = hermite_make(n, nodes, i, v);
    /* Exact integral of the cubic over the interval: the trapezoid plus the
     * derivative correction (Euler-Maclaurin is exact for cubics). */
    sum += (0.5 * (h.f0 + h.f1) + (h.d0 - h.d1) / 12.0) * (nodes[i + 1] - nodes[i]);
    F[i + 1] = sum;
  }
  return sum;
}

double ss_cr_mix_at(const ss_cr_mix *m, const float *data, size_t n, size_t stride, size_t k) {
  double v = 0.0;
  for (int j = 0; j < m->count; ++j) {
    v += m->w[j] * data[(m->row[j] * n + k) * stride];
  }
  return v;
}

double ss_cr_sample_mix(size_t n, const double *nodes, const ss_cr_mix *m, const float *f,
                        size_t f_stride, const float *F, double u, double *fval, double *pdf) {
  double total = ss_cr_mix_at(m, F, n, 1, n - 1);
  if (!(total > 0.0)) {
    return NAN;
  }
  double target = u * total;
  /* Interval whose cumulative integral brackets the target. */
  size_t lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (ss_cr_mix_at(m, F, n, 1, mid) <= target) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  size_t i = lo;
  double v[4];
  v[0] = i > 0 ? ss_cr_mix_at(m, f, n, f_stride, i - 1) : 0.0;
  v[1] = ss_cr_mix_at(m, f, n, f_stride, i);
  v[2] = ss_cr_mix_at(m, f, n, f_stride, i + 1);
  v[3] = i + 2 < n ? ss_cr_mix_at(m, f, n, f_stride, i + 2) : 0.0;
  hermite h = hermite_make(n, nodes, i, v);
  double width = nodes[i + 1] - nodes[i];
  double rest = (target - ss_cr_mix_at(m, F, n, 1, i)) / width;

  /* Start from the inverse of the linear interpolant's integral, then
   * Newton steps that fall back to bisection when they leave the bracket
   * (PBR 3rd ed., sec. 8.8.2). */
  double t;
  if (h.f0 != h.f1) {
    t = (h.f0 - sqrt(fmax(0.0, h.f0 * h.f0 + 2.0 * rest * (h.f1 - h.f0)))) / (h.f0 - h.f1);
  } else {
    t = h.f0 > 0.0 ? rest / h.f0 : 0.5;
  }
  double a = 0.0, b = 1.0, Fh = 0.0, fh = 0.0;
  double tol = 1e-12 * fabs(hermite_integral(&h, 1.0));
  for (int iter = 0; iter < 100; ++iter) {
    if (!(t >= a && t <= b)) {
      t = 0.5 * (a + b);
    }
    Fh = hermite_integral(&h, t);
    fh = hermite_value(&h, t);
    if (fabs(Fh - rest) <= tol || b - a < 1e-13) {
      break;
    }
    if (Fh - rest < 0.0) {
      a = t;
    } else {
      b = t;
    }
    t -= (Fh - rest) / fh;
  }
  if (fval) {
    *fval = fh;
  }
  if (pdf) {
    *pdf = fh / total;
  }
  return nodes[i] + width * t;
}

double ss_cr_sample(size_t n, const double *nodes, const float *f, size_t f_stride, const float *F,
                    double u, double *fval, double *pdf) {
  ss_cr_mix m = {.count = 1, .row = {0}, .w = {1.0}};
  return ss_cr_sample_mix(n, nodes, &m, f, f_stride, F, u, fval, pdf);
}

double ss_cr_invert(size_t n, const double *nodes, const double *values, double y) {
  if (!(y > values[0])) {
    return nodes[0];
  }
  if (!(y < values[n - 1])) {
    return nodes[n - 1];
  }
  size_t i = ss_cr_find_interval(n, values, y);
  double v[4] = {i > 0 ? values[i - 1] : 0.0, values[i], values[i + 1],
                 i + 2 < n ? values[i + 2] : 0.0};
  hermite h = hermite_make(n, nodes, i, v);
  double a = 0.0, b = 1.0, t = 0.5;
  for (int iter = 0; iter < 100; ++iter) {
    if (!(t > a && t < b)) {
      t = 0.5 * (a + b);
    }
    double fh = hermite_value(&h, t);
    /* Derivative of the Hermite cubic with respect to t. */
    double dfh = h.d0 + t * (2.0 * (-2.0 * h.d0 - h.d1 + 3.0 * (h.f1 - h.f0)) +
                             t * 3.0 * (h.d0 + h.d1 + 2.0 * (h.f0 - h.f1)));
    if (fabs(fh - y) < 1e-14 || b - a < 1e-14) {
      break;
    }
    if (fh - y < 0.0) {
      a = t;
    } else {
      b = t;
    }
    t -= (fh - y) / dfh;
  }
  return nodes[i] + t * (nodes[i + 1] - nodes[i]);
}

/* The weights of ss_cr_weights as cubics in t: the Hermite basis
 * h00 = 1 - 3t^2 + 2t^3, h01 = 3t^2 - 2t^3, h10 = t - 2t^2 + t^3,
 * h11 = t^3 - t^2 (coefficients of t^0..t^3) applied to the same finite
 * differences (PBR 3rd ed., sec. 8.8.1). acc[j][p]: node j, power p. */
static void piece_weights(size_t n, const double *x, size_t i, double acc[][4]) {
  static const double h00[4] = {1, 0, -3, 2}, h01[4] = {0, 0, 3, -2};
  static const double h10[4] = {0, 1, -2, 1}, h11[4] = {0, 0, -1, 1};
  double a = i > 0 ? (x[i + 1] - x[i]) / (x[i + 1] - x[i - 1]) : 0.0;
  double b = i + 2 < n ? (x[i + 1] - x[i]) / (x[i + 2] - x[i]) : 0.0;
  for (int p = 0; p < 4; ++p) {
    acc[i][p] += h00[p];
    acc[i + 1][p] += h01[p];
    if (i > 0) {
      acc[i - 1][p] -= a * h10[p];
      acc[i + 1][p] += a * h10[p];
    } else {
      acc[i][p] -= h10[p];
      acc[i + 1][p] += h10[p];
    }
    if (i + 2 < n) {
      acc[i][p] -= b * h11[p];
      acc[i + 2][p] += b * h11[p];
    } else {
      acc[i][p] -= h11[p];
      acc[i + 1][p] += h11[p];
    }
  }
}

/* Key of a non-negative double: its exponent and leading mantissa bits,
 * monotone in x. */
static uint64_t bucket_key(double x) {
  union {
    double d;
    uint64_t u;
  } bits = {x};
  return bits.u >> (52 - SS_CR_BUCKET_BITS);
}

static double bucket_edge(uint64_t key) {
  union {
    uint64_t u;
    double d;
  } bits = {key << (52 - SS_CR_BUCKET_BITS)};
  return bits.d;
}

/* Buckets where few nodes share one (a spacing not much finer than the
 * bucket width, as on uniform and geometric grids); else bisection. */
enum { BUCKET_MAX = 4096, BUCKET_MAX_STEPS = 2 };

static int grid_buckets(ss_cr_grid *g) {
  const double *x = g->nodes;
  size_t n = g->n;
  g->bucket = NULL;
  g->steps = 0;
  if (!(x[0] >= 0.0 && x[1] > 0.0 && isfinite(x[n - 1]))) {
    return 1;
  }
  /* One bucket below nodes[1] so that every smaller x maps to interval 0. */
  uint64_t lo = bucket_key(x[1]) - 1, hi = bucket_key(x[n - 1]);
  if (hi - lo + 1 > BUCKET_MAX) {
    return 1;
  }
  int steps = 0;
  size_t i = 0;
  for (uint64_t k = lo; k <= hi; ++k) {
    double lower = bucket_edge(k), upper = bucket_edge(k + 1);
    while (i + 1 < n && x[i + 1] <= lower) {
      ++i;
    }
    int inside = 0;
    for (size_t j = i + 1; j < n && x[j] < upper; ++j) {
      ++inside;
    }
    steps = inside > steps ? inside : steps;
  }
  if (steps > BUCKET_MAX_STEPS) {
    return 1;
  }
  g->bucket = malloc(hi - lo + 1);
  if (!g->bucket) {
    return 0;
  }
  i = 0;
  for (uint64_t k = lo; k <= hi; ++k) {
    while (i + 1 < n && x[i + 1] <= bucket_edge(k)) {
      ++i;
    }
    g->bucket[k - lo] = (uint8_t)(i < n - 2 ? i : n - 2);
  }
  g->key_lo = lo;
  g->key_hi = hi;
  g->steps = steps;
  return 1;
}

int ss_cr_grid_init(ss_cr_grid *g, size_t n, const double *nodes, int mirror_ghost) {
  size_t real = mirror_ghost ? n - 1 : n;
  g->n = n;
  g->nodes = nodes;
  g->x_max = nodes[real - 1];
  g->piece = malloc((n - 1) * sizeof *g->piece);
  g->pad = malloc((n + BUCKET_MAX_STEPS) * sizeof *g->pad);
  g->bucket = NULL;
  if (!g->piece || !g->pad || real < 4 || n > 255 || !grid_buckets(g)) {
    ss_cr_grid_free(g);
    return 0;
  }
  for (size_t j = 0; j < n + BUCKET_MAX_STEPS; ++j) {
    g->pad[j] = j < n ? nodes[j] : INFINITY;
  }
  double acc[256][4];
  for (size_t i = 0; i + 1 < n; ++i) {
    ss_cr_piece *p = g->piece + i;
    for (size_t j = 0; j < n; ++j) {
      acc[j][0] = acc[j][1] = acc[j][2] = acc[j][3] = 0.0;
    }
    piece_weights(n, nodes, i, acc);
    if (mirror_ghost) {
      for (int q = 0; q < 4; ++q) {
        acc[n - 3][q] += acc[n - 1][q];
        acc[n - 1][q] = 0.0;
      }
    }
    /* Taps i-1..i+2 shifted inside the real nodes (the weights beyond the
     * ends are zero). */
    size_t base = i > 0 ? i - 1 : 0;
    base = base + 4 > real ? real - 4 : base;
    for (size_t j = 0; j < n; ++j) {
      int used = acc[j][0] != 0.0 || acc[j][1] != 0.0 || acc[j][2] != 0.0 || acc[j][3] != 0.0;
      if (used && (j < base || j >= base + 4)) {
        ss_cr_grid_free(g);
        return 0;
      }
    }
    p->base = base;
    p->x0 = nodes[i];
    p->inv_width = 1.0 / (nodes[i + 1] - nodes[i]);
    for (int k = 0; k < 4; ++k) {
      for (int q = 0; q < 4; ++q) {
        p->m[q][k] = acc[base + (size_t)k][q];
      }
    }
  }
  return 1;
}

void ss_cr_grid_free(ss_cr_grid *g) {
  free(g->piece);
  free(g->pad);
  free(g->bucket);
  g->piece = NULL;
  g->pad = NULL;
  g->bucket = NULL;
}
