/* Tetrahedral meshing by gmsh (src/fem/fem_gmsh.c) and the mesh structure
 * (src/fem/fem_mesh.c). */
#include "subsurf/fem.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

static ss_vec3 vtx(const ss_fem_mesh *m, uint32_t v) {
  return ss_vec3_make(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]);
}

static double tet_volume(const ss_fem_mesh *m, size_t t) {
  const uint32_t *v = m->tets + 4 * t;
  ss_vec3 a = vtx(m, v[0]);
  return ss_vec3_dot(ss_vec3_cross(ss_vec3_sub(vtx(m, v[1]), a), ss_vec3_sub(vtx(m, v[2]), a)),
                     ss_vec3_sub(vtx(m, v[3]), a)) /
         6.0;
}

/* Volume of the tetrahedra, and of the boundary by the divergence theorem
 * (int x . n ds / 3: positive only when every face is wound outward). */
static void volumes(const ss_fem_mesh *m, double *tets, double *boundary, double *area) {
  *tets = *boundary = *area = 0.0;
  for (size_t t = 0; t < m->num_tets; ++t) {
    double v = tet_volume(m, t);
    cr_assert(v > 0.0, "tetrahedron %zu is not positively oriented", t);
    *tets += v;
  }
  for (size_t f = 0; f < m->num_faces; ++f) {
    const uint32_t *v = m->faces + 3 * f;
    ss_vec3 p0 = vtx(m, v[0]);
    ss_vec3 n = ss_vec3_cross(ss_vec3_sub(vtx(m, v[1]), p0), ss_vec3_sub(vtx(m, v[2]), p0));
    *boundary += ss_vec3_dot(p0, n) / 6.0;
    *area += 0.5 * ss_vec3_length(n);
  }
}

Test(fem_mesh, box_mesh_fills_the_box_and_its_boundary_is_closed_and_outward) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = 0.5, .size_min = 0.5};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-1, -2, -3), ss_vec3_make(1, 1, 0), &o, &m, &err),
               SS_OK, "%s", err.message);
  double vt, vb, area;
  volumes(m, &vt, &vb, &area);
  cr_assert_float_eq(vt, 18.0, 1e-9);
  cr_assert_float_eq(vb, 18.0, 1e-9);
  cr_assert_float_eq(area, 2.0 * (2 * 3 + 2 * 3 + 3 * 3), 1e-9);
  /* gmsh honours the size: no edge much longer than requested */
  cr_assert_lt(ss_fem_mesh_max_edge(m), 2.0 * 0.5);
  ss_fem_mesh_destroy(m);
}

static double max_edge_near(const ss_fem_mesh *m, ss_vec3 c, double radius) {
  double h = 0.0;
  for (size_t t = 0; t < m->num_tets; ++t) {
    const uint32_t *v = m->tets + 4 * t;
    ss_vec3 p[4];
    for (int k = 0; k < 4; ++k) {
      p[k] = vtx(m, v[k]);
    }
    ss_vec3 g = ss_vec3_scale(ss_vec3_add(ss_vec3_add(p[0], p[1]), ss_vec3_add(p[2], p[3])), 0.25);
    if (ss_vec3_length(ss_vec3_sub(g, c)) > radius) {
      continue;
    }
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        double l = ss_vec3_length(ss_vec3_sub(p[i], p[j]));
        h = l > h ? l : h;
      }
    }
  }
  return h;
}

Test(fem_mesh, refinement_makes_elements_small_near_the_source_only) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = 1.0,
                           .size_min = 0.1,
                           .refine_center = ss_vec3_make(0, 0, 0),
                           .refine_radius = 0.3,
                           .refine_grade = 2.0};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-4, -4, -4), ss_vec3_make(4, 4, 0), &o, &m, &err),
               SS_OK, "%s", err.message);
  cr_assert_lt(max_edge_near(m, o.refine_center, 0.3), 2.5 * 0.1);
  cr_assert_gt(ss_fem_mesh_max_edge(m), 0.7);
  ss_fem_mesh_destroy(m);
}

