/* Element sizes from the medium's variation (include/subsurf/fem.h,
 * ss_fem_size_options): refinement where the medium varies fast
 * (Jakob2010 sec. 6.2 refines where the source varies,
 * along the edges of the projected source image). Every tetrahedron takes
 * its (M, mu0) at its centroid, so a density step or a turn of the flakes'
 * axis inside a large element moves the interface by up to the element's
 * size; small elements there keep it in place. The medium is sampled on a
 * lattice, two z-slices of coefficients at a time, the sizes of the whole
 * lattice kept as floats. */
#include "subsurf/fem.h"
#include "subsurf/table_index.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* At most this many lattice samples (16 MB of sizes). */
#define MAX_SAMPLES (1 << 22)

struct ss_fem_size_field {
  ss_vec3 lo;
  double step[3];
  int n[3];
  float *size; /* n[0] n[1] n[2], x fastest */
  double smallest;
};

static ss_status check(const ss_fem_size_options *o, ss_error *err) {
  ss_vec3 d = ss_vec3_sub(o->hi, o->lo);
  if (!(d.x > 0.0 && d.y > 0.0 && d.z > 0.0) || !isfinite(d.x + d.y + d.z) ||
      !isfinite(o->lo.x + o->lo.y + o->lo.z)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem size field: box sides %g x %g x %g must be positive and finite", d.x,
                        d.y, d.z);
  }
  if (!(o->spacing > 0.0) || !isfinite(o->spacing) || !(o->tolerance > 0.0) ||
      !isfinite(o->tolerance)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem size field: spacing %g and tolerance %g must be positive and finite",
                        o->spacing, o->tolerance);
  }
  if (!(o->size_min > 0.0) || !(o->size_min <= o->size_max) || !isfinite(o->size_max) ||
      !(o->grade >= 0.0) || !isfinite(o->grade)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem size field: sizes min %g, max %g, grade %g (need 0 < min <= max, "
                        "grade >= 0, finite)",
                        o->size_min, o->size_max, o->grade);
  }
  return SS_OK;
}

/* The lattice: about `spacing` apart, coarsened to at most MAX_SAMPLES. */
static void lattice(const ss_fem_size_options *o, ss_fem_size_field *f) {
  ss_vec3 d = ss_vec3_sub(o->hi, o->lo);
  double side[3] = {d.x, d.y, d.z}, h = o->spacing;
  for (;;) {
    double total = 1.0;
    for (int a = 0; a < 3; ++a) {
      f->n[a] = (int)fmin(ceil(side[a] / h) + 1.0, (double)MAX_SAMPLES);
      f->n[a] = f->n[a] < 2 ? 2 : f->n[a];
      total *= f->n[a];
    }
    if (total <= MAX_SAMPLES) {
      break;
    }
    h *= 1.05 * cbrt(total / MAX_SAMPLES);
  }
  f->lo = o->lo;
  for (int a = 0; a < 3; ++a) {
    f->step[a] = side[a] / (f->n[a] - 1);
  }
}

/* The relative change of the coefficients between two samples. */
static double relative_change(const ss_fem_coeffs *a, const ss_fem_coeffs *b) {
  double diff = 0.0, na = 0.0, nb = 0.0;
  for (int k = 0; k < 9; ++k) {
    diff += (a->M[k] - b->M[k]) * (a->M[k] - b->M[k]);
    na += a->M[k] * a->M[k];
    nb += b->M[k] * b->M[k];
  }
  double big = sqrt(fmax(na, nb)), r = big > 0.0 ? sqrt(diff) / big : 0.0;
  double mu = fmax(a->mu0, b->mu0);
  return mu > 0.0 ? fmax(r, fabs(a->mu0 - b->mu0) / mu) : r;
}

static size_t index_of(const ss_fem_size_field *f, int i, int j, int k) {
  return ((size_t)k * (size_t)f->n[1] + (size_t)j) * (size_t)f->n[0] + (size_t)i;
}

