/* The blue-noise points of pass 1 of the `hierarchical` integrator
 * (poisson_disk.c; Cook 1986 dart throwing, Jensen & Buhler 2002 sec. 3):
 * on the surface with its face normal, each the same share of the area,
 * spread by area, and kept apart by a minimum distance that white noise
 * would violate. */
#include "subsurf/irradiance_points.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#define COUNT 3000

static ss_irradiance_point *cube_points(ss_mesh **mesh) {
  ss_error err;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(2, 2, 2), 12, mesh, &err), SS_OK, "%s", err.message);
  ss_irradiance_point *p = malloc(COUNT * sizeof *p);
  cr_assert_not_null(p);
  cr_assert_eq(ss_poisson_disk_points(*mesh, 3, COUNT, 7, p, &err), SS_OK, "%s", err.message);
  return p;
}

/* Which face of the cube [-1, 1]^3 a point lies on (0..5), -1: on none. */
static int face_of(ss_vec3 p, ss_vec3 n) {
  double c[3] = {p.x, p.y, p.z}, m[3] = {n.x, n.y, n.z};
  for (int a = 0; a < 3; ++a) {
    if (fabs(fabs(c[a]) - 1.0) < 1e-12 && fabs(fabs(m[a]) - 1.0) < 1e-12 && c[a] * m[a] > 0.0) {
      return 2 * a + (c[a] > 0.0);
    }
  }
  return -1;
}

Test(poisson_disk, points_lie_on_the_faces_with_their_normals_and_equal_areas) {
  ss_mesh *mesh;
  ss_irradiance_point *p = cube_points(&mesh);
  cr_assert_float_eq(p[0].area * COUNT, 24.0, 1e-12);
  for (size_t i = 0; i < COUNT; ++i) {
    cr_assert_geq(face_of(p[i].p, p[i].n), 0, "point %zu (%g %g %g) is off the cube's faces", i,
                  p[i].p.x, p[i].p.y, p[i].p.z);
    cr_assert_eq(p[i].area, p[0].area);
    cr_assert_eq(p[i].shape, 3u);
  }
  free(p);
  ss_mesh_destroy(mesh);
}

/* Each face holds 1/6 of the points; a uniform draw by area puts a binomial
 * count there (standard deviation sqrt(COUNT p (1 - p)), p = 1/6), blue noise
 * fewer deviations: within 4.5 of them. */
Test(poisson_disk, points_are_spread_over_the_faces_by_area) {
  ss_mesh *mesh;
  ss_irradiance_point *p = cube_points(&mesh);
  size_t per_face[6] = {0};
  for (size_t i = 0; i < COUNT; ++i) {
    per_face[face_of(p[i].p, p[i].n)]++;
  }
  double expect = COUNT / 6.0, sd = sqrt(COUNT * (1.0 / 6.0) * (5.0 / 6.0));
  for (int f = 0; f < 6; ++f) {
    cr_assert_leq(fabs((double)per_face[f] - expect), 4.5 * sd, "face %d: %zu points, expected %g",
                  f, per_face[f], expect);
  }
  free(p);
  ss_mesh_destroy(mesh);
}

/* The closest pair is at least half the first disk radius sqrt(0.75 A /
 * COUNT) apart (the radius shrinks by 10 % per pass, a few passes); for
 * COUNT uniform points the closest pair lies about sqrt(A / (pi COUNT^2)),
 * 1/75 of that radius, apart. */
Test(poisson_disk, points_keep_a_minimum_distance) {
  ss_mesh *mesh;
  ss_irradiance_point *p = cube_points(&mesh);
  double closest = INFINITY;
  for (size_t i = 0; i < COUNT; ++i) {
    for (size_t j = i + 1; j < COUNT; ++j) {
      ss_vec3 d = ss_vec3_sub(p[i].p, p[j].p);
      closest = fmin(closest, ss_vec3_dot(d, d));
    }
  }
  double r0 = sqrt(0.75 * 24.0 / COUNT);
  cr_assert_geq(sqrt(closest), 0.5 * r0, "closest pair %g apart, first radius %g", sqrt(closest),
                r0);
  free(p);
  ss_mesh_destroy(mesh);
}
