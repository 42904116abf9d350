#include "subsurf/mesh.h"

#include "core/large_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_mesh_create(size_t num_vertices, size_t num_triangles, unsigned flags, ss_mesh **out,
                         ss_error *err) {
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
  m->positions = ss_large_alloc((3 * num_vertices + 1) * sizeof *m->positions);
  m->indices = ss_large_alloc((3 * num_triangles + 1) * sizeof *m->indices);
  int ok = m->positions && m->indices;
  if (flags & SS_MESH_NORMALS) {
    m->normals = ss_large_alloc((3 * num_vertices + 1) * sizeof *m->normals);
    ok = ok && m->normals;
  }
  if (flags & SS_MESH_UVS) {
    m->uvs = ss_large_alloc((2 * num_vertices + 1) * sizeof *m->uvs);
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
  (*out)->closed = mesh->closed;
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
      return ss_error_set(err, SS_ERR_PARSE, "vertex %zu has a non-finite position (%g, %g, %g)", v,
                          p[0], p[1], p[2]);
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
      return ss_error_set(err, SS_ERR_PARSE, "vertex %zu has non-finite texture coordinates", v);
    }
  }
  size_t degenerate = 0;
  for (size_t i = 0; i < m->num_triangles; ++i) {
    for (int k = 0; k < 3; ++k) {
      uint32_t idx = m->indices[3 * i + (size_t)k];
      if (idx >= m->num_vertices) {
        return ss_error_set(err, SS_ERR_PARSE,
                            "triangle %zu refers to vertex %u but there are %zu vertices", i, idx,
                            m->num_vertices);
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

/* An open-addressing hash table (linear probing, power-of-two capacity at
 * least twice the entries) welds the positions, and a counting sort groups
 * the edges: the closedness check is linear in the mesh size (sorting every
 * edge cost 0.3 s on a 327 k-triangle sphere). */
static size_t table_capacity(size_t n) {
  size_t cap = 16;
  while (cap < 2 * n) {
    cap *= 2;
  }
  return cap;
}

/* splitmix64's finaliser: a well-mixed hash of a 64-bit key. */
static uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ULL;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/* Welds equal positions (compared as floats, so -0 equals +0): weld[v] is
 * the first vertex with v's position. `slots` holds vertex index + 1 (0:
 * empty). */
static void weld_positions(const ss_mesh *m, uint32_t *slots, size_t mask, uint32_t *weld) {
  for (size_t v = 0; v < m->num_vertices; ++v) {
    const float *p = m->positions + 3 * v;
    float q[3] = {p[0] + 0.0f, p[1] + 0.0f, p[2] + 0.0f}; /* -0 + 0 = +0 */
    uint32_t bits[3];
    memcpy(bits, q, sizeof bits);
    uint64_t key = mix64(((uint64_t)bits[0] << 32 | bits[1]) ^ mix64(bits[2]));
    size_t h = (size_t)key & mask;
    for (;; h = (h + 1) & mask) {
      if (slots[h] == 0) {
        slots[h] = (uint32_t)v + 1;
        weld[v] = (uint32_t)v;
        break;
      }
      const float *r = m->positions + 3 * (size_t)(slots[h] - 1);
      if (r[0] == p[0] && r[1] == p[1] && r[2] == p[2]) {
        weld[v] = slots[h] - 1;
        break;
      }
    }
  }
}

/* How many of the n targets in `list` equal v. */
static uint32_t count_target(const uint32_t *list, uint32_t n, uint32_t v) {
  uint32_t c = 0;
  for (uint32_t k = 0; k < n; ++k) {
    c += list[k] == v;
  }
  return c;
}

/* Closedness is a property of the surface, not of the index buffer: shapes
 * with per-face normals or uv seams duplicate vertices, so edges are compared
 * after welding bit-identical positions. Closed: every directed edge a -> b is
 * used exactly once, and so is its twin b -> a. The directed edges are
 * grouped by their first vertex (a counting sort into compressed rows), so
 * each check scans a vertex's few outgoing edges. */
ss_status ss_mesh_check_closed(const ss_mesh *m, ss_error *err) {
  size_t nv = m->num_vertices, nt = m->num_triangles;
  size_t vcap = table_capacity(nv);
  uint32_t *slots = calloc(vcap, sizeof *slots);
  uint32_t *weld = malloc((nv + 1) * sizeof *weld);
  uint32_t *row = calloc(nv + 2, sizeof *row);
  uint32_t *target = malloc((3 * nt + 1) * sizeof *target);
  ss_status st = SS_OK;
  if (!slots || !weld || !row || !target) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "mesh closedness check: out of memory");
    goto done;
  }
  weld_positions(m, slots, vcap - 1, weld);
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < nt; ++i) {
      for (int k = 0; k < 3; ++k) {
        uint32_t a = weld[m->indices[3 * i + (size_t)k]];
        uint32_t b = weld[m->indices[3 * i + (size_t)((k + 1) % 3)]];
        if (a == b) {
          continue;
        }
        if (pass == 0) {
          row[a + 2]++;
        } else {
          target[row[a + 1]++] = b;
        }
      }
    }
    for (size_t v = 0; pass == 0 && v < nv; ++v) {
      row[v + 2] += row[v + 1];
    }
  }
  /* row[a] .. row[a + 1] now delimit the targets of a's edges. */
  for (uint32_t a = 0; a < (uint32_t)nv; ++a) {
    for (uint32_t k = row[a]; k < row[a + 1]; ++k) {
      uint32_t b = target[k];
      uint32_t same = count_target(target + row[a], row[a + 1] - row[a], b);
      uint32_t twin = count_target(target + row[b], row[b + 1] - row[b], a);
      if (same != 1 || twin != 1) {
        st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "mesh is not closed: the edge from vertex %u to vertex %u is used %u "
                          "time(s) in this direction and %u time(s) in the opposite one "
                          "(expected 1 and 1)",
                          a, b, same, twin);
        goto done;
      }
    }
  }
done:
  free(slots);
  free(weld);
  free(row);
  free(target);
  return st;
}
