/* The tabulated kernel of pass 2 of the `hierarchical` integrator
 * (hierarchical.h). Every radially symmetric model of the registry with
 * light entering along the normal (w_i = n_i, Ft(w_i) = Ft(1)) has
 *     S(x_i, n_i, n_i; x_o, n_o, w_o) = A(w_o . n_o) T(|x_o - x_i|)
 * (radial_model.c: Ft(1) Ft(w_o) R(r) / pi, or R normalised by the exit
 * transmission), so the octree's ~1000 kernel evaluations per lookup need
 * only T(r) from a table and A from one evaluation of the model per lookup.
 * The build checks this factorisation on sample geometries and reports a
 * model that breaks it (then pass 2 evaluates the model itself).
 *
 * The nodes are uniform in x = the piecewise-linear log2 of u = r^2 /
 * r_min^2 that a double's bits give directly (exponent + mantissa / 2^52,
 * Mitchell's approximation): SS_HIER_TABLE_PER_OCTAVE nodes per octave of
 * u, so that between two nodes u, and r^2, is linear in x and the linear
 * interpolation is a linear interpolation in r^2 over a cell of relative
 * width 1/64 (relative error about (sigma_tr r)^2 / 131072 for an
 * exponential profile, 1e-4 for r^-3). */
#include "render/integrators/hierarchical.h"

#include "subsurf/sampling.h"
#include "subsurf/table_index.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Radii below r_min read T(r_min) (point spacings are far larger); the
 * table ends where T has fallen below SS_HIER_TABLE_FLOOR of its largest
 * value in every channel (0 beyond). */
#define R_MIN_MFP 1e-3
#define MAX_OCTAVES 80

/* Mitchell's log2 of u >= 1 (u's bits read as a fixed-point number). */
static double pseudo_log2(double u) {
  uint64_t bits;
  memcpy(&bits, &u, sizeof bits);
  return (double)bits * 0x1p-52 - 1023.0;
}

/* Its inverse: u with pseudo_log2(u) = x (x >= 0). */
static double pseudo_exp2(double x) {
  double e = floor(x);
  return ldexp(1.0 + (x - e), (int)e);
}

/* The kernel K = S / Ft(1) at distance r for w_o = n_o on a plane. */
static void canonical(const ss_bssrdf *b, double inv_ft, double r, double k[3]) {
  ss_bssrdf_query q = {.x_i = ss_vec3_make(0, 0, 0),
                       .n_i = ss_vec3_make(0, 0, 1),
                       .w_i = ss_vec3_make(0, 0, 1),
                       .x_o = ss_vec3_make(r, 0, 0),
                       .n_o = ss_vec3_make(0, 0, 1),
                       .w_o = ss_vec3_make(0, 0, 1)};
  ss_bssrdf_eval(b, &q, k);
  for (int c = 0; c < 3; ++c) {
    k[c] *= inv_ft;
  }
}

/* The shortest transport mean free path 1 / max_c sigma_t'. */
static double shortest_mfp(const ss_bssrdf *b) {
  const ss_medium_optics *m = &ss_bssrdf_get_params(b)->medium;
  double st = 0.0;
  for (int c = 0; c < 3; ++c) {
    st = fmax(st, m->sigma_s.c[c] * (1.0 - m->g.c[c]) + m->sigma_a.c[c]);
  }
  return st > 0.0 && isfinite(st) ? 1.0 / st : 1.0;
}

/* The largest radius of the table: from the sampler's radius, doubled
 * while any channel is still above the floor. */
static double table_end(const ss_bssrdf *b, double inv_ft, double r_min, const double peak[3]) {
  double r = 0.0;
  for (int c = 0; c < 3; ++c) {
    double m = ss_bssrdf_max_radius(b, c);
    r = fmax(r, isfinite(m) ? m : 0.0);
  }
  r = fmax(r, 16.0 * r_min);
  double limit = r_min * exp2(0.5 * (MAX_OCTAVES - 1));
  for (; r < limit; r *= 2.0) {
    double k[3];
    canonical(b, inv_ft, r, k);
    int above = 0;
    for (int c = 0; c < 3; ++c) {
      above |= fabs(k[c]) > SS_HIER_TABLE_FLOOR * peak[c];
    }
    if (!above) {
      break;
    }
  }
  return fmin(r, limit);
}

