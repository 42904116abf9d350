/* Procedural triangle meshes. Every shape is wound outward and every vertex
 * that two faces share has bit-identical coordinates in both, so that
 * Embree's watertight triangle test leaves no crack between them. */
#include "core/large_alloc.h"
#include "render/sphere_uv.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void set3(float *dst, size_t i, double x, double y, double z) {
  dst[3 * i] = (float)x;
  dst[3 * i + 1] = (float)y;
  dst[3 * i + 2] = (float)z;
}

static void set_tri(uint32_t *idx, size_t t, size_t a, size_t b, size_t c) {
  idx[3 * t] = (uint32_t)a;
  idx[3 * t + 1] = (uint32_t)b;
  idx[3 * t + 2] = (uint32_t)c;
}

static int positive_finite(double x) { return isfinite(x) && x > 0.0; }

ss_status ss_shape_sphere_uv(double radius, unsigned n_theta, unsigned n_phi, ss_mesh **out,
                             ss_error *err) {
  *out = NULL;
  if (!positive_finite(radius)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "sphere: radius %g must be positive and finite", radius);
  }
  if (n_theta < 2 || n_phi < 3 || n_theta > 32768 || n_phi > 65536 ||
      (double)(n_theta + 1) * (double)(n_phi + 1) > 2e8) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "sphere: tessellation %u x %u out of range (expected rings in "
                        "[2, 32768], segments in [3, 65536], at most 2e8 vertices)",
                        n_theta, n_phi);
  }
  size_t cols = (size_t)n_phi + 1, nv = ((size_t)n_theta + 1) * cols;
  size_t nt = 2 * (size_t)n_phi * ((size_t)n_theta - 1);
  ss_mesh *m;
  ss_status st = ss_mesh_create(nv, nt, SS_MESH_NORMALS | SS_MESH_UVS, &m, err);
  if (st != SS_OK) {
    return st;
  }
  for (size_t i = 0; i <= n_theta; ++i) {
    double theta = SS_PI * (double)i / (double)n_theta;
    double ct = cos(theta), sth = sin(theta);
    if (i == 0 || i == n_theta) {
      ct = i == 0 ? 1.0 : -1.0;
      sth = 0.0;
    }
    for (size_t j = 0; j < cols; ++j) {
      /* The seam column repeats column 0 exactly. */
      double phi = 2.0 * SS_PI * (double)(j % n_phi) / (double)n_phi;
      double x = sth * cos(phi), y = sth * sin(phi), z = ct;
      size_t v = i * cols + j;
      set3(m->positions, v, radius * x, radius * y, radius * z);
      set3(m->normals, v, x, y, z);
      m->uvs[2 * v] = (float)((double)j / (double)n_phi);
      m->uvs[2 * v + 1] = (float)((double)i / (double)n_theta);
    }
  }
  size_t t = 0;
  for (size_t i = 0; i < n_theta; ++i) {
    for (size_t j = 0; j < n_phi; ++j) {
      size_t v00 = i * cols + j, v01 = v00 + 1, v10 = v00 + cols, v11 = v10 + 1;
      /* d/dtheta x d/dphi points outward. */
      if (i != 0) {
        set_tri(m->indices, t++, v00, v11, v01);
      }
      if (i + 1 != n_theta) {
        set_tri(m->indices, t++, v00, v10, v11);
      }
    }
  }
  m->closed = 1;
  *out = m;
  return SS_OK;
}

/* The icosphere is subdivided level by level; each triangle knows the ids
 * of its three edges (edge[3 f + k] runs from corner k to corner k + 1), so
 * the midpoint of an edge is found in an array indexed by edge id instead
 * of a hash map. Ids of the next level: the half of parent edge e at its
 * lower-numbered end is 2 e, the other half 2 e + 1; the three edges inside
 * parent triangle f are 2 E + 3 f + {0, 1, 2}. Vertices are numbered as
 * they are first met in triangle order, as by the hash map they replace. */
typedef struct {
  double *pos;   /* 3 per vertex of the levels before the last, on the unit sphere */
  size_t nv;     /* vertices so far */
  uint32_t *mid; /* per edge of the current level: its midpoint, or UINT32_MAX */
  /* The last level writes its new vertices straight into the mesh's float
   * arrays (radius x position, and the normal); NULL before it. */
  ss_mesh *last;
  double radius;
} ico_state;

