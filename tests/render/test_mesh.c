#include "subsurf/mesh.h"
#include "subsurf/sampling.h"
#include "subsurf/transform.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static ss_mesh *make_cube(ss_vec3 size, unsigned n) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_cube(size, n, &m, &err), SS_OK, "%s", err.message);
  return m;
}

static double max_matrix_diff(ss_mat4 a, ss_mat4 b) {
  double d = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      d = fmax(d, fabs(a.m[i][j] - b.m[i][j]));
    }
  }
  return d;
}

Test(mesh, cube_area_volume_and_closedness_match_the_box) {
  ss_vec3 size = ss_vec3_make(1.0, 2.0, 3.0);
  ss_mesh *m = make_cube(size, 5);
  ss_error err;
  cr_assert_eq(m->num_triangles, 6u * 2 * 25);
  cr_assert_float_eq(ss_mesh_area(m), 2.0 * (2.0 + 6.0 + 3.0), 1e-5);
  cr_assert_float_eq(ss_mesh_signed_volume(m), 6.0, 1e-5);
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
  size_t degenerate = 99;
  cr_assert_eq(ss_mesh_validate(m, &degenerate, &err), SS_OK, "%s", err.message);
  cr_assert_eq(degenerate, 0u);
  ss_vec3 lo, hi;
  ss_mesh_bounds(m, &lo, &hi);
  cr_assert_float_eq(lo.x, -0.5, 0.0);
  cr_assert_float_eq(hi.z, 1.5, 0.0);
  /* Per-face normals agree with the winding, which points outward. */
  for (size_t t = 0; t < m->num_triangles; ++t) {
    ss_vec3 ng = ss_vec3_normalize(ss_mesh_triangle_normal(m, t));
    const float *n = m->normals + 3 * (size_t)m->indices[3 * t];
    cr_assert_float_eq(ss_vec3_dot(ng, ss_vec3_make(n[0], n[1], n[2])), 1.0, 1e-6);
  }
  ss_mesh_destroy(m);
}

static double uv_sphere_area_error(unsigned n) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_sphere_uv(2.0, n, 2 * n, &m, &err), SS_OK, "%s", err.message);
  double rel = fabs(ss_mesh_area(m) - 16.0 * SS_PI) / (16.0 * SS_PI);
  ss_mesh_destroy(m);
  return rel;
}

Test(mesh, uv_sphere_area_converges_quadratically_to_four_pi_r2) {
  double e1 = uv_sphere_area_error(32), e2 = uv_sphere_area_error(64);
  cr_assert_lt(e2, 2e-3, "relative area error %g at 64 rings", e2);
  /* An inscribed polyhedron's area deficit is O(h^2): halving h divides it by 4. */
  cr_assert(e1 / e2 > 3.5 && e1 / e2 < 4.5, "error ratio %g, expected ~4", e1 / e2);
}

Test(mesh, uv_sphere_is_closed_outward_and_on_the_sphere) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_sphere_uv(1.5, 17, 23, &m, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
  size_t degenerate = 99;
  cr_assert_eq(ss_mesh_validate(m, &degenerate, &err), SS_OK, "%s", err.message);
  cr_assert_eq(degenerate, 0u);
  cr_assert_gt(ss_mesh_signed_volume(m), 0.9 * 4.0 / 3.0 * SS_PI * 1.5 * 1.5 * 1.5);
  for (size_t v = 0; v < m->num_vertices; ++v) {
    cr_assert_float_eq(ss_vec3_length(ss_mesh_position(m, (uint32_t)v)), 1.5, 1e-6);
  }
  ss_mesh_destroy(m);
}

static int compare_float3(const void *a, const void *b) { return memcmp(a, b, 3 * sizeof(float)); }

/* Number of bit-distinct vertex positions. */
static size_t distinct_positions(const ss_mesh *m) {
  float *p = malloc(3 * m->num_vertices * sizeof *p);
  cr_assert_not_null(p);
  memcpy(p, m->positions, 3 * m->num_vertices * sizeof *p);
  qsort(p, m->num_vertices, 3 * sizeof *p, compare_float3);
  size_t n = m->num_vertices > 0;
  for (size_t v = 1; v < m->num_vertices; ++v) {
    n += memcmp(p + 3 * v, p + 3 * (v - 1), 3 * sizeof *p) != 0;
  }
  free(p);
  return n;
}

