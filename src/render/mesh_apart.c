/* Whether two closed meshes are apart: neither inside the other, and their
 * surfaces nowhere closer than eps (mesh_apart.h). Surface contact is found
 * by testing the triangles of one mesh against those of the other that
 * share a cell of a uniform grid over the region where both can be; nesting
 * by ray parity from one vertex. Closest points and segment tests follow
 * Ericson, Real-Time Collision Detection (2005), sec. 5.1.5, 5.1.9, 5.3.6. */
#include "render/mesh_apart.h"

#include "subsurf/table_index.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  ss_vec3 v[3];
} tri;

static tri tri_of(const ss_mesh *m, size_t t) {
  tri r;
  for (int k = 0; k < 3; ++k) {
    r.v[k] = ss_mesh_position(m, m->indices[3 * t + (size_t)k]);
  }
  return r;
}

static double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

/* Ericson sec. 5.1.5: the point of triangle abc closest to p. */
static ss_vec3 closest_on_triangle(ss_vec3 p, const tri *t) {
  ss_vec3 a = t->v[0], b = t->v[1], c = t->v[2];
  ss_vec3 ab = ss_vec3_sub(b, a), ac = ss_vec3_sub(c, a), ap = ss_vec3_sub(p, a);
  double d1 = ss_vec3_dot(ab, ap), d2 = ss_vec3_dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    return a;
  }
  ss_vec3 bp = ss_vec3_sub(p, b);
  double d3 = ss_vec3_dot(ab, bp), d4 = ss_vec3_dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) {
    return b;
  }
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    return ss_vec3_add(a, ss_vec3_scale(ab, d1 / (d1 - d3)));
  }
  ss_vec3 cp = ss_vec3_sub(p, c);
  double d5 = ss_vec3_dot(ab, cp), d6 = ss_vec3_dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) {
    return c;
  }
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    return ss_vec3_add(a, ss_vec3_scale(ac, d2 / (d2 - d6)));
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return ss_vec3_add(b, ss_vec3_scale(ss_vec3_sub(c, b), w));
  }
  double denom = va + vb + vc;
  if (!(denom > 0.0)) {
    return a; /* degenerate triangle: its edges are tested separately */
  }
  return ss_vec3_add(a, ss_vec3_add(ss_vec3_scale(ab, vb / denom), ss_vec3_scale(ac, vc / denom)));
}

/* Ericson sec. 5.1.9: squared distance between segments p1q1 and p2q2. */
static double segments_dist2(ss_vec3 p1, ss_vec3 q1, ss_vec3 p2, ss_vec3 q2) {
  ss_vec3 d1 = ss_vec3_sub(q1, p1), d2 = ss_vec3_sub(q2, p2), r = ss_vec3_sub(p1, p2);
  double a = ss_vec3_dot(d1, d1), e = ss_vec3_dot(d2, d2), f = ss_vec3_dot(d2, r);
  double s = 0.0, t = 0.0;
  if (a <= 0.0 && e <= 0.0) {
    return ss_vec3_length2(r);
  }
  if (a <= 0.0) {
    t = clamp01(f / e);
  } else {
    double c = ss_vec3_dot(d1, r);
    if (e <= 0.0) {
      s = clamp01(-c / a);
    } else {
      double b = ss_vec3_dot(d1, d2), denom = a * e - b * b;
      s = denom > 0.0 ? clamp01((b * f - c * e) / denom) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = clamp01(-c / a);
      } else if (t > 1.0) {
        t = 1.0;
        s = clamp01((b - c) / a);
      }
    }
  }
  ss_vec3 c1 = ss_vec3_add(p1, ss_vec3_scale(d1, s)), c2 = ss_vec3_add(p2, ss_vec3_scale(d2, t));
  return ss_vec3_length2(ss_vec3_sub(c1, c2));
}

/* Ericson sec. 5.3.6 (Moller-Trumbore form): whether the segment or ray
 * o + t d, t in (0, tmax], crosses the triangle's interior or edges. */
static int crosses(ss_vec3 o, ss_vec3 d, double tmax, const tri *t) {
  ss_vec3 e1 = ss_vec3_sub(t->v[1], t->v[0]), e2 = ss_vec3_sub(t->v[2], t->v[0]);
  ss_vec3 pv = ss_vec3_cross(d, e2);
  double det = ss_vec3_dot(e1, pv);
  if (det == 0.0) {
    return 0; /* parallel: contact shows in the distances */
  }
  ss_vec3 tv = ss_vec3_sub(o, t->v[0]);
  double u = ss_vec3_dot(tv, pv) / det;
  ss_vec3 qv = ss_vec3_cross(tv, e1);
  double v = ss_vec3_dot(d, qv) / det, s = ss_vec3_dot(e2, qv) / det;
  return u >= 0.0 && v >= 0.0 && u + v <= 1.0 && s > 0.0 && s <= tmax;
}

