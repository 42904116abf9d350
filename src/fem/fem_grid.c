/* Point location in a tetrahedral mesh through a uniform grid of cells, each
 * listing the tetrahedra whose bounding boxes overlap it (about two
 * tetrahedra per cell). */
#include "fem/fem_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void tet_bounds(const ss_fem_mesh *m, size_t t, double lo[3], double hi[3]) {
  for (int a = 0; a < 3; ++a) {
    lo[a] = INFINITY;
    hi[a] = -INFINITY;
  }
  for (int k = 0; k < 4; ++k) {
    const double *p = m->positions + 3 * (size_t)m->tets[4 * t + (size_t)k];
    for (int a = 0; a < 3; ++a) {
      lo[a] = p[a] < lo[a] ? p[a] : lo[a];
      hi[a] = p[a] > hi[a] ? p[a] : hi[a];
    }
  }
}

static size_t cell_index(const ss_fem_grid *g, const double x[3], size_t c[3]) {
  double o[3] = {g->lo.x, g->lo.y, g->lo.z};
  for (int a = 0; a < 3; ++a) {
    double f = floor((x[a] - o[a]) / g->cell);
    c[a] = f < 0.0 ? 0 : (f >= (double)g->dims[a] ? g->dims[a] - 1 : (size_t)f);
  }
  return (c[2] * g->dims[1] + c[1]) * g->dims[0] + c[0];
}

/* Visits the cells overlapped by tetrahedron t: counts (tet == NULL) or fills. */
static void visit(ss_fem_grid *g, const ss_fem_mesh *m, size_t t, size_t *fill) {
  double lo[3], hi[3];
  size_t a[3], b[3];
  tet_bounds(m, t, lo, hi);
  cell_index(g, lo, a);
  cell_index(g, hi, b);
  for (size_t z = a[2]; z <= b[2]; ++z) {
    for (size_t y = a[1]; y <= b[1]; ++y) {
      for (size_t x = a[0]; x <= b[0]; ++x) {
        size_t i = (z * g->dims[1] + y) * g->dims[0] + x;
        if (fill) {
          g->tet[fill[i]++] = (uint32_t)t;
        } else {
          g->start[i + 1]++;
        }
      }
    }
  }
}

ss_status ss_fem_grid_build(const ss_fem_mesh *m, ss_fem_grid *g, ss_error *err) {
  memset(g, 0, sizeof *g);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t v = 0; v < m->num_vertices; ++v) {
    for (int a = 0; a < 3; ++a) {
      double p = m->positions[3 * v + (size_t)a];
      lo[a] = p < lo[a] ? p : lo[a];
      hi[a] = p > hi[a] ? p : hi[a];
    }
  }
  double vol = 1.0, ext[3];
  for (int a = 0; a < 3; ++a) {
    ext[a] = hi[a] - lo[a] > 0.0 ? hi[a] - lo[a] : 1.0;
    vol *= ext[a];
  }
  /* about one cell per two tetrahedra, at most 1024 per axis */
  g->cell = cbrt(2.0 * vol / (double)(m->num_tets ? m->num_tets : 1));
  size_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    double d = ceil(ext[a] / g->cell);
    g->dims[a] = d < 1.0 ? 1 : (d > 1024.0 ? 1024 : (size_t)d);
    cells *= g->dims[a];
  }
  for (int a = 0; a < 3; ++a) {
    g->cell = fmax(g->cell, ext[a] / (double)g->dims[a]);
  }
  g->lo = ss_vec3_make(lo[0], lo[1], lo[2]);
  g->start = calloc(cells + 1, sizeof *g->start);
  size_t *fill = malloc(cells * sizeof *fill);
  if (!g->start || !fill) {
    free(fill);
    ss_fem_grid_free(g);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for a grid of %zu cells", cells);
  }
  for (size_t t = 0; t < m->num_tets; ++t) {
    visit(g, m, t, NULL);
  }
  for (size_t i = 0; i < cells; ++i) {
    g->start[i + 1] += g->start[i];
    fill[i] = g->start[i];
  }
  g->tet = malloc((g->start[cells] ? g->start[cells] : 1) * sizeof *g->tet);
  if (!g->tet) {
    free(fill);
    ss_fem_grid_free(g);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for the point-location grid");
  }
  for (size_t t = 0; t < m->num_tets; ++t) {
    visit(g, m, t, fill);
  }
  free(fill);
  return SS_OK;
}

int ss_fem_grid_locate(const ss_fem_grid *g, const ss_fem_mesh *m, ss_vec3 x, size_t *tet,
                       double lambda[4]) {
  double p[3] = {x.x, x.y, x.z}, o[3] = {g->lo.x, g->lo.y, g->lo.z};
  for (int a = 0; a < 3; ++a) {
    if (!(p[a] >= o[a] - 1e-9 * g->cell) || !(p[a] <= o[a] + g->cell * (double)g->dims[a])) {
      return 0;
    }
  }
  size_t c[3], i = cell_index(g, p, c);
  for (size_t k = g->start[i]; k < g->start[i + 1]; ++k) {
    if (ss_fem_tet_barycentric(m, g->tet[k], x, lambda)) {
      *tet = g->tet[k];
      return 1;
    }
  }
  return 0;
}

void ss_fem_grid_free(ss_fem_grid *g) {
  free(g->start);
  free(g->tet);
  memset(g, 0, sizeof *g);
}