Test(mesh, icosphere_counts_closedness_and_area) {
  ss_error err;
  double prev_err = 0.0;
  for (unsigned k = 0; k <= 5; ++k) {
    ss_mesh *m = NULL;
    cr_assert_eq(ss_shape_icosphere(1.0, k, &m, &err), SS_OK, "%s", err.message);
    cr_assert_eq(m->num_triangles, 20u << (2 * k));
    /* seam and pole vertices are duplicated for the uvs (mesh.h) */
    cr_assert_eq(distinct_positions(m), 10u * (1u << (2 * k)) + 2);
    cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "level %u: %s", k, err.message);
    for (size_t v = 0; v < m->num_vertices; ++v) {
      cr_assert_float_eq(ss_vec3_length(ss_mesh_position(m, (uint32_t)v)), 1.0, 1e-6);
    }
    double rel = (4.0 * SS_PI - ss_mesh_area(m)) / (4.0 * SS_PI);
    cr_assert_gt(rel, 0.0, "an inscribed polyhedron has less area than the sphere");
    if (k >= 3) {
      cr_assert(prev_err / rel > 3.5 && prev_err / rel < 4.5, "level %u ratio %g", k,
                prev_err / rel);
    }
    prev_err = rel;
    ss_mesh_destroy(m);
  }
  cr_assert_lt(prev_err, 2e-3);
}

Test(mesh, quad_has_the_area_of_the_rectangle_and_is_open) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_quad(3.0, 0.5, 7, 2, &m, &err), SS_OK, "%s", err.message);
  cr_assert_float_eq(ss_mesh_area(m), 1.5, 1e-6);
  for (size_t t = 0; t < m->num_triangles; ++t) {
    cr_assert_gt(ss_mesh_triangle_normal(m, t).z, 0.0);
  }
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "not closed") != NULL, "%s", err.message);
  ss_mesh_destroy(m);
}

Test(mesh, removing_a_triangle_opens_a_closed_mesh) {
  ss_mesh *m = make_cube(ss_vec3_make(1, 1, 1), 2);
  ss_error err;
  m->num_triangles -= 1;
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_ERR_INVALID_ARGUMENT);
  ss_mesh_destroy(m);
}