/* 1 when all of b lies more than eps to one side of a's plane. */
static int separated_by_plane(const tri *a, const tri *b, double eps) {
  ss_vec3 n = ss_vec3_cross(ss_vec3_sub(a->v[1], a->v[0]), ss_vec3_sub(a->v[2], a->v[0]));
  double len = ss_vec3_length(n);
  if (!(len > 0.0)) {
    return 0;
  }
  int above = 0, below = 0;
  for (int k = 0; k < 3; ++k) {
    double d = ss_vec3_dot(n, ss_vec3_sub(b->v[k], a->v[0])) / len;
    above += d > eps;
    below += d < -eps;
  }
  return above == 3 || below == 3;
}

/* Closest points of two triangles are a vertex and a face or two edges,
 * unless they cross (an edge of one through the other). */
static int triangles_within(const tri *a, const tri *b, double eps) {
  if (separated_by_plane(a, b, eps) || separated_by_plane(b, a, eps)) {
    return 0;
  }
  double eps2 = eps * eps;
  for (int k = 0; k < 3; ++k) {
    ss_vec3 a0 = a->v[k], a1 = a->v[(k + 1) % 3], b0 = b->v[k], b1 = b->v[(k + 1) % 3];
    if (crosses(a0, ss_vec3_sub(a1, a0), 1.0, b) || crosses(b0, ss_vec3_sub(b1, b0), 1.0, a)) {
      return 1;
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (ss_vec3_length2(ss_vec3_sub(a->v[k], closest_on_triangle(a->v[k], b))) <= eps2 ||
        ss_vec3_length2(ss_vec3_sub(b->v[k], closest_on_triangle(b->v[k], a))) <= eps2) {
      return 1;
    }
    for (int j = 0; j < 3; ++j) {
      if (segments_dist2(a->v[k], a->v[(k + 1) % 3], b->v[j], b->v[(j + 1) % 3]) <= eps2) {
        return 1;
      }
    }
  }
  return 0;
}

/* Ray parity from p in three fixed, unaligned directions, majority vote
 * (a ray through an edge or a vertex can miscount once). */
int ss_mesh_contains(const ss_mesh *m, ss_vec3 p) {
  static const double dirs[3][3] = {
      {0.5773502, 0.5773503, 0.5773501}, {-0.2672612, 0.5345225, 0.8017837}, {0.8, -0.36, 0.48}};
  int votes = 0;
  for (int k = 0; k < 3; ++k) {
    ss_vec3 d = ss_vec3_make(dirs[k][0], dirs[k][1], dirs[k][2]);
    int hits = 0;
    for (size_t t = 0; t < m->num_triangles; ++t) {
      tri tr = tri_of(m, t);
      hits += crosses(p, d, INFINITY, &tr);
    }
    votes += hits & 1;
  }
  return votes >= 2;
}

typedef struct {
  ss_vec3 lo, hi;
} box;

static ss_vec3 vmin(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}

static ss_vec3 vmax(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}

static box tri_box(const tri *t, double eps) {
  box b = {t->v[0], t->v[0]};
  for (int k = 1; k < 3; ++k) {
    b.lo = vmin(b.lo, t->v[k]);
    b.hi = vmax(b.hi, t->v[k]);
  }
  ss_vec3 e = ss_vec3_make(eps, eps, eps);
  return (box){ss_vec3_sub(b.lo, e), ss_vec3_add(b.hi, e)};
}

static int overlaps(box a, box b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
         a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

/* A uniform grid of k^3 cells over `region`, holding triangles of one mesh
 * as compressed rows (start[c] .. start[c + 1] in ids). */
typedef struct {
  box region;
  int k;
  size_t *start, *ids;
} grid;

static void cell_range(const grid *g, box b, int lo[3], int hi[3]) {
  const double bl[3] = {b.lo.x, b.lo.y, b.lo.z}, bh[3] = {b.hi.x, b.hi.y, b.hi.z};
  const double rl[3] = {g->region.lo.x, g->region.lo.y, g->region.lo.z};
  const double rh[3] = {g->region.hi.x, g->region.hi.y, g->region.hi.z};
  for (int a = 0; a < 3; ++a) {
    double w = (rh[a] - rl[a]) / g->k;
    double l = w > 0.0 ? floor((bl[a] - rl[a]) / w) : 0.0,
           h = w > 0.0 ? floor((bh[a] - rl[a]) / w) : 0.0;
    lo[a] = ss_table_cell_clamped(l, g->k);
    hi[a] = ss_table_cell_clamped(h, g->k);
  }
}

static size_t cell_of(const grid *g, int x, int y, int z) {
  return ((size_t)z * (size_t)g->k + (size_t)y) * (size_t)g->k + (size_t)x;
}

static int grid_build(grid *g, const ss_mesh *m, double eps) {
  size_t cells = (size_t)g->k * (size_t)g->k * (size_t)g->k;
  g->start = calloc(cells + 1, sizeof *g->start);
  if (!g->start) {
    return -1;
  }
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t t = 0; t < m->num_triangles; ++t) {
      tri tr = tri_of(m, t);
      box b = tri_box(&tr, eps);
      if (!overlaps(b, g->region)) {
        continue;
      }
      int lo[3], hi[3];
      cell_range(g, b, lo, hi);
      for (int z = lo[2]; z <= hi[2]; ++z) {
        for (int y = lo[1]; y <= hi[1]; ++y) {
          for (int x = lo[0]; x <= hi[0]; ++x) {
            size_t c = cell_of(g, x, y, z);
            if (pass == 0) {
              g->start[c + 1]++;
            } else {
              g->ids[g->start[c]++] = t;
            }
          }
        }
      }
    }
    if (pass == 0) {
      for (size_t c = 0; c < cells; ++c) {
        g->start[c + 1] += g->start[c];
      }
      g->ids = malloc((g->start[cells] + 1) * sizeof *g->ids);
      if (!g->ids) {
        return -1;
      }
    } else {
      /* Filling advanced each start to the next row's: shift back. */
      for (size_t c = cells; c > 0; --c) {
        g->start[c] = g->start[c - 1];
      }
      g->start[0] = 0;
    }
  }
  return 0;
}