/* Lowers both samples' sizes to tolerance / g for the gradient g = r / d. */
static void limit(ss_fem_size_field *f, const ss_fem_size_options *o, size_t p, size_t q, double r,
                  double d) {
  if (r > 0.0) {
    float s = (float)fmax(o->size_min, o->tolerance * d / r);
    f->size[p] = s < f->size[p] ? s : f->size[p];
    f->size[q] = s < f->size[q] ? s : f->size[q];
  }
}

/* Samples slice k into c (n[0] n[1] coefficients). */
static ss_status sample_slice(const ss_fem_size_field *f, ss_fem_medium_fn medium, void *ctx, int k,
                              ss_fem_coeffs *c, ss_error *err) {
  for (int j = 0; j < f->n[1]; ++j) {
    for (int i = 0; i < f->n[0]; ++i) {
      ss_vec3 x = ss_vec3_make(f->lo.x + i * f->step[0], f->lo.y + j * f->step[1],
                               f->lo.z + k * f->step[2]);
      ss_status st = medium(ctx, x, &c[(size_t)j * (size_t)f->n[0] + (size_t)i], err);
      if (st != SS_OK) {
        return st;
      }
    }
  }
  return SS_OK;
}

/* The sizes from the changes along x, y (within slice k) and z (to k - 1). */
static void slice_sizes(ss_fem_size_field *f, const ss_fem_size_options *o, int k,
                        const ss_fem_coeffs *cur, const ss_fem_coeffs *prev) {
  size_t nx = (size_t)f->n[0];
  for (int j = 0; j < f->n[1]; ++j) {
    for (int i = 0; i < f->n[0]; ++i) {
      size_t s = (size_t)j * nx + (size_t)i, p = index_of(f, i, j, k);
      if (i > 0) {
        limit(f, o, p, p - 1, relative_change(&cur[s], &cur[s - 1]), f->step[0]);
      }
      if (j > 0) {
        limit(f, o, p, p - nx, relative_change(&cur[s], &cur[s - nx]), f->step[1]);
      }
      if (prev) {
        limit(f, o, p, index_of(f, i, j, k - 1), relative_change(&cur[s], &prev[s]), f->step[2]);
      }
    }
  }
}

/* Grading: size_i <= size_j + grade |x_i - x_j| over the 26 neighbours, by a
 * forward and a backward sweep (a chamfer distance transform). */
static void grade_sizes(ss_fem_size_field *f, double grade) {
  for (int pass = 0; pass < 2; ++pass) {
    int dir = pass == 0 ? 1 : -1;
    for (int kk = 0; kk < f->n[2]; ++kk) {
      int k = dir > 0 ? kk : f->n[2] - 1 - kk;
      for (int jj = 0; jj < f->n[1]; ++jj) {
        int j = dir > 0 ? jj : f->n[1] - 1 - jj;
        for (int ii = 0; ii < f->n[0]; ++ii) {
          int i = dir > 0 ? ii : f->n[0] - 1 - ii;
          size_t p = index_of(f, i, j, k);
          double best = f->size[p];
          /* the 13 neighbours already visited in this sweep's order */
          for (int dk = -1; dk <= 0; ++dk) {
            for (int dj = -1; dj <= 1; ++dj) {
              for (int di = -1; di <= 1; ++di) {
                if (dk == 0 && (dj > 0 || (dj == 0 && di >= 0))) {
                  continue;
                }
                int a = i + dir * di, b = j + dir * dj, c = k + dir * dk;
                if (a < 0 || b < 0 || c < 0 || a >= f->n[0] || b >= f->n[1] || c >= f->n[2]) {
                  continue;
                }
                double d =
                    sqrt(di * di * f->step[0] * f->step[0] + dj * dj * f->step[1] * f->step[1] +
                         dk * dk * f->step[2] * f->step[2]);
                best = fmin(best, f->size[index_of(f, a, b, c)] + grade * d);
              }
            }
          }
          f->size[p] = (float)best;
        }
      }
    }
  }
}