/* The midpoint vertex of edge e = (a, b), made on first use. */
static uint32_t edge_midpoint(ico_state *s, uint32_t e, uint32_t a, uint32_t b) {
  if (s->mid[e] != UINT32_MAX) {
    return s->mid[e];
  }
  if (a > b) {
    uint32_t t = a;
    a = b;
    b = t;
  }
  /* The midpoint is computed once per edge from (min, max): both triangles
   * that share the edge get the same vertex. */
  const double *pa = s->pos + 3 * (size_t)a, *pb = s->pos + 3 * (size_t)b;
  double x = pa[0] + pb[0], y = pa[1] + pb[1], z = pa[2] + pb[2];
  double inv = 1.0 / sqrt(x * x + y * y + z * z);
  uint32_t v = (uint32_t)s->nv++;
  x *= inv;
  y *= inv;
  z *= inv;
  if (s->last) {
    set3(s->last->positions, v, s->radius * x, s->radius * y, s->radius * z);
    set3(s->last->normals, v, x, y, z);
  } else {
    s->pos[3 * (size_t)v] = x;
    s->pos[3 * (size_t)v + 1] = y;
    s->pos[3 * (size_t)v + 2] = z;
  }
  s->mid[e] = v;
  return v;
}

/* The id of the half of edge e = (v, w) that touches v. */
static uint32_t half_edge(uint32_t e, uint32_t v, uint32_t w) { return 2 * e + (v > w); }

/* One 1-to-4 split of nt triangles with ne edges into `kids` (and, unless
 * kid_edges is NULL, their edge ids): each triangle splits into its three
 * corners and the middle one, all keeping the parent's orientation. */
