/* Tetrahedral meshes: construction from arrays, boundary faces, point
 * location. The mesher (fem_gmsh.c) fills them through ss_fem_mesh_create. */
#include "fem/fem_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The three vertices of face f of a tetrahedron (the face opposite vertex f). */
static const int face_vertex[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

typedef struct {
  uint32_t key[3]; /* sorted vertex indices */
  uint32_t tet;
  uint8_t face;
} face_rec;

static int face_cmp(const void *pa, const void *pb) {
  const face_rec *a = pa, *b = pb;
  for (int i = 0; i < 3; ++i) {
    if (a->key[i] != b->key[i]) {
      return a->key[i] < b->key[i] ? -1 : 1;
    }
  }
  return 0;
}

static ss_vec3 vertex(const double *p, uint32_t v) {
  return ss_vec3_make(p[3 * (size_t)v], p[3 * (size_t)v + 1], p[3 * (size_t)v + 2]);
}

static double tet_signed_volume6(const double *p, const uint32_t *t) {
  ss_vec3 a = vertex(p, t[0]);
  ss_vec3 e1 = ss_vec3_sub(vertex(p, t[1]), a), e2 = ss_vec3_sub(vertex(p, t[2]), a),
          e3 = ss_vec3_sub(vertex(p, t[3]), a);
  return ss_vec3_dot(ss_vec3_cross(e1, e2), e3);
}

/* The faces that belong to exactly one tetrahedron, wound outward (with
 * positively oriented tetrahedra, face_vertex lists each face outward). */
static ss_status find_boundary(ss_fem_mesh *m, ss_error *err) {
  size_t n = 4 * m->num_tets;
  face_rec *rec = malloc((n ? n : 1) * sizeof *rec);
  if (!rec) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem mesh: out of memory for %zu faces", n);
  }
  for (size_t t = 0; t < m->num_tets; ++t) {
    for (int f = 0; f < 4; ++f) {
      face_rec *r = &rec[4 * t + (size_t)f];
      uint32_t k[3];
      for (int i = 0; i < 3; ++i) {
        k[i] = m->tets[4 * t + (size_t)face_vertex[f][i]];
      }
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2 - i; ++j) {
          if (k[j] > k[j + 1]) {
            uint32_t s = k[j];
            k[j] = k[j + 1];
            k[j + 1] = s;
          }
        }
      }
      memcpy(r->key, k, sizeof k);
      r->tet = (uint32_t)t;
      r->face = (uint8_t)f;
    }
  }
  qsort(rec, n, sizeof *rec, face_cmp);
  size_t count = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    while (j < n && !face_cmp(&rec[i], &rec[j])) {
      ++j;
    }
    if (j - i > 2) {
      ss_status st =
          ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                       "fem mesh: face (%u, %u, %u) is shared by %zu tetrahedra (at most 2)",
                       rec[i].key[0], rec[i].key[1], rec[i].key[2], j - i);
      free(rec);
      return st;
    }
    if (j - i == 1) {
      rec[count++] = rec[i];
    }
    i = j;
  }
  m->faces = malloc((count ? 3 * count : 1) * sizeof *m->faces);
  if (!m->faces) {
    free(rec);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem mesh: out of memory");
  }
  for (size_t i = 0; i < count; ++i) {
    const uint32_t *t = m->tets + 4 * (size_t)rec[i].tet;
    for (int k = 0; k < 3; ++k) {
      m->faces[3 * i + (size_t)k] = t[face_vertex[rec[i].face][k]];
    }
  }
  m->num_faces = count;
  free(rec);
  return SS_OK;
}