ss_status ss_hier_table_build(const ss_bssrdf *b, double eta, ss_hier_table *t, ss_error *err) {
  memset(t, 0, sizeof *t);
  double inv_ft = 1.0 / ss_irradiance_fresnel_weight(1.0, eta);
  double r_min = R_MIN_MFP * shortest_mfp(b);
  double peak[3] = {0, 0, 0};
  /* the largest values: scanned over octaves of r from r_min */
  for (double r = r_min; r < 1e3 * shortest_mfp(b); r *= 2.0) {
    double k[3];
    canonical(b, inv_ft, r, k);
    for (int c = 0; c < 3; ++c) {
      peak[c] = fmax(peak[c], fabs(k[c]));
    }
  }
  double r_max = table_end(b, inv_ft, r_min, peak);
  double s_min = r_min * r_min;
  t->n = (int)ceil(pseudo_log2(r_max * r_max / s_min) * SS_HIER_TABLE_PER_OCTAVE) + 2;
  t->value = malloc((size_t)t->n * sizeof *t->value);
  if (!t->value) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "hierarchical: out of memory for a kernel table");
  }
  for (int i = 0; i < t->n; ++i) {
    double k[3];
    double s = s_min * pseudo_exp2((double)i / SS_HIER_TABLE_PER_OCTAVE);
    canonical(b, inv_ft, sqrt(s), k);
    for (int c = 0; c < 3; ++c) {
      t->value[i][c] = (float)k[c];
    }
  }
  t->value[t->n - 1][0] = t->value[t->n - 1][1] = t->value[t->n - 1][2] = 0.0f;
  t->inv_s_min = 1.0 / s_min;
  t->r_ref = shortest_mfp(b);
  canonical(b, inv_ft, t->r_ref, t->ref);
  return SS_OK;
}

void ss_hier_table_destroy(ss_hier_table *t) {
  free(t->value);
  memset(t, 0, sizeof *t);
}

void ss_hier_table_lookup(const ss_hier_table *t, double r2, double k[3]) {
  double u = r2 * t->inv_s_min;
  if (!(u > 1.0)) {
    for (int c = 0; c < 3; ++c) {
      k[c] = t->value[0][c];
    }
    return;
  }
  double x = pseudo_log2(u) * SS_HIER_TABLE_PER_OCTAVE;
  int i = ss_table_cell(x, t->n - 1);
  if (i < 0) {
    k[0] = k[1] = k[2] = 0.0;
    return;
  }
  double f = x - i;
  for (int c = 0; c < 3; ++c) {
    k[c] = t->value[i][c] + f * (t->value[i + 1][c] - t->value[i][c]);
  }
}

void ss_hier_table_disk(const ss_hier_table *t, double r, double out[3]) {
  double s_min = 1.0 / t->inv_s_min, s_end = r * r;
  double sum[3];
  /* T is constant below r_min and linear in s = r^2 between nodes: the
   * integral pi int_0^{r^2} T(s) ds of the interpolant is exact */
  double s0 = fmin(s_end, s_min);
  for (int c = 0; c < 3; ++c) {
    sum[c] = t->value[0][c] * s0;
  }
  for (int i = 0; i + 1 < t->n && s_min * pseudo_exp2((double)i / SS_HIER_TABLE_PER_OCTAVE) < s_end;
       ++i) {
    double a = s_min * pseudo_exp2((double)i / SS_HIER_TABLE_PER_OCTAVE);
    double b = s_min * pseudo_exp2((double)(i + 1) / SS_HIER_TABLE_PER_OCTAVE);
    double e = fmin(b, s_end), f = (e - a) / (b - a);
    for (int c = 0; c < 3; ++c) {
      double v0 = t->value[i][c], v1 = t->value[i + 1][c];
      sum[c] += (e - a) * (v0 + 0.5 * f * (v1 - v0));
    }
  }
  for (int c = 0; c < 3; ++c) {
    out[c] = SS_PI * sum[c];
  }
}