/* The longest edge of the boundary triangles with a vertex within `tol` of
 * the circle of radius r about the origin in the plane z = 0. */
static double max_edge_at_rim(const ss_fem_mesh *m, double r, double tol) {
  double h = 0.0;
  for (size_t f = 0; f < m->num_faces; ++f) {
    const uint32_t *v = m->faces + 3 * f;
    int at_rim = 0;
    for (int k = 0; k < 3; ++k) {
      ss_vec3 p = vtx(m, v[k]);
      at_rim |= fabs(p.z) < 1e-9 && fabs(hypot(p.x, p.y) - r) < tol;
    }
    for (int k = 0; at_rim && k < 3; ++k) {
      h = fmax(h, ss_vec3_length(ss_vec3_sub(vtx(m, v[k]), vtx(m, v[(k + 1) % 3]))));
    }
  }
  return h;
}

Test(fem_mesh, rim_refinement_makes_elements_small_along_the_spot_edge_only) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = 1.0,
                           .size_min = 0.3,
                           .refine_center = ss_vec3_make(0, 0, 0),
                           .refine_radius = 1.5,
                           .refine_grade = 2.0,
                           .rim_radius = 1.0,
                           .rim_size = 0.08};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-4, -4, -4), ss_vec3_make(4, 4, 0), &o, &m, &err),
               SS_OK, "%s", err.message);
  cr_assert_lt(max_edge_at_rim(m, 1.0, 0.02), 2.5 * 0.08);
  /* the spot's centre is 1 away from its rim: there the graded size 0.3 */
  cr_assert_gt(max_edge_near(m, o.refine_center, 0.3), 0.2);
  ss_fem_mesh_destroy(m);
  o.rim_radius = 0.0;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-4, -4, -4), ss_vec3_make(4, 4, 0), &o, &m, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "rim"), "%s", err.message);
  cr_assert_null(m);
}

/* The octahedron |x| + |y| + |z| <= 1, wound outward. */
static const float octa_p[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
static const uint32_t octa_t[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                  2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};

Test(fem_mesh, closed_surface_is_filled_to_its_volume) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = 0.2, .size_min = 0.2};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_surface(octa_p, 6, octa_t, 8, &o, &m, &err), SS_OK, "%s", err.message);
  double vt, vb, area;
  volumes(m, &vt, &vb, &area);
  cr_assert_float_eq(vt, 4.0 / 3.0, 1e-9);
  cr_assert_float_eq(vb, 4.0 / 3.0, 1e-9);
  cr_assert_float_eq(area, 8.0 * sqrt(3.0) / 2.0, 1e-9);
  cr_assert_gt(m->num_tets, 100, "the surface was re-meshed to the requested size");
  ss_fem_mesh_destroy(m);
}

Test(fem_mesh, open_surface_is_a_mesher_error) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = 0.2, .size_min = 0.2};
  ss_fem_mesh *m = NULL;
  cr_assert_neq(ss_fem_mesh_surface(octa_p, 6, octa_t, 7, &o, &m, &err), SS_OK);
  cr_assert_null(m);
  cr_assert(strstr(err.message, "fem mesh"), "%s", err.message);
}

Test(fem_mesh, degenerate_tetrahedron_is_named) {
  const double p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const uint32_t t[] = {0, 1, 2, 3};
  ss_error err = {0};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_create(p, 4, t, 1, &m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "tetrahedron 0 has zero volume"), "%s", err.message);
}

Test(fem_mesh, bad_sizes_are_refused_before_meshing) {
  ss_error err = {0};
  ss_fem_mesh *m = NULL;
  ss_fem_mesh_options o = {.size_max = 0.1, .size_min = 0.2};
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(0, 0, 0), ss_vec3_make(1, 1, 1), &o, &m, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "min 0.2, max 0.1"), "%s", err.message);
  o.size_max = NAN;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(0, 0, 0), ss_vec3_make(1, 1, 1), &o, &m, &err),
               SS_ERR_INVALID_ARGUMENT);
}