ss_status ss_fem_mesh_create(const double *positions, size_t num_vertices, const uint32_t *tets,
                             size_t num_tets, ss_fem_mesh **out, ss_error *err) {
  *out = NULL;
  if (num_tets == 0 || num_vertices < 4 || num_vertices >= UINT32_MAX) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem mesh: %zu vertices and %zu tetrahedra (need at least 4 and 1)",
                        num_vertices, num_tets);
  }
  ss_fem_mesh *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem mesh: out of memory");
  }
  m->num_vertices = num_vertices;
  m->num_tets = num_tets;
  m->positions = malloc(3 * num_vertices * sizeof *m->positions);
  m->tets = malloc(4 * num_tets * sizeof *m->tets);
  if (!m->positions || !m->tets) {
    ss_fem_mesh_destroy(m);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem mesh: out of memory for %zu tetrahedra",
                        num_tets);
  }
  memcpy(m->positions, positions, 3 * num_vertices * sizeof *m->positions);
  memcpy(m->tets, tets, 4 * num_tets * sizeof *m->tets);
  for (size_t i = 0; i < 3 * num_vertices; ++i) {
    if (!isfinite(m->positions[i])) {
      ss_fem_mesh_destroy(m);
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "fem mesh: vertex %zu is not finite",
                          i / 3);
    }
  }
  for (size_t t = 0; t < num_tets; ++t) {
    uint32_t *v = m->tets + 4 * t;
    for (int k = 0; k < 4; ++k) {
      if (v[k] >= num_vertices) {
        uint32_t bad = v[k]; /* v points into m */
        ss_fem_mesh_destroy(m);
        return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                            "fem mesh: tetrahedron %zu has vertex %u (of %zu)", t, bad,
                            num_vertices);
      }
    }
    double vol6 = tet_signed_volume6(m->positions, v);
    if (!(fabs(vol6) > 0.0)) {
      ss_fem_mesh_destroy(m);
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "fem mesh: tetrahedron %zu has zero volume (degenerate)", t);
    }
    if (vol6 < 0.0) {
      uint32_t s = v[2];
      v[2] = v[3];
      v[3] = s;
    }
  }
  ss_status st = find_boundary(m, err);
  if (st != SS_OK) {
    ss_fem_mesh_destroy(m);
    return st;
  }
  *out = m;
  return SS_OK;
}

void ss_fem_mesh_destroy(ss_fem_mesh *mesh) {
  if (!mesh) {
    return;
  }
  free(mesh->positions);
  free(mesh->tets);
  free(mesh->faces);
  free(mesh);
}

void ss_fem_face_vertices(const ss_fem_mesh *mesh, size_t f, ss_vec3 p[3]) {
  for (int k = 0; k < 3; ++k) {
    p[k] = vertex(mesh->positions, mesh->faces[3 * f + (size_t)k]);
  }
}

double ss_fem_mesh_max_edge(const ss_fem_mesh *mesh) {
  double h = 0.0;
  for (size_t t = 0; t < mesh->num_tets; ++t) {
    const uint32_t *v = mesh->tets + 4 * t;
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        double l = ss_vec3_length(
            ss_vec3_sub(vertex(mesh->positions, v[i]), vertex(mesh->positions, v[j])));
        h = l > h ? l : h;
      }
    }
  }
  return h;
}

int ss_fem_tet_barycentric(const ss_fem_mesh *mesh, size_t t, ss_vec3 x, double lambda[4]) {
  /* Barycentric coordinates by signed sub-volumes, with a small tolerance so
   * that points on faces (the boundary) are found. */
  const double tol = 1e-9;
  const uint32_t *v = mesh->tets + 4 * t;
  double vol = tet_signed_volume6(mesh->positions, v);
  for (int k = 0; k < 4; ++k) {
    ss_vec3 q[4];
    for (int i = 0; i < 4; ++i) {
      q[i] = i == k ? x : vertex(mesh->positions, v[i]);
    }
    ss_vec3 e1 = ss_vec3_sub(q[1], q[0]), e2 = ss_vec3_sub(q[2], q[0]),
            e3 = ss_vec3_sub(q[3], q[0]);
    lambda[k] = ss_vec3_dot(ss_vec3_cross(e1, e2), e3) / vol;
    if (!(lambda[k] >= -tol)) {
      return 0;
    }
  }
  return 1;
}

int ss_fem_locate(const ss_fem_mesh *mesh, ss_vec3 x, size_t *tet, double lambda[4]) {
  for (size_t t = 0; t < mesh->num_tets; ++t) {
    if (ss_fem_tet_barycentric(mesh, t, x, lambda)) {
      *tet = t;
      return 1;
    }
  }
  return 0;
}

int ss_fem_interpolate(const ss_fem_mesh *mesh, const double *f, ss_vec3 x, double *value) {
  size_t t;
  double lambda[4];
  *value = 0.0;
  if (!ss_fem_locate(mesh, x, &t, lambda)) {
    return 0;
  }
  for (int k = 0; k < 4; ++k) {
    *value += lambda[k] * f[mesh->tets[4 * t + (size_t)k]];
  }
  return 1;
}