static void ico_split(ico_state *s, const uint32_t *tri, const uint32_t *edge, size_t nt, size_t ne,
                      uint32_t *kids, uint32_t *kid_edges) {
  memset(s->mid, 0xFF, ne * sizeof *s->mid);
  for (size_t f = 0; f < nt; ++f) {
    uint32_t a = tri[3 * f], b = tri[3 * f + 1], c = tri[3 * f + 2];
    uint32_t eab = edge[3 * f], ebc = edge[3 * f + 1], eca = edge[3 * f + 2];
    uint32_t ab = edge_midpoint(s, eab, a, b);
    uint32_t bc = edge_midpoint(s, ebc, b, c);
    uint32_t ca = edge_midpoint(s, eca, c, a);
    const uint32_t k[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
    memcpy(kids + 12 * f, k, sizeof k);
    if (kid_edges) {
      uint32_t in = (uint32_t)(2 * ne + 3 * f); /* ab-ca, ab-bc, bc-ca */
      const uint32_t ke[12] = {half_edge(eab, a, b),
                               in,
                               half_edge(eca, a, c),
                               half_edge(eab, b, a),
                               half_edge(ebc, b, c),
                               in + 1,
                               in + 2,
                               half_edge(ebc, c, b),
                               half_edge(eca, c, a),
                               in + 1,
                               in + 2,
                               in};
      memcpy(kid_edges + 12 * f, ke, sizeof ke);
    }
  }
}

ss_status ss_shape_icosphere(double radius, unsigned subdivisions, ss_mesh **out, ss_error *err) {
  *out = NULL;
  if (!positive_finite(radius)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "icosphere: radius %g must be positive and finite", radius);
  }
  if (subdivisions > 10) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "icosphere: %u subdivisions out of range (expected 0 to 10)", subdivisions);
  }
  size_t pow4 = (size_t)1 << (2 * subdivisions);
  size_t nv_final = 10 * pow4 + 2, nt_final = 20 * pow4;
  /* Levels before the last: at most nt_final / 4 triangles and as many
   * edges as the last level's parents have (30 pow4 / 4). */
  size_t nt_inner = nt_final / 4 < 20 ? 20 : nt_final / 4, ne_inner = 3 * nt_inner / 2;
  size_t nv_prev = subdivisions ? 10 * pow4 / 4 + 2 : 12; /* vertices before the last level */
  ss_mesh *m = NULL;
  /* One block for the work arrays (fewer fresh pages to fault in): the
   * inner levels' positions, then the triangles and edge ids of two levels
   * and the midpoints. */
  double *work =
      ss_large_alloc(3 * nv_prev * sizeof(double) + (12 * nt_inner + ne_inner) * sizeof(uint32_t));
  uint32_t *ids = work ? (uint32_t *)(work + 3 * nv_prev) : NULL;
  ico_state s = {work, 12, ids ? ids + 12 * nt_inner : NULL, NULL, radius};
  uint32_t *tri[2] = {ids, ids ? ids + 3 * nt_inner : NULL};
  uint32_t *edge[2] = {ids ? ids + 6 * nt_inner : NULL, ids ? ids + 9 * nt_inner : NULL};
  /* The mesh has room for the uvs' seam and pole copies from the start. */
  size_t room = ss_spherical_uvs_room(nv_final);
  ss_status st = ss_mesh_create(room, nt_final, SS_MESH_NORMALS | SS_MESH_UVS, &m, err);
  if (st != SS_OK) {
    goto done;
  }
  m->num_vertices = nv_final;
  if (!work) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "icosphere: out of memory");
    goto done;
  }
  /* The regular icosahedron: cyclic permutations of (0, +-1, +-phi). */
  const double g = 0.5 * (1.0 + sqrt(5.0));
  const double base[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                              {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                              {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const uint32_t faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  double inv_len = 1.0 / sqrt(1.0 + g * g);
  for (int v = 0; v < 12; ++v) {
    for (int k = 0; k < 3; ++k) {
      s.pos[3 * v + k] = base[v][k] * inv_len;
    }
  }
  uint32_t *t0 = subdivisions == 0 ? m->indices : tri[0];
  uint32_t ends[30][2];
  size_t ne = 0;
  for (int f = 0; f < 20; ++f) {
    ss_vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      const double *q = base[faces[f][k]];
      p[k] = ss_vec3_make(q[0], q[1], q[2]);
    }
    ss_vec3 n = ss_vec3_cross(ss_vec3_sub(p[1], p[0]), ss_vec3_sub(p[2], p[0]));
    int flip = ss_vec3_dot(n, p[0]) < 0.0;
    t0[3 * f] = faces[f][0];
    t0[3 * f + 1] = faces[f][flip ? 2 : 1];
    t0[3 * f + 2] = faces[f][flip ? 1 : 2];
    /* The icosahedron's 30 edges get ids in order of appearance. */
    for (int k = 0; k < 3; ++k) {
      uint32_t a = t0[3 * f + k], b = t0[3 * f + (k + 1) % 3];
      size_t e = 0;
      while (e < ne &&
             !((ends[e][0] == a && ends[e][1] == b) || (ends[e][0] == b && ends[e][1] == a))) {
        ++e;
      }
      if (e == ne) {
        ends[ne][0] = a;
        ends[ne++][1] = b;
      }
      edge[0][3 * f + k] = (uint32_t)e;
    }
  }
  size_t nt = 20;
  for (unsigned level = 0; level < subdivisions; ++level) {
    int cur = level & 1, last = level + 1 == subdivisions;
    s.last = last ? m : NULL;
    ico_split(&s, tri[cur], edge[cur], nt, ne, last ? m->indices : tri[!cur],
              last ? NULL : edge[!cur]);
    ne = 2 * ne + 3 * nt;
    nt *= 4;
  }
  for (size_t v = 0; v < nv_prev; ++v) {
    const double *p = s.pos + 3 * v;
    set3(m->positions, v, radius * p[0], radius * p[1], radius * p[2]);
    set3(m->normals, v, p[0], p[1], p[2]);
  }
  if ((st = ss_mesh_spherical_uvs_in_place(m, room, err)) == SS_OK) {
    m->closed = 1;
    *out = m;
    m = NULL;
  }
done:
  ss_mesh_destroy(m);
  free(work);
  return st;
}

/* Coordinate k of n along an edge of length `size` centred at 0; the ends are
 * exact so that faces meeting at an edge agree bit for bit. */
static double grid_coord(double size, unsigned k, unsigned n) {
  if (k == n) {
    return 0.5 * size;
  }
  return -0.5 * size + size * (double)k / (double)n;
}

ss_status ss_shape_cube(ss_vec3 size, unsigned n, ss_mesh **out, ss_error *err) {
  *out = NULL;
  if (!positive_finite(size.x) || !positive_finite(size.y) || !positive_finite(size.z)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "cube: size (%g, %g, %g) must be positive and finite", size.x, size.y,
                        size.z);
  }
  if (n < 1 || n > 4096) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "cube: %u subdivisions per face out of range (expected 1 to 4096)", n);
  }
  size_t per_face_v = ((size_t)n + 1) * ((size_t)n + 1), per_face_t = 2 * (size_t)n * n;
  ss_mesh *m;
  ss_status st =
      ss_mesh_create(6 * per_face_v, 6 * per_face_t, SS_MESH_NORMALS | SS_MESH_UVS, &m, err);
  if (st != SS_OK) {
    return st;
  }
  const double sz[3] = {size.x, size.y, size.z};
  size_t v = 0, t = 0;
  for (int a = 0; a < 3; ++a) {
    for (int s = -1; s <= 1; s += 2) {
      /* Axes (b, c) with e_b x e_c = s e_a make the face wind outward. */
      int b = s > 0 ? (a + 1) % 3 : (a + 2) % 3;
      int c = s > 0 ? (a + 2) % 3 : (a + 1) % 3;
      size_t first = v;
      for (unsigned j = 0; j <= n; ++j) {
        for (unsigned i = 0; i <= n; ++i) {
          double p[3], nrm[3] = {0, 0, 0};
          p[a] = 0.5 * s * sz[a];
          p[b] = grid_coord(sz[b], i, n);
          p[c] = grid_coord(sz[c], j, n);
          nrm[a] = s;
          set3(m->positions, v, p[0], p[1], p[2]);
          set3(m->normals, v, nrm[0], nrm[1], nrm[2]);
          m->uvs[2 * v] = (float)((double)i / n);
          m->uvs[2 * v + 1] = (float)((double)j / n);
          ++v;
        }
      }
      for (unsigned j = 0; j < n; ++j) {
        for (unsigned i = 0; i < n; ++i) {
          size_t v00 = first + (size_t)j * (n + 1) + i, v10 = v00 + 1;
          size_t v01 = v00 + n + 1, v11 = v01 + 1;
          set_tri(m->indices, t++, v00, v10, v11);
          set_tri(m->indices, t++, v00, v11, v01);
        }
      }
    }
  }
  m->closed = 1;
  *out = m;
  return SS_OK;
}

