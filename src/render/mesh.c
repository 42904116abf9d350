#include "subsurf/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_mesh_create(size_t num_vertices, size_t num_triangles, unsigned flags,
                         ss_mesh **out, ss_error *err) {
  *out = NULL;
  if (num_vertices >= (size_t)UINT32_MAX || num_triangles > SIZE_MAX / 12) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "mesh: %zu vertices / %zu triangles exceed the 32-bit index range",
                        num_vertices, num_triangles);
  }
  ss_mesh *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "mesh: out of memory");
  }
  m->num_vertices = num_vertices;
  m->num_triangles = num_triangles;
  /* +1 keeps malloc(0) from returning NULL for empty meshes. */
  m->positions = malloc((3 * num_vertices + 1) * sizeof *m->positions);
  m->indices = malloc((3 * num_triangles + 1) * sizeof *m->indices);
  int ok = m->positions && m->indices;
  if (flags & SS_MESH_NORMALS) {
    m->normals = malloc((3 * num_vertices + 1) * sizeof *m->normals);
    ok = ok && m->normals;
  }
  if (flags & SS_MESH_UVS) {
    m->uvs = malloc((2 * num_vertices + 1) * sizeof *m->uvs);
    ok = ok && m->uvs;
  }
  if (!ok) {
    ss_mesh_destroy(m);
    return ss_error_set(err, SS_ERR_NO_MEMORY,
                        "mesh: out of memory for %zu vertices and %zu triangles", num_vertices,
                        num_triangles);
  }
  *out = m;
  return SS_OK;
}

void ss_mesh_destroy(ss_mesh *mesh) {
  if (!mesh) {
    return;
  }
  free(mesh->positions);
  free(mesh->normals);
  free(mesh->uvs);
  free(mesh->indices);
  free(mesh);
}

ss_status ss_mesh_clone(const ss_mesh *mesh, ss_mesh **out, ss_error *err) {
  unsigned flags = (mesh->normals ? SS_MESH_NORMALS : 0u) | (mesh->uvs ? SS_MESH_UVS : 0u);
  ss_status st = ss_mesh_create(mesh->num_vertices, mesh->num_triangles, flags, out, err);
  if (st != SS_OK) {
    return st;
  }
  size_t nv = mesh->num_vertices;
  memcpy((*out)->positions, mesh->positions, 3 * nv * sizeof(float));
  memcpy((*out)->indices, mesh->indices, 3 * mesh->num_triangles * sizeof(uint32_t));
  if (mesh->normals) {
    memcpy((*out)->normals, mesh->normals, 3 * nv * sizeof(float));
  }
  if (mesh->uvs) {
    memcpy((*out)->uvs, mesh->uvs, 2 * nv * sizeof(float));
  }
  return SS_OK;
}

void ss_mesh_triangle(const ss_mesh *m, size_t tri, ss_vec3 p[3]) {
  const uint32_t *idx = m->indices + 3 * tri;
  for (int k = 0; k < 3; ++k) {
    p[k] = ss_mesh_position(m, idx[k]);
  }
}

ss_vec3 ss_mesh_triangle_normal(const ss_mesh *m, size_t tri) {
  ss_vec3 p[3];
  ss_mesh_triangle(m, tri, p);
  return ss_vec3_cross(ss_vec3_sub(p[1], p[0]), ss_vec3_sub(p[2], p[0]));
}

double ss_mesh_triangle_area(const ss_mesh *m, size_t tri) {
  return 0.5 * ss_vec3_length(ss_mesh_triangle_normal(m, tri));
}

double ss_mesh_area(const ss_mesh *m) {
  double sum = 0.0;
  for (size_t i = 0; i < m->num_triangles; ++i) {
    sum += ss_mesh_triangle_area(m, i);
  }
  return sum;
}

/* Divergence theorem: V = sum over triangles of p0 . (p1 x p2) / 6. */
double ss_mesh_signed_volume(const ss_mesh *m) {
  double sum = 0.0;
  for (size_t i = 0; i < m->num_triangles; ++i) {
    ss_vec3 p[3];
    ss_mesh_triangle(m, i, p);
    sum += ss_vec3_dot(p[0], ss_vec3_cross(p[1], p[2]));
  }
  return sum / 6.0;
}

void ss_mesh_bounds(const ss_mesh *m, ss_vec3 *lo, ss_vec3 *hi) {
  double l[3] = {INFINITY, INFINITY, INFINITY}, h[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t v = 0; v < m->num_vertices; ++v) {
    for (int k = 0; k < 3; ++k) {
      double x = m->positions[3 * v + (size_t)k];
      l[k] = fmin(l[k], x);
      h[k] = fmax(h[k], x);
    }
  }
  *lo = ss_vec3_make(l[0], l[1], l[2]);
  *hi = ss_vec3_make(h[0], h[1], h[2]);
}

ss_status ss_mesh_transform(ss_mesh *m, ss_mat4 xf, ss_error *err) {
  ss_mat4 inv;
  if (!ss_mat4_inverse(xf, &inv)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "mesh transform: the matrix is singular or not finite");
  }
  for (size_t v = 0; v < m->num_vertices; ++v) {
    float *p = m->positions + 3 * v;
    ss_vec3 q = ss_mat4_apply_point(xf, ss_vec3_make(p[0], p[1], p[2]));
    p[0] = (float)q.x;
    p[1] = (float)q.y;
    p[2] = (float)q.z;
    if (m->normals) {
      float *n = m->normals + 3 * v;
      ss_vec3 t = ss_mat4_apply_normal(inv, ss_vec3_make(n[0], n[1], n[2]));
      double len = ss_vec3_length(t);
      if (len > 0.0) {
        t = ss_vec3_scale(t, 1.0 / len);
      }
      n[0] = (float)t.x;
      n[1] = (float)t.y;
      n[2] = (float)t.z;
    }
  }
  /* A mirroring transform turns counter-clockwise winding clockwise. */
  if (ss_mat4_det3(xf) < 0.0) {
    ss_mesh_flip_winding(m);
  }
  return SS_OK;
}

