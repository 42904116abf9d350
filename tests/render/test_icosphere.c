/* The icosphere generator (edge ids in arrays, uvs added in place) builds
 * bit for bit the mesh of the straightforward construction it replaced:
 * subdivision with the midpoint of each edge found by searching the edges
 * made so far, then ss_mesh_add_spherical_uvs on a copy. Same vertices in
 * the same order, same triangles, so renders of sphere scenes are
 * unchanged. Generated closed shapes carry the closed mark (mesh.h). */
#include <criterion/criterion.h>

#include "subsurf/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  uint32_t a, b, mid;
} edge_entry;

/* The midpoint vertex of (a, b): found among the edges made so far, or
 * made from (min, max) as the generator documents. */
static uint32_t midpoint(edge_entry *edges, size_t *ne, double *pos, size_t *nv, uint32_t a,
                         uint32_t b) {
  if (a > b) {
    uint32_t t = a;
    a = b;
    b = t;
  }
  for (size_t e = 0; e < *ne; ++e) {
    if (edges[e].a == a && edges[e].b == b) {
      return edges[e].mid;
    }
  }
  double x = pos[3 * a] + pos[3 * b], y = pos[3 * a + 1] + pos[3 * b + 1];
  double z = pos[3 * a + 2] + pos[3 * b + 2];
  double inv = 1.0 / sqrt(x * x + y * y + z * z);
  uint32_t v = (uint32_t)(*nv)++;
  pos[3 * v] = x * inv;
  pos[3 * v + 1] = y * inv;
  pos[3 * v + 2] = z * inv;
  edges[(*ne)++] = (edge_entry){a, b, v};
  return v;
}

static ss_mesh *reference_icosphere(double radius, unsigned subdivisions) {
  size_t pow4 = (size_t)1 << (2 * subdivisions);
  size_t nv_final = 10 * pow4 + 2, nt_final = 20 * pow4;
  double *pos = malloc(3 * nv_final * sizeof *pos);
  uint32_t *tri = malloc(3 * nt_final * sizeof *tri), *next = malloc(3 * nt_final * sizeof *next);
  edge_entry *edges = malloc(3 * nt_final * sizeof *edges);
  cr_assert(pos && tri && next && edges);
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
      pos[3 * v + k] = base[v][k] * inv_len;
    }
  }
  for (int f = 0; f < 20; ++f) {
    ss_vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = ss_vec3_make(base[faces[f][k]][0], base[faces[f][k]][1], base[faces[f][k]][2]);
    }
    ss_vec3 n = ss_vec3_cross(ss_vec3_sub(p[1], p[0]), ss_vec3_sub(p[2], p[0]));
    int flip = ss_vec3_dot(n, p[0]) < 0.0;
    tri[3 * f] = faces[f][0];
    tri[3 * f + 1] = faces[f][flip ? 2 : 1];
    tri[3 * f + 2] = faces[f][flip ? 1 : 2];
  }
  size_t nv = 12, nt = 20;
  for (unsigned level = 0; level < subdivisions; ++level) {
    size_t ne = 0;
    for (size_t f = 0; f < nt; ++f) {
      uint32_t a = tri[3 * f], b = tri[3 * f + 1], c = tri[3 * f + 2];
      uint32_t ab = midpoint(edges, &ne, pos, &nv, a, b);
      uint32_t bc = midpoint(edges, &ne, pos, &nv, b, c);
      uint32_t ca = midpoint(edges, &ne, pos, &nv, c, a);
      const uint32_t kids[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
      memcpy(next + 12 * f, kids, sizeof kids);
    }
    nt *= 4;
    uint32_t *swap = tri;
    tri = next;
    next = swap;
  }
  cr_assert_eq(nv, nv_final);
  ss_mesh *m, *out;
  ss_error err;
  cr_assert_eq(ss_mesh_create(nv, nt, SS_MESH_NORMALS, &m, &err), SS_OK);
  for (size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) {
      m->positions[3 * v + k] = (float)(radius * pos[3 * v + k]);
      m->normals[3 * v + k] = (float)pos[3 * v + k];
    }
  }
  memcpy(m->indices, tri, 3 * nt * sizeof *tri);
  cr_assert_eq(ss_mesh_add_spherical_uvs(m, &out, &err), SS_OK, "%s", err.message);
  ss_mesh_destroy(m);
  free(pos);
  free(tri);
  free(next);
  free(edges);
  return out;
}

Test(icosphere, equals_the_straightforward_subdivision_bit_for_bit) {
  for (unsigned level = 0; level <= 4; ++level) {
    double radius = level == 3 ? 2.5 : 1.0;
    ss_mesh *want = reference_icosphere(radius, level), *got;
    ss_error err;
    cr_assert_eq(ss_shape_icosphere(radius, level, &got, &err), SS_OK, "%s", err.message);
    cr_assert_eq(got->num_vertices, want->num_vertices, "level %u", level);
    cr_assert_eq(got->num_triangles, want->num_triangles, "level %u", level);
    size_t nv = got->num_vertices;
    cr_assert(!memcmp(got->positions, want->positions, 3 * nv * sizeof(float)), "level %u", level);
    cr_assert(!memcmp(got->normals, want->normals, 3 * nv * sizeof(float)), "level %u", level);
    cr_assert(!memcmp(got->uvs, want->uvs, 2 * nv * sizeof(float)), "level %u", level);
    cr_assert(!memcmp(got->indices, want->indices, 3 * got->num_triangles * sizeof(uint32_t)),
              "level %u", level);
    ss_mesh_destroy(want);
    ss_mesh_destroy(got);
  }
}

Test(icosphere, generated_closed_shapes_are_marked_and_the_mark_is_true) {
  ss_mesh *m[4];
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(1.0, 6, &m[0], &err), SS_OK);
  cr_assert_eq(ss_shape_sphere_uv(1.0, 9, 14, &m[1], &err), SS_OK);
  cr_assert_eq(ss_shape_cube(ss_vec3_make(1, 2, 3), 4, &m[2], &err), SS_OK);
  cr_assert_eq(ss_shape_quad(1.0, 1.0, 3, 3, &m[3], &err), SS_OK);
  for (int k = 0; k < 3; ++k) {
    cr_assert(m[k]->closed, "shape %d", k);
    cr_assert_eq(ss_mesh_check_closed(m[k], &err), SS_OK, "shape %d: %s", k, err.message);
    cr_assert_gt(ss_mesh_signed_volume(m[k]), 0.0, "shape %d winds outward", k);
    /* A mirroring transform keeps the mesh closed and outward (mesh.h). */
    cr_assert_eq(ss_mesh_transform(m[k], ss_mat4_scale(ss_vec3_make(-1, 2, 1)), &err), SS_OK);
    cr_assert(m[k]->closed);
    cr_assert_eq(ss_mesh_check_closed(m[k], &err), SS_OK, "shape %d: %s", k, err.message);
    cr_assert_gt(ss_mesh_signed_volume(m[k]), 0.0, "shape %d winds outward", k);
    ss_mesh *copy;
    cr_assert_eq(ss_mesh_clone(m[k], &copy, &err), SS_OK);
    cr_assert(copy->closed);
    ss_mesh_destroy(copy);
  }
  cr_assert(!m[3]->closed);
  for (int k = 0; k < 4; ++k) {
    ss_mesh_destroy(m[k]);
  }
}