ss_status ss_shape_quad(double width, double height, unsigned nx, unsigned ny, ss_mesh **out,
                        ss_error *err) {
  *out = NULL;
  if (!positive_finite(width) || !positive_finite(height)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "quad: size %g x %g must be positive and finite", width, height);
  }
  if (nx < 1 || ny < 1 || nx > 16384 || ny > 16384) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "quad: tessellation %u x %u out of range (expected 1 to 16384 each)", nx,
                        ny);
  }
  size_t nv = ((size_t)nx + 1) * ((size_t)ny + 1), nt = 2 * (size_t)nx * ny;
  ss_mesh *m;
  ss_status st = ss_mesh_create(nv, nt, SS_MESH_NORMALS | SS_MESH_UVS, &m, err);
  if (st != SS_OK) {
    return st;
  }
  size_t v = 0, t = 0;
  for (unsigned j = 0; j <= ny; ++j) {
    for (unsigned i = 0; i <= nx; ++i) {
      set3(m->positions, v, grid_coord(width, i, nx), grid_coord(height, j, ny), 0.0);
      set3(m->normals, v, 0.0, 0.0, 1.0);
      m->uvs[2 * v] = (float)((double)i / nx);
      m->uvs[2 * v + 1] = (float)((double)j / ny);
      ++v;
    }
  }
  for (unsigned j = 0; j < ny; ++j) {
    for (unsigned i = 0; i < nx; ++i) {
      size_t v00 = (size_t)j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
      set_tri(m->indices, t++, v00, v10, v11);
      set_tri(m->indices, t++, v00, v11, v01);
    }
  }
  *out = m;
  return SS_OK;
}
