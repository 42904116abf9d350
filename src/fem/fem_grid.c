/* Point location in a tetrahedral mesh through a two-level grid: uniform
 * cells over the mesh's bounding box (about two tetrahedra per cell), each
 * listing the tetrahedra whose bounding boxes overlap it, and in every cell
 * that lists more than GRID_CROWD times the mean over the listing cells
 * (and more than GRID_LEAF: on a graded mesh, where the elements there are
 * much smaller than the mean) a finer uniform grid over that cell, sized
 * the same way by the count it lists. */
#include "fem/fem_internal.h"

#include "subsurf/table_index.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define GRID_LEAF 32       /* a cell listing more tetrahedra may get a finer grid, */
#define GRID_CROWD 4.0     /* when that is more than 4 times the mean */
#define GRID_MAX_DIMS 1024 /* cells per axis of the top grid */
#define FINE_MAX_DIMS 32   /* cells per axis of a finer grid */

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

/* The cell of x, clamped to the grid (so that a box's corners bracket the
 * cells of every point inside it). */
static size_t cell_index(const ss_fem_cells *g, const double x[3], size_t c[3]) {
  double o[3] = {g->lo.x, g->lo.y, g->lo.z};
  for (int a = 0; a < 3; ++a) {
    c[a] = ss_table_cell_clamped_size((x[a] - o[a]) / g->cell, g->dims[a]);
  }
  return (c[2] * g->dims[1] + c[1]) * g->dims[0] + c[0];
}

/* Visits the cells overlapped by tetrahedron t: counts (fill NULL) or fills. */
static void visit(ss_fem_cells *g, const ss_fem_mesh *m, size_t t, size_t *fill) {
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

static size_t num_cells(const ss_fem_cells *g) { return g->dims[0] * g->dims[1] * g->dims[2]; }

static void cells_free(ss_fem_cells *g) {
  free(g->start);
  free(g->tet);
  memset(g, 0, sizeof *g);
}

/* Cells over the box [lo, lo + ext] about `per_cell` tetrahedra each (of n,
 * at most max_dims per axis) listing the tetrahedra subset[0 .. n) (all of
 * the mesh's when subset is NULL) whose bounding boxes overlap them. */
static ss_status cells_build(const ss_fem_mesh *m, const uint32_t *subset, size_t n,
                             const double lo[3], const double ext[3], size_t max_dims,
                             ss_fem_cells *g, ss_error *err) {
  memset(g, 0, sizeof *g);
  g->cell = cbrt(2.0 * ext[0] * ext[1] * ext[2] / (double)(n ? n : 1));
  for (int a = 0; a < 3; ++a) {
    double d = ceil(ext[a] / g->cell);
    g->dims[a] = d < 1.0 ? 1 : (d > (double)max_dims ? max_dims : (size_t)d);
  }
  for (int a = 0; a < 3; ++a) {
    g->cell = fmax(g->cell, ext[a] / (double)g->dims[a]);
  }
  g->lo = ss_vec3_make(lo[0], lo[1], lo[2]);
  size_t cells = num_cells(g);
  g->start = calloc(cells + 1, sizeof *g->start);
  size_t *fill = malloc(cells * sizeof *fill);
  if (!g->start || !fill) {
    free(fill);
    cells_free(g);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for a grid of %zu cells", cells);
  }
  for (size_t k = 0; k < n; ++k) {
    visit(g, m, subset ? subset[k] : k, NULL);
  }
  for (size_t i = 0; i < cells; ++i) {
    g->start[i + 1] += g->start[i];
    fill[i] = g->start[i];
  }
  g->tet = malloc((g->start[cells] ? g->start[cells] : 1) * sizeof *g->tet);
  if (!g->tet) {
    free(fill);
    cells_free(g);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for the point-location grid");
  }
  for (size_t k = 0; k < n; ++k) {
    visit(g, m, subset ? subset[k] : k, fill);
  }
  free(fill);
  return SS_OK;
}

/* The finer grids of the crowded top cells. On a uniform mesh no cell is
 * (the cells' counts stay near their mean; measured: refining every cell
 * over 32 made locating the rays' points on one 3 times slower). */
static ss_status refine(const ss_fem_mesh *m, ss_fem_grid *g, ss_error *err) {
  size_t cells = num_cells(&g->top), listing = 0, crowded = 0;
  for (size_t i = 0; i < cells; ++i) {
    listing += g->top.start[i + 1] > g->top.start[i];
  }
  double limit =
      fmax(GRID_LEAF, GRID_CROWD * (double)g->top.start[cells] / (double)(listing ? listing : 1));
  for (size_t i = 0; i < cells; ++i) {
    crowded += (double)(g->top.start[i + 1] - g->top.start[i]) > limit;
  }
  g->child = malloc((cells ? cells : 1) * sizeof *g->child);
  g->fine = calloc(crowded ? crowded : 1, sizeof *g->fine);
  if (!g->child || !g->fine) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for the point-location grid");
  }
  const ss_fem_cells *t = &g->top;
  for (size_t i = 0; i < cells; ++i) {
    size_t n = t->start[i + 1] - t->start[i];
    g->child[i] = -1;
    if (!((double)n > limit)) {
      continue;
    }
    size_t c[3] = {i % t->dims[0], (i / t->dims[0]) % t->dims[1], i / (t->dims[0] * t->dims[1])};
    double lo[3] = {t->lo.x + c[0] * t->cell, t->lo.y + c[1] * t->cell, t->lo.z + c[2] * t->cell};
    double ext[3] = {t->cell, t->cell, t->cell};
    ss_status st =
        cells_build(m, t->tet + t->start[i], n, lo, ext, FINE_MAX_DIMS, &g->fine[g->num_fine], err);
    if (st != SS_OK) {
      return st;
    }
    g->child[i] = (int64_t)g->num_fine++;
  }
  return SS_OK;
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
  double ext[3];
  for (int a = 0; a < 3; ++a) {
    ext[a] = hi[a] - lo[a] > 0.0 ? hi[a] - lo[a] : 1.0;
  }
  ss_status st = cells_build(m, NULL, m->num_tets, lo, ext, GRID_MAX_DIMS, &g->top, err);
  if (st == SS_OK) {
    st = refine(m, g, err);
  }
  if (st != SS_OK) {
    ss_fem_grid_free(g);
  }
  return st;
}

int ss_fem_grid_locate(const ss_fem_grid *g, const ss_fem_mesh *m, ss_vec3 x, size_t *tet,
                       double lambda[4]) {
  const ss_fem_cells *cells = &g->top;
  double p[3] = {x.x, x.y, x.z}, o[3] = {cells->lo.x, cells->lo.y, cells->lo.z};
  for (int a = 0; a < 3; ++a) {
    if (!(p[a] >= o[a] - 1e-9 * cells->cell) ||
        !(p[a] <= o[a] + cells->cell * (double)cells->dims[a])) {
      return 0;
    }
  }
  size_t c[3], i = cell_index(cells, p, c);
  if (g->child[i] >= 0) {
    cells = &g->fine[g->child[i]];
    i = cell_index(cells, p, c);
  }
  for (size_t k = cells->start[i]; k < cells->start[i + 1]; ++k) {
    if (ss_fem_tet_barycentric(m, cells->tet[k], x, lambda)) {
      *tet = cells->tet[k];
      return 1;
    }
  }
  return 0;
}

void ss_fem_grid_free(ss_fem_grid *g) {
  for (size_t k = 0; k < g->num_fine; ++k) {
    cells_free(&g->fine[k]);
  }
  free(g->fine);
  free(g->child);
  cells_free(&g->top);
  memset(g, 0, sizeof *g);
}