/* 1 when some triangle of a is within eps of one of b in the grid. */
static int surfaces_meet(const ss_mesh *a, const ss_mesh *b, const grid *g, double eps) {
  for (size_t t = 0; t < a->num_triangles; ++t) {
    tri ta = tri_of(a, t);
    box bb = tri_box(&ta, eps);
    if (!overlaps(bb, g->region)) {
      continue;
    }
    int lo[3], hi[3];
    cell_range(g, bb, lo, hi);
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          size_t c = cell_of(g, x, y, z);
          for (size_t i = g->start[c]; i < g->start[c + 1]; ++i) {
            tri tb = tri_of(b, g->ids[i]);
            if (overlaps(bb, tri_box(&tb, 0.0)) && triangles_within(&ta, &tb, eps)) {
              return 1;
            }
          }
        }
      }
    }
  }
  return 0;
}

ss_mesh_relation ss_mesh_relation_of(const ss_mesh *a, const ss_mesh *b, double eps) {
  box ba, bb;
  ss_mesh_bounds(a, &ba.lo, &ba.hi);
  ss_mesh_bounds(b, &bb.lo, &bb.hi);
  ss_vec3 e = ss_vec3_make(eps, eps, eps);
  box region = {vmax(ss_vec3_sub(ba.lo, e), ss_vec3_sub(bb.lo, e)),
                vmin(ss_vec3_add(ba.hi, e), ss_vec3_add(bb.hi, e))};
  if (a->num_triangles == 0 || b->num_triangles == 0 || !overlaps(region, region)) {
    return SS_MESHES_APART;
  }
  size_t n = a->num_triangles + b->num_triangles;
  int k = (int)ceil(cbrt((double)n / 4.0));
  grid g = {region, k < 1 ? 1 : (k > 96 ? 96 : k), NULL, NULL};
  ss_mesh_relation rel;
  if (grid_build(&g, b, eps) != 0) {
    rel = SS_MESHES_UNKNOWN;
  } else if (surfaces_meet(a, b, &g, eps)) {
    rel = SS_MESHES_TOUCH;
  } else if (ss_mesh_contains(b, ss_mesh_position(a, a->indices[0]))) {
    rel = SS_MESHES_A_IN_B;
  } else if (ss_mesh_contains(a, ss_mesh_position(b, b->indices[0]))) {
    rel = SS_MESHES_B_IN_A;
  } else {
    rel = SS_MESHES_APART;
  }
  free(g.start);
  free(g.ids);
  return rel;
}
