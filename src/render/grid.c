/* Voxel grids of density and flake axes (grid.h). */
#include "subsurf/grid.h"
#include "subsurf/table_index.h"

#include <math.h>
#include <stdlib.h>

ss_status ss_grid_create(const int n[3], ss_vec3 lo, ss_vec3 hi, int with_axis, ss_grid **out,
                         ss_error *err) {
  *out = NULL;
  int64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    if (n[a] < 1) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "grid dimensions must be >= 1, got %d",
                          n[a]);
    }
    count *= n[a];
    if (count > SS_GRID_MAX_VOXELS) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "grid of %d x %d x %d voxels is larger "
                          "than 2^31 voxels",
                          n[0], n[1], n[2]);
    }
    double l = ss_vec3_component(lo, a), h = ss_vec3_component(hi, a);
    if (!(isfinite(l) && isfinite(h) && l < h)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "grid bounds must be finite with lo < hi, got [%g, %g] along %c", l, h,
                          "xyz"[a]);
    }
  }
  ss_grid *g = calloc(1, sizeof *g);
  if (g) {
    g->density = calloc((size_t)count, sizeof *g->density);
    g->axis = with_axis ? malloc((size_t)count * 2 * sizeof *g->axis) : NULL;
  }
  if (!g || !g->density || (with_axis && !g->axis)) {
    ss_grid_destroy(g);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "grid: out of memory for %lld voxels",
                        (long long)count);
  }
  for (int a = 0; a < 3; ++a) {
    g->n[a] = n[a];
  }
  g->lo = lo;
  g->hi = hi;
  for (int64_t v = 0; with_axis && v < count; ++v) {
    ss_grid_set_axis(g, v, ss_vec3_make(0.0, 0.0, 1.0));
  }
  *out = g;
  return SS_OK;
}

void ss_grid_destroy(ss_grid *g) {
  if (g) {
    free(g->density);
    free(g->axis);
    free(g);
  }
}

size_t ss_grid_bytes_per_voxel(const ss_grid *g) {
  return sizeof *g->density + (g->axis ? 2 * sizeof *g->axis : 0);
}

static uint16_t quantise(double x) { return (uint16_t)lrint((x * 0.5 + 0.5) * 65535.0); }
static double dequantise(uint16_t q) { return q / 65535.0 * 2.0 - 1.0; }

/* Cigolle et al. 2014, sec. 3.8 (octahedral encoding): project on the
 * octahedron |x| + |y| + |z| = 1 and fold the lower half over the upper. */
void ss_grid_set_axis(ss_grid *g, int64_t v, ss_vec3 axis) {
  double l1 = fabs(axis.x) + fabs(axis.y) + fabs(axis.z);
  double x = axis.x / l1, y = axis.y / l1;
  if (axis.z < 0.0) {
    double fx = (1.0 - fabs(y)) * copysign(1.0, x), fy = (1.0 - fabs(x)) * copysign(1.0, y);
    x = fx;
    y = fy;
  }
  g->axis[2 * v] = quantise(x);
  g->axis[2 * v + 1] = quantise(y);
}

ss_vec3 ss_grid_axis_of(const ss_grid *g, int64_t v) {
  if (!g->axis) {
    return ss_vec3_make(0.0, 0.0, 1.0);
  }
  double x = dequantise(g->axis[2 * v]), y = dequantise(g->axis[2 * v + 1]);
  double z = 1.0 - fabs(x) - fabs(y);
  if (z < 0.0) {
    double fx = (1.0 - fabs(y)) * copysign(1.0, x), fy = (1.0 - fabs(x)) * copysign(1.0, y);
    x = fx;
    y = fy;
  }
  return ss_vec3_normalize(ss_vec3_make(x, y, z));
}

ss_status ss_grid_finish(ss_grid *g, ss_error *err) {
  double m = 0.0;
  int64_t count = ss_grid_voxels(g);
  for (int64_t v = 0; v < count; ++v) {
    double d = g->density[v];
    if (!(isfinite(d) && d >= 0.0)) {
      int64_t i = v % g->n[0], j = v / g->n[0] % g->n[1], k = v / g->n[0] / g->n[1];
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "voxel (%lld, %lld, %lld): density must be finite and >= 0, got %g",
                          (long long)i, (long long)j, (long long)k, d);
    }
    m = fmax(m, d);
  }
  g->max_density = m;
  return SS_OK;
}

/* The voxel coordinate of p along axis a, in voxel units from lo. */
static double voxel_coord(const ss_grid *g, ss_vec3 p, int a) {
  double l = ss_vec3_component(g->lo, a), h = ss_vec3_component(g->hi, a);
  return (ss_vec3_component(p, a) - l) / (h - l) * g->n[a];
}

static int inside(const ss_grid *g, ss_vec3 p) {
  return p.x >= g->lo.x && p.x <= g->hi.x && p.y >= g->lo.y && p.y <= g->hi.y && p.z >= g->lo.z &&
         p.z <= g->hi.z;
}

double ss_grid_density(const ss_grid *g, ss_vec3 p) {
  if (!inside(g, p)) {
    return 0.0;
  }
  int i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    double u = voxel_coord(g, p, a) - 0.5;
    double fl = floor(u);
    f[a] = u - fl;
    i0[a] = ss_table_cell_clamped(fl, g->n[a]);
    i1[a] = ss_table_cell_clamped(fl + 1.0, g->n[a]);
  }
  double r = 0.0;
  for (int c = 0; c < 8; ++c) {
    int i = c & 1 ? i1[0] : i0[0], j = c & 2 ? i1[1] : i0[1], k = c & 4 ? i1[2] : i0[2];
    double w =
        (c & 1 ? f[0] : 1.0 - f[0]) * (c & 2 ? f[1] : 1.0 - f[1]) * (c & 4 ? f[2] : 1.0 - f[2]);
    r += w * g->density[ss_grid_index(g, i, j, k)];
  }
  return r;
}

ss_vec3 ss_grid_axis(const ss_grid *g, ss_vec3 p) {
  int i[3];
  for (int a = 0; a < 3; ++a) {
    i[a] = ss_table_cell_clamped(voxel_coord(g, p, a), g->n[a]);
  }
  return ss_grid_axis_of(g, ss_grid_index(g, i[0], i[1], i[2]));
}

/* Kay & Kajiya's slabs: the ray's parameter interval inside the box. */
int ss_grid_clip(const ss_grid *g, ss_vec3 o, ss_vec3 d, double tmin, double tmax, double *t0,
                 double *t1) {
  double a = tmin, b = tmax;
  for (int k = 0; k < 3; ++k) {
    double ok = ss_vec3_component(o, k), dk = ss_vec3_component(d, k);
    double l = ss_vec3_component(g->lo, k), h = ss_vec3_component(g->hi, k);
    if (dk == 0.0) {
      if (ok < l || ok > h) {
        return 0;
      }
      continue;
    }
    double ta = (l - ok) / dk, tb = (h - ok) / dk;
    if (ta > tb) {
      double s = ta;
      ta = tb;
      tb = s;
    }
    a = fmax(a, ta);
    b = fmin(b, tb);
  }
  *t0 = a;
  *t1 = b;
  return a < b;
}