Test(mesh, shapes_reject_bad_parameters) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_sphere_uv(-1.0, 8, 8, &m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "radius") != NULL);
  cr_assert_eq(ss_shape_sphere_uv(1.0, 1, 8, &m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_eq(ss_shape_icosphere(NAN, 2, &m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_eq(ss_shape_icosphere(1.0, 11, &m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_eq(ss_shape_cube(ss_vec3_make(1, 0, 1), 1, &m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_eq(ss_shape_quad(1.0, 1.0, 0, 1, &m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_null(m);
}

Test(mesh, transform_scales_area_and_volume_and_keeps_outward_winding) {
  ss_mesh *m = make_cube(ss_vec3_make(1, 1, 1), 3);
  ss_error err;
  ss_mat4 xf = ss_mat4_mul(ss_mat4_translate(ss_vec3_make(1, -2, 3)),
                           ss_mat4_mul(ss_mat4_rotate(37.0, ss_vec3_make(1, 2, 3)),
                                       ss_mat4_scale(ss_vec3_make(2, 3, 4))));
  cr_assert_eq(ss_mesh_transform(m, xf, &err), SS_OK, "%s", err.message);
  cr_assert_float_eq(ss_mesh_signed_volume(m), 24.0, 1e-4);
  cr_assert_float_eq(ss_mesh_area(m), 2.0 * (6.0 + 12.0 + 8.0), 1e-4);
  /* A mirror keeps the volume positive: the winding is flipped with it. */
  cr_assert_eq(ss_mesh_transform(m, ss_mat4_scale(ss_vec3_make(-1, 1, 1)), &err), SS_OK);
  cr_assert_float_eq(ss_mesh_signed_volume(m), 24.0, 1e-4);
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
  /* The normals still agree with the (flipped) winding. */
  for (size_t t = 0; t < m->num_triangles; ++t) {
    ss_vec3 ng = ss_vec3_normalize(ss_mesh_triangle_normal(m, t));
    const float *n = m->normals + 3 * (size_t)m->indices[3 * t];
    cr_assert_float_eq(ss_vec3_dot(ng, ss_vec3_make(n[0], n[1], n[2])), 1.0, 1e-5);
  }
  ss_mat4 singular = ss_mat4_scale(ss_vec3_make(1, 0, 1));
  cr_assert_eq(ss_mesh_transform(m, singular, &err), SS_ERR_INVALID_ARGUMENT);
  ss_mesh_destroy(m);
}

Test(mesh, normals_transform_by_the_inverse_transpose) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(1.0, 3, &m, &err), SS_OK, "%s", err.message);
  const double a = 3.0, b = 0.5, c = 1.5;
  cr_assert_eq(ss_mesh_transform(m, ss_mat4_scale(ss_vec3_make(a, b, c)), &err), SS_OK);
  /* An ellipsoid's normal is the gradient (x/a^2, y/b^2, z/c^2). */
  for (size_t v = 0; v < m->num_vertices; ++v) {
    ss_vec3 p = ss_mesh_position(m, (uint32_t)v);
    ss_vec3 g = ss_vec3_normalize(ss_vec3_make(p.x / (a * a), p.y / (b * b), p.z / (c * c)));
    const float *n = m->normals + 3 * v;
    cr_assert_float_eq(ss_vec3_dot(g, ss_vec3_make(n[0], n[1], n[2])), 1.0, 1e-5);
  }
  ss_mesh_destroy(m);
}

Test(mesh, validate_reports_nan_out_of_range_and_degenerate_triangles) {
  ss_mesh *m = make_cube(ss_vec3_make(1, 1, 1), 1);
  ss_error err;
  size_t degenerate;
  m->positions[3 * 3 + 1] = NAN;
  cr_assert_eq(ss_mesh_validate(m, &degenerate, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "vertex 3") != NULL, "%s", err.message);
  m->positions[3 * 3 + 1] = 0.5f;
  m->indices[3 * 5 + 2] = (uint32_t)m->num_vertices;
  cr_assert_eq(ss_mesh_validate(m, &degenerate, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "triangle 5") != NULL, "%s", err.message);
  m->indices[3 * 5 + 2] = m->indices[3 * 5];
  cr_assert_eq(ss_mesh_validate(m, &degenerate, &err), SS_OK, "%s", err.message);
  cr_assert_eq(degenerate, 1u);
  m->normals[0] = 0.0f;
  m->normals[1] = 0.0f;
  m->normals[2] = 0.0f;
  cr_assert_eq(ss_mesh_validate(m, &degenerate, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "normal") != NULL, "%s", err.message);
  ss_mesh_destroy(m);
}

Test(mesh, clone_is_a_deep_copy) {
  ss_mesh *m = make_cube(ss_vec3_make(1, 1, 1), 2), *c = NULL;
  ss_error err;
  cr_assert_eq(ss_mesh_clone(m, &c, &err), SS_OK);
  c->positions[0] += 1.0f;
  cr_assert_neq(c->positions[0], m->positions[0]);
  cr_assert_eq(memcmp(c->indices, m->indices, 3 * m->num_triangles * sizeof(uint32_t)), 0);
  cr_assert_not_null(c->normals);
  cr_assert_not_null(c->uvs);
  ss_mesh_destroy(m);
  ss_mesh_destroy(c);
}

Test(transform, inverse_times_matrix_is_identity) {
  ss_mat4 xf = ss_mat4_mul(ss_mat4_translate(ss_vec3_make(4, 5, -6)),
                           ss_mat4_mul(ss_mat4_rotate(-71.0, ss_vec3_make(0.3, -1, 2)),
                                       ss_mat4_scale(ss_vec3_make(0.1, 7, 2))));
  ss_mat4 inv;
  cr_assert(ss_mat4_inverse(xf, &inv));
  cr_assert_lt(max_matrix_diff(ss_mat4_mul(xf, inv), ss_mat4_identity()), 1e-12);
  cr_assert_lt(max_matrix_diff(ss_mat4_mul(inv, xf), ss_mat4_identity()), 1e-12);
  cr_assert_not(ss_mat4_inverse(ss_mat4_scale(ss_vec3_make(1, 1, 0)), &inv));
}

Test(transform, rotation_is_right_handed_and_orthonormal) {
  ss_mat4 r = ss_mat4_rotate(90.0, ss_vec3_make(0, 0, 2));
  ss_vec3 x = ss_mat4_apply_vector(r, ss_vec3_make(1, 0, 0));
  cr_assert_float_eq(x.y, 1.0, 1e-15);
  cr_assert_float_eq(x.x, 0.0, 1e-15);
  ss_mat4 q = ss_mat4_rotate(33.0, ss_vec3_make(1, 1, -1));
  cr_assert_lt(max_matrix_diff(ss_mat4_mul(q, ss_mat4_transpose(q)), ss_mat4_identity()), 1e-14);
  cr_assert_float_eq(ss_mat4_det3(q), 1.0, 1e-14);
}

Test(transform, look_at_maps_camera_axes_to_the_view) {
  ss_mat4 c2w;
  cr_assert(
      ss_mat4_look_at(ss_vec3_make(0, 0, 5), ss_vec3_make(0, 0, 0), ss_vec3_make(0, 1, 0), &c2w));
  ss_vec3 o = ss_mat4_apply_point(c2w, ss_vec3_make(0, 0, 0));
  ss_vec3 fwd = ss_mat4_apply_vector(c2w, ss_vec3_make(0, 0, 1));
  ss_vec3 right = ss_mat4_apply_vector(c2w, ss_vec3_make(1, 0, 0));
  ss_vec3 up = ss_mat4_apply_vector(c2w, ss_vec3_make(0, 1, 0));
  cr_assert_float_eq(o.z, 5.0, 1e-15);
  cr_assert_float_eq(fwd.z, -1.0, 1e-15);
  cr_assert_float_eq(right.x, 1.0, 1e-15);
  cr_assert_float_eq(up.y, 1.0, 1e-15);
  cr_assert_not(
      ss_mat4_look_at(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 1, 0), ss_vec3_make(0, 1, 0), &c2w));
}