void ss_mesh_flip_winding(ss_mesh *m) {
  for (size_t i = 0; i < m->num_triangles; ++i) {
    uint32_t t = m->indices[3 * i + 1];
    m->indices[3 * i + 1] = m->indices[3 * i + 2];
    m->indices[3 * i + 2] = t;
  }
}

ss_status ss_mesh_validate(const ss_mesh *m, size_t *num_degenerate, ss_error *err) {
  if (num_degenerate) {
    *num_degenerate = 0;
  }
  for (size_t v = 0; v < m->num_vertices; ++v) {
    const float *p = m->positions + 3 * v;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
      return ss_error_set(err, SS_ERR_PARSE, "vertex %zu has a non-finite position (%g, %g, %g)",
                          v, p[0], p[1], p[2]);
    }
    if (m->normals) {
      const float *n = m->normals + 3 * v;
      if (!isfinite(n[0]) || !isfinite(n[1]) || !isfinite(n[2]) ||
          !(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.0f)) {
        return ss_error_set(err, SS_ERR_PARSE,
                            "vertex %zu has an invalid normal (%g, %g, %g): expected finite "
                            "and non-zero",
                            v, n[0], n[1], n[2]);
      }
    }
    if (m->uvs && (!isfinite(m->uvs[2 * v]) || !isfinite(m->uvs[2 * v + 1]))) {
      return ss_error_set(err, SS_ERR_PARSE, "vertex %zu has non-finite texture coordinates",
                          v);
    }
  }
  size_t degenerate = 0;
  for (size_t i = 0; i < m->num_triangles; ++i) {
    for (int k = 0; k < 3; ++k) {
      uint32_t idx = m->indices[3 * i + (size_t)k];
      if (idx >= m->num_vertices) {
        return ss_error_set(err, SS_ERR_PARSE,
                            "triangle %zu refers to vertex %u but there are %zu vertices", i,
                            idx, m->num_vertices);
      }
    }
    if (!(ss_mesh_triangle_area(m, i) > 0.0)) {
      ++degenerate;
    }
  }
  if (num_degenerate) {
    *num_degenerate = degenerate;
  }
  return SS_OK;
}

typedef struct {
  float p[3];
  uint32_t v;
} weld_key;

static int compare_positions(const void *a, const void *b) {
  const float *p = ((const weld_key *)a)->p, *q = ((const weld_key *)b)->p;
  for (int k = 0; k < 3; ++k) {
    if (p[k] != q[k]) {
      return p[k] < q[k] ? -1 : 1;
    }
  }
  return 0;
}

static int compare_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

static size_t count_edge(const uint64_t *edges, size_t n, uint64_t key) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (edges[mid] < key) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  size_t c = 0;
  while (lo + c < n && edges[lo + c] == key) {
    ++c;
  }
  return c;
}

/* Closedness is a property of the surface, not of the index buffer: shapes
 * with per-face normals or uv seams duplicate vertices, so edges are compared
 * after welding bit-identical positions. */
ss_status ss_mesh_check_closed(const ss_mesh *m, ss_error *err) {
  size_t nv = m->num_vertices, ne = 3 * m->num_triangles;
  weld_key *order = malloc((nv + 1) * sizeof *order);
  uint32_t *weld = malloc((nv + 1) * sizeof *weld);
  uint64_t *edges = malloc((ne + 1) * sizeof *edges);
  ss_status st = SS_OK;
  if (!order || !weld || !edges) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "mesh closedness check: out of memory");
    goto done;
  }
  for (size_t v = 0; v < nv; ++v) {
    memcpy(order[v].p, m->positions + 3 * v, sizeof order[v].p);
    order[v].v = (uint32_t)v;
  }
  qsort(order, nv, sizeof *order, compare_positions);
  for (size_t k = 0; k < nv; ++k) {
    int same = k > 0 && compare_positions(&order[k - 1], &order[k]) == 0;
    weld[order[k].v] = same ? weld[order[k - 1].v] : order[k].v;
  }
  size_t n = 0;
  for (size_t i = 0; i < m->num_triangles; ++i) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = weld[m->indices[3 * i + (size_t)k]];
      uint32_t b = weld[m->indices[3 * i + (size_t)((k + 1) % 3)]];
      if (a != b) {
        edges[n++] = ((uint64_t)a << 32) | b;
      }
    }
  }
  qsort(edges, n, sizeof *edges, compare_u64);
  for (size_t k = 0; k < n; ++k) {
    uint64_t e = edges[k];
    uint32_t a = (uint32_t)(e >> 32), b = (uint32_t)e;
    size_t same = count_edge(edges, n, e);
    size_t twin = count_edge(edges, n, ((uint64_t)b << 32) | a);
    if (same != 1 || twin != 1) {
      st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "mesh is not closed: the edge from vertex %u to vertex %u is used %zu "
                        "time(s) in this direction and %zu time(s) in the opposite one "
                        "(expected 1 and 1)",
                        a, b, same, twin);
      goto done;
    }
  }
done:
  free(order);
  free(weld);
  free(edges);
  return st;
}
