/* The algebra of adding-doubling's operators (layer_ops.h): composition, the
 * inverse of the interreflection series and the adding equations. */
#include "transport/layer_ops.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int layer_op_alloc(layer_op *op, int n) {
  op->d = calloc((size_t)n, sizeof *op->d);
  op->s = calloc((size_t)n * (size_t)n, sizeof *op->s);
  if (!op->d || !op->s) {
    layer_op_free(op);
    return 0;
  }
  return 1;
}

void layer_op_free(layer_op *op) {
  free(op->d);
  free(op->s);
  op->d = op->s = NULL;
}

void layer_op_zero(layer_op *op, int n) {
  memset(op->d, 0, (size_t)n * sizeof *op->d);
  memset(op->s, 0, (size_t)n * (size_t)n * sizeof *op->s);
}

void layer_op_copy(layer_op *dst, const layer_op *src, int n) {
  memcpy(dst->d, src->d, (size_t)n * sizeof *dst->d);
  memcpy(dst->s, src->s, (size_t)n * (size_t)n * sizeof *dst->s);
}

int layer_slab_alloc(layer_slab *s, int n) {
  memset(s, 0, sizeof *s);
  if (!layer_op_alloc(&s->r, n) || !layer_op_alloc(&s->t, n) || !layer_op_alloc(&s->rs, n) ||
      !layer_op_alloc(&s->ts, n)) {
    layer_slab_free(s);
    return 0;
  }
  return 1;
}

void layer_slab_free(layer_slab *s) {
  layer_op_free(&s->r);
  layer_op_free(&s->t);
  layer_op_free(&s->rs);
  layer_op_free(&s->ts);
}

int layer_work_alloc(layer_work *w, int n) {
  memset(w, 0, sizeof *w);
  w->n = n;
  w->lu = malloc((size_t)n * (size_t)n * sizeof *w->lu);
  if (!w->lu || !layer_op_alloc(&w->y, n) || !layer_op_alloc(&w->x, n) ||
      !layer_op_alloc(&w->q, n) || !layer_op_alloc(&w->t, n)) {
    layer_work_free(w);
    return 0;
  }
  return 1;
}

void layer_work_free(layer_work *w) {
  free(w->lu);
  w->lu = NULL;
  layer_op_free(&w->y);
  layer_op_free(&w->x);
  layer_op_free(&w->q);
  layer_op_free(&w->t);
}

/* (d_a + s_a W)(d_b + s_b W) = d_a d_b + (d_a s_b + s_a d_b + s_a W s_b) W. */
void layer_op_compose(layer_op *out, const layer_op *a, const layer_op *b, const double *w,
                      layer_work *ws) {
  int n = ws->n;
  for (int i = 0; i < n; ++i) {
    out->d[i] = a->d[i] * b->d[i];
    double *row = out->s + (size_t)i * (size_t)n;
    const double *ar = a->s + (size_t)i * (size_t)n, *br = b->s + (size_t)i * (size_t)n;
    for (int j = 0; j < n; ++j) {
      row[j] = a->d[i] * br[j] + ar[j] * b->d[j];
    }
    for (int k = 0; k < n; ++k) {
      double f = ar[k] * w[k];
      if (f == 0.0) {
        continue;
      }
      const double *bk = b->s + (size_t)k * (size_t)n;
      for (int j = 0; j < n; ++j) {
        row[j] += f * bk[j];
      }
    }
  }
}

/* Solves m x = b in place (b: n right-hand sides as the columns of a
 * row-major n x n matrix) by Gaussian elimination with partial pivoting. */