ss_status ss_fem_size_field_from_medium(ss_fem_medium_fn medium, void *ctx,
                                        const ss_fem_size_options *opt, ss_fem_size_field **out,
                                        ss_error *err) {
  *out = NULL;
  ss_status st = check(opt, err);
  if (st != SS_OK) {
    return st;
  }
  ss_fem_size_field *f = calloc(1, sizeof *f);
  if (!f) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem size field: out of memory");
  }
  lattice(opt, f);
  size_t total = (size_t)f->n[0] * (size_t)f->n[1] * (size_t)f->n[2];
  size_t slice = (size_t)f->n[0] * (size_t)f->n[1];
  f->size = malloc(total * sizeof *f->size);
  ss_fem_coeffs *c[2] = {malloc(slice * sizeof *c[0]), malloc(slice * sizeof *c[1])};
  if (!f->size || !c[0] || !c[1]) {
    st =
        ss_error_set(err, SS_ERR_NO_MEMORY, "fem size field: out of memory for %zu samples", total);
  }
  for (size_t i = 0; st == SS_OK && i < total; ++i) {
    f->size[i] = (float)opt->size_max;
  }
  for (int k = 0; st == SS_OK && k < f->n[2]; ++k) {
    ss_fem_coeffs *cur = c[k & 1], *prev = k > 0 ? c[(k + 1) & 1] : NULL;
    st = sample_slice(f, medium, ctx, k, cur, err);
    if (st == SS_OK) {
      slice_sizes(f, opt, k, cur, prev);
    }
  }
  free(c[0]);
  free(c[1]);
  if (st != SS_OK) {
    ss_fem_size_field_destroy(f);
    return st;
  }
  grade_sizes(f, opt->grade);
  f->smallest = INFINITY;
  for (size_t i = 0; i < total; ++i) {
    f->smallest = fmin(f->smallest, f->size[i]);
  }
  *out = f;
  return SS_OK;
}

double ss_fem_size_field_at(const ss_fem_size_field *f, ss_vec3 x) {
  double p[3] = {x.x - f->lo.x, x.y - f->lo.y, x.z - f->lo.z}, t[3];
  int i0[3];
  for (int a = 0; a < 3; ++a) {
    double u = fmin(fmax(p[a] / f->step[a], 0.0), (double)(f->n[a] - 1));
    i0[a] = ss_table_cell_clamped(u, f->n[a] - 1);
    t[a] = u - i0[a];
  }
  double s = 0.0;
  for (int c = 0; c < 8; ++c) {
    int d[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
    double w = 1.0;
    for (int a = 0; a < 3; ++a) {
      w *= d[a] ? t[a] : 1.0 - t[a];
    }
    s += w * f->size[index_of(f, i0[0] + d[0], i0[1] + d[1], i0[2] + d[2])];
  }
  return s;
}

double ss_fem_size_field_cells(const ss_fem_size_field *f) {
  size_t total = (size_t)f->n[0] * (size_t)f->n[1] * (size_t)f->n[2];
  double sum = 0.0;
  for (size_t i = 0; i < total; ++i) {
    sum += 1.0 / ((double)f->size[i] * f->size[i] * f->size[i]);
  }
  double volume = 1.0;
  for (int a = 0; a < 3; ++a) {
    volume *= f->step[a] * (f->n[a] - 1);
  }
  return sum / (double)total * volume;
}

double ss_fem_size_field_min(const ss_fem_size_field *f) { return f->smallest; }

const float *ss_fem_size_field_lattice(const ss_fem_size_field *f, ss_vec3 *lo, double step[3],
                                       int n[3]) {
  *lo = f->lo;
  memcpy(step, f->step, sizeof f->step);
  memcpy(n, f->n, sizeof f->n);
  return f->size;
}

void ss_fem_size_field_destroy(ss_fem_size_field *f) {
  if (f) {
    free(f->size);
    free(f);
  }
}
