/* Catmull-Rom splines on non-uniform nodes, for tabulated BSSRDFs: tensor
 * interpolation weights in 1D/2D/3D, exact integration of the spline, sampling
 * by inverting its integral, and inversion of a monotone spline.
 *
 * The spline is the cubic Hermite interpolant whose node derivatives are the
 * central finite differences of the data (one-sided at the ends), the scheme
 * pbrt-v3 uses for its BSSRDF table (Pharr, Jakob & Humphreys, "Physically
 * Based Rendering", 3rd ed., sec. 8.8.1). Because it is linear in the data,
 * interpolating along other axes first and then along the sampled axis gives
 * the same function as interpolating the tensor product directly. Nodes are
 * doubles; tabulated values are float32 (the tables' storage precision); all
 * arithmetic is double. */
#ifndef SUBSURF_CATMULL_ROM_H
#define SUBSURF_CATMULL_ROM_H

#include <stddef.h>
#include <stdint.h>

/* One axis of a table: n >= 2 strictly increasing nodes. */
typedef struct {
  size_t n;
  const double *nodes;
} ss_cr_axis;

/* Index of the interval [nodes[i], nodes[i+1]] containing x, clamped to
 * [0, n-2]. */
size_t ss_cr_find_interval(size_t n, const double *nodes, double x);

/* Spline weights of x: value(x) = sum_k w[k] * data[*offset + k], k = 0..3.
 * *offset may be -1 or n-3 at the ends, where the matching weights are zero.
 * Returns 0 (and leaves outputs untouched) when x is outside [nodes[0],
 * nodes[n-1]] or NaN. */
int ss_cr_weights(size_t n, const double *nodes, double x, long *offset, double w[4]);

/* Tensor-product weights on a dims-dimensional row-major table (the last axis
 * varies fastest). Fills up to 4^dims (index, weight) pairs with non-zero
 * weight and returns their count, or -1 when a coordinate is out of range. */
int ss_cr_tensor(int dims, const ss_cr_axis *axes, const double *x, size_t *index, double *w);

/* Value of the 1D spline at x (0 outside the nodes); data read with a stride. */
double ss_cr_eval(size_t n, const double *nodes, const float *f, size_t stride, double x);

/* Integral of the spline over each interval: F[0] = 0, F[i+1] = F[i] + the
 * integral over [x_i, x_{i+1}] (exact for the cubic). Returns F[n-1]. */
double ss_cr_integrate(size_t n, const double *nodes, const float *f, size_t stride, double *F);

/* A linear mixture of table rows along the last axis: row k of the mixture
 * is sum_j w[j] * data[row[j] * n * stride + k * stride]. */
#define SS_CR_MIX_MAX 64
typedef struct {
  int count;
  size_t row[SS_CR_MIX_MAX];
  double w[SS_CR_MIX_MAX];
} ss_cr_mix;

/* Element k of the mixture of `data` whose rows have n elements of `stride`. */
double ss_cr_mix_at(const ss_cr_mix *m, const float *data, size_t n, size_t stride, size_t k);

/* Samples x with density proportional to the spline of the mixed rows of f,
 * given the mixed rows of its cumulative integral F (built by
 * ss_cr_integrate, stride 1). u in [0, 1). Newton-bisection on the spline's
 * integral inside the interval found on F. *fval = spline value at x, *pdf =
 * fval / total. Returns NaN when the total is not positive. */
double ss_cr_sample_mix(size_t n, const double *nodes, const ss_cr_mix *m, const float *f,
                        size_t f_stride, const float *F, double u, double *fval, double *pdf);

/* 1D sampling (a mixture of one row with weight 1). */
double ss_cr_sample(size_t n, const double *nodes, const float *f, size_t f_stride, const float *F,
                    double u, double *fval, double *pdf);

/* A grid prepared for repeated queries: each interval's four spline weights
 * as cubics in the local coordinate t (precomputed from the node spacing,
 * so a query costs no division), on four taps that always lie inside the
 * table, and an interval lookup by the leading bits of x (a table of
 * buckets, each holding at most `steps` nodes) where the spacing allows it,
 * else by bisection. Optionally the last node is a mirror ghost whose
 * weight folds onto node n - 3 (the theta axis of table_gwc.h). */
typedef struct {
  double x0, inv_width; /* t = (x - x0) * inv_width */
  /* w[k] = m[0][k] + t (m[1][k] + t (m[2][k] + t m[3][k])) on taps base + k */
  double m[4][4];
  size_t base;
} ss_cr_piece;

typedef struct {
  size_t n;            /* nodes (with the ghost) */
  const double *nodes; /* not owned */
  double *pad;         /* a copy of the nodes followed by `steps` infinities */
  double x_max;        /* last queryable node: nodes[n-1], or nodes[n-2] with a ghost */
  ss_cr_piece *piece;  /* n - 1 intervals */
  uint8_t *bucket;     /* interval of each bucket's lower edge, or NULL: bisection */
  uint64_t key_lo, key_hi;
  int steps; /* nodes inside one bucket at most */
} ss_cr_grid;

#define SS_CR_BUCKET_BITS 4

/* Prepares the grid (n >= 4 nodes, or 5 with a ghost). Returns 0 when out of
 * memory. The nodes must outlive the grid. */
int ss_cr_grid_init(ss_cr_grid *g, size_t n, const double *nodes, int mirror_ghost);
void ss_cr_grid_free(ss_cr_grid *g);

/* The interval of x in [nodes[0], x_max]: ss_cr_find_interval's answer. */
static inline size_t ss_cr_grid_find(const ss_cr_grid *g, double x) {
  if (!g->bucket) {
    return ss_cr_find_interval(g->n, g->nodes, x);
  }
  union {
    double d;
    uint64_t u;
  } bits = {x};
  uint64_t key = bits.u >> (52 - SS_CR_BUCKET_BITS);
  key = key < g->key_lo ? g->key_lo : (key > g->key_hi ? g->key_hi : key);
  size_t i = g->bucket[key - g->key_lo];
  for (int s = 0; s < g->steps; ++s) {
    i += x >= g->pad[i + 1];
  }
  return i < g->n - 2 ? i : g->n - 2;
}

/* Weights of x on the piece's taps p->base..p->base+3. */
static inline void ss_cr_piece_weights(const ss_cr_piece *p, double x, double w[4]) {
  double t = (x - p->x0) * p->inv_width, t2 = t * t;
  for (int k = 0; k < 4; ++k) {
    /* Estrin's form: a shorter dependency chain than Horner's. */
    w[k] = (p->m[0][k] + t * p->m[1][k]) + t2 * (p->m[2][k] + t * p->m[3][k]);
  }
}

/* Weights of x on taps *base..*base+3 (the values ss_cr_weights gives, the
 * ghost folded). Returns 0 outside [nodes[0], x_max] or for NaN. */
static inline int ss_cr_grid_weights(const ss_cr_grid *g, double x, size_t *base, double w[4]) {
  if (!(x >= g->nodes[0] && x <= g->x_max)) {
    return 0;
  }
  const ss_cr_piece *p = g->piece + ss_cr_grid_find(g, x);
  ss_cr_piece_weights(p, x, w);
  *base = p->base;
  return 1;
}

/* x such that the spline of the monotone increasing values equals y, by
 * Newton-bisection; clamped to the end nodes outside the value range. */
double ss_cr_invert(size_t n, const double *nodes, const double *values, double y);

#endif