void ss_hier_table_angular(const ss_hier_table *t, const ss_hier_kernel_ctx *analytic,
                           double a[3]) {
  ss_frame f = ss_frame_from_normal(analytic->n_o);
  ss_vec3 x_i = ss_vec3_madd(analytic->x_o, f.s, t->r_ref);
  double k[3];
  ss_hier_kernel(analytic, x_i, analytic->n_o, k);
  for (int c = 0; c < 3; ++c) {
    a[c] = t->ref[c] != 0.0 ? k[c] / t->ref[c] : 0.0;
  }
}

void ss_hier_kernel_tabulated(const void *ctx, ss_vec3 x_i, ss_vec3 n_i, double k[3]) {
  const ss_hier_table_ctx *c = ctx;
  (void)n_i;
  ss_vec3 d = ss_vec3_sub(x_i, c->x_o);
  ss_hier_table_lookup(c->table, ss_vec3_dot(d, d), k);
  for (int i = 0; i < 3; ++i) {
    k[i] *= c->a[i];
  }
}

/* The largest relative difference between the tabulated and the model's
 * kernel over sample geometries (tilted normals, oblique views, radii over
 * the table), where the model's value is above SS_HIER_TABLE_FLOOR x 1e3
 * of the channel's largest value (below it: the difference over that). */
double ss_hier_table_check(const ss_hier_table *t, const ss_bssrdf *b, double eta) {
  double worst = 0.0, peak[3] = {0, 0, 0};
  for (int i = 0; i < t->n; ++i) {
    for (int c = 0; c < 3; ++c) {
      peak[c] = fmax(peak[c], fabs(t->value[i][c]));
    }
  }
  double inv_ft = 1.0 / ss_irradiance_fresnel_weight(1.0, eta);
  double r_min = sqrt(1.0 / t->inv_s_min);
  double octaves = (double)(t->n - 1) / SS_HIER_TABLE_PER_OCTAVE; /* of r^2 */
  for (int j = 0; j < 64; ++j) {
    /* radii spread over the table, off the nodes */
    double r = r_min * exp2(0.5 * octaves * (j + 0.37) / 64.0);
    double cos_o = 1.0 - 0.95 * (j % 8) / 7.0, sin_o = sqrt(1.0 - cos_o * cos_o);
    double tilt = 0.3 * ((j / 8) % 3);
    ss_hier_kernel_ctx a = {.b = b,
                            .x_o = ss_vec3_make(0.1, -0.2, 0.3),
                            .n_o = ss_vec3_make(0, 0, 1),
                            .w_o = ss_vec3_make(sin_o, 0, cos_o),
                            .inv_ft_normal = inv_ft};
    ss_hier_table_ctx tc = {.table = t, .x_o = a.x_o};
    ss_hier_table_angular(t, &a, tc.a);
    ss_vec3 x_i = ss_vec3_add(a.x_o, ss_vec3_make(r * cos(j), r * sin(j), 0));
    ss_vec3 n_i = ss_vec3_normalize(ss_vec3_make(tilt, 0, 1));
    double want[3], got[3];
    ss_hier_kernel(&a, x_i, n_i, want);
    ss_hier_kernel_tabulated(&tc, x_i, n_i, got);
    for (int c = 0; c < 3; ++c) {
      double scale = fmax(fabs(want[c]), 1e3 * SS_HIER_TABLE_FLOOR * peak[c]);
      if (scale > 0.0) {
        worst = fmax(worst, fabs(got[c] - want[c]) / scale);
      }
    }
  }
  return worst;
}