static int solve_in_place(double *m, double *b, int n) {
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r) {
      if (fabs(m[(size_t)r * n + c]) > fabs(m[(size_t)p * n + c])) {
        p = r;
      }
    }
    double piv = m[(size_t)p * n + c];
    if (!(fabs(piv) > 0.0) || !isfinite(piv)) {
      return 0;
    }
    if (p != c) {
      for (int j = 0; j < n; ++j) {
        double t = m[(size_t)p * n + j];
        m[(size_t)p * n + j] = m[(size_t)c * n + j];
        m[(size_t)c * n + j] = t;
        t = b[(size_t)p * n + j];
        b[(size_t)p * n + j] = b[(size_t)c * n + j];
        b[(size_t)c * n + j] = t;
      }
    }
    for (int r = c + 1; r < n; ++r) {
      double f = m[(size_t)r * n + c] / piv;
      if (f == 0.0) {
        continue;
      }
      for (int j = c; j < n; ++j) {
        m[(size_t)r * n + j] -= f * m[(size_t)c * n + j];
      }
      for (int j = 0; j < n; ++j) {
        b[(size_t)r * n + j] -= f * b[(size_t)c * n + j];
      }
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    double *br = b + (size_t)r * n;
    for (int k = r + 1; k < n; ++k) {
      double f = m[(size_t)r * n + k];
      if (f == 0.0) {
        continue;
      }
      const double *bk = b + (size_t)k * n;
      for (int j = 0; j < n; ++j) {
        br[j] -= f * bk[j];
      }
    }
    double inv = 1.0 / m[(size_t)r * n + r];
    for (int j = 0; j < n; ++j) {
      br[j] *= inv;
    }
  }
  return 1;
}

/* (I - d_q - s_q W)^-1 = y + s_y W with y = 1 / (1 - d_q) and
 * (diag(1 - d_q) - s_q W) s_y = s_q diag(y): exact also at the nodes of
 * weight 0, whose columns of s_q W vanish. */
int layer_op_inverse_series(layer_op *out, const layer_op *q, const double *w, layer_work *ws) {
  int n = ws->n;
  for (int i = 0; i < n; ++i) {
    double den = 1.0 - q->d[i];
    if (!(den > 0.0)) {
      return 0;
    }
    out->d[i] = 1.0 / den;
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double qs = q->s[(size_t)i * n + j];
      ws->lu[(size_t)i * n + j] = (i == j ? 1.0 - q->d[i] : 0.0) - qs * w[j];
      out->s[(size_t)i * n + j] = qs * out->d[j];
    }
  }
  return solve_in_place(ws->lu, out->s, n);
}

static void op_add_in_place(layer_op *acc, const layer_op *a, int n) {
  for (int i = 0; i < n; ++i) {
    acc->d[i] += a->d[i];
  }
  for (size_t i = 0; i < (size_t)n * (size_t)n; ++i) {
    acc->s[i] += a->s[i];
  }
}

/* PharrHanrahan2000 sec. 3.4 (read right to left):
 * R_ab = R_a + T*_a R_b (I - R*_a R_b)^-1 T_a, T_ab = T_b (I - R*_a R_b)^-1 T_a,
 * R*_ab = R*_b + T_b R*_a (I - R_b R*_a)^-1 T*_b, T*_ab = T*_a (I - R_b R*_a)^-1 T*_b. */
/* One side of the adding equations: light entering the top face of `a`,
 * reflected (r_out) and transmitted (t_out) by a over b. The other side is
 * the same with the two slabs seen from below. */
static int add_side(layer_op *r_out, layer_op *t_out, const layer_op *r_a, const layer_op *rs_a,
                    const layer_op *t_a, const layer_op *ts_a, const layer_op *r_b,
                    const layer_op *t_b, const double *w, layer_work *ws) {
  layer_op_compose(&ws->q, rs_a, r_b, w, ws);
  if (!layer_op_inverse_series(&ws->y, &ws->q, w, ws)) {
    return 0;
  }
  layer_op_compose(&ws->x, &ws->y, t_a, w, ws);
  layer_op_compose(&ws->t, r_b, &ws->x, w, ws);
  layer_op_compose(r_out, ts_a, &ws->t, w, ws);
  op_add_in_place(r_out, r_a, ws->n);
  layer_op_compose(t_out, t_b, &ws->x, w, ws);
  return 1;
}

int layer_add(layer_slab *out, const layer_slab *a, const layer_slab *b, const double *w,
              int symmetric, layer_work *ws) {
  if (!add_side(&out->r, &out->t, &a->r, &a->rs, &a->t, &a->ts, &b->r, &b->t, w, ws)) {
    return 0;
  }
  if (symmetric) {
    layer_op_copy(&out->rs, &out->r, ws->n);
    layer_op_copy(&out->ts, &out->t, ws->n);
    return 1;
  }
  return add_side(&out->rs, &out->ts, &b->rs, &b->r, &b->ts, &b->t, &a->rs, &a->ts, w, ws);
}
