/* Texture coordinates of the built-in shapes: the sphere's are spherical
 * (u = phi / 2pi, v = theta / pi) and continuous on every triangle, the
 * quad's and the cube faces' span [0, 1]^2 linearly, and hits interpolate
 * them. */
#include <criterion/criterion.h>

#include "subsurf/accel.h"
#include "subsurf/mesh.h"
#include "subsurf/sampling.h"

#include <math.h>

static void spherical(ss_vec3 p, double *u, double *v) {
  double phi = atan2(p.y, p.x);
  *u = phi < 0.0 ? phi / (2.0 * SS_PI) + 1.0 : phi / (2.0 * SS_PI);
  *v = acos(p.z / ss_vec3_length(p)) / SS_PI;
}

Test(shape_uv, icosphere_uvs_are_spherical_and_continuous_and_it_stays_closed) {
  for (unsigned level = 0; level <= 4; ++level) {
    ss_mesh *m;
    ss_error err;
    cr_assert_eq(ss_shape_icosphere(2.0, level, &m, &err), SS_OK);
    cr_assert_not_null(m->uvs);
    cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
    cr_assert_eq(ss_mesh_validate(m, NULL, &err), SS_OK);
    for (size_t k = 0; k < m->num_vertices; ++k) {
      ss_vec3 p = ss_mesh_position(m, (uint32_t)k);
      double u, v;
      spherical(p, &u, &v);
      double su = m->uvs[2 * k], sv = m->uvs[2 * k + 1];
      cr_assert_float_eq(sv, v, 1e-6, "vertex %zu", k);
      if (hypot(p.x, p.y) > 1e-6) { /* u is free at the poles */
        double du = fabs(su - u);
        cr_assert(du < 1e-6 || fabs(du - 1.0) < 1e-6, "vertex %zu: u %g, expected %g (mod 1)", k,
                  su, u);
      }
    }
    for (size_t t = 0; t < m->num_triangles; ++t) {
      double lo = 2.0, hi = -1.0;
      for (int c = 0; c < 3; ++c) {
        double u = m->uvs[2 * m->indices[3 * t + (size_t)c]];
        lo = fmin(lo, u);
        hi = fmax(hi, u);
      }
      /* no triangle wraps around the sphere; small ones span little u */
      cr_assert(hi - lo < (level >= 2 ? 0.25 : 0.5 + 1e-9),
                "level %u triangle %zu spans u [%g, %g]", level, t, lo, hi);
    }
    ss_mesh_destroy(m);
  }
}

Test(shape_uv, quad_and_cube_uvs_span_the_unit_square_linearly) {
  ss_mesh *q;
  ss_error err;
  cr_assert_eq(ss_shape_quad(3.0, 2.0, 3, 2, &q, &err), SS_OK);
  for (size_t k = 0; k < q->num_vertices; ++k) {
    ss_vec3 p = ss_mesh_position(q, (uint32_t)k);
    cr_assert_float_eq(q->uvs[2 * k], p.x / 3.0 + 0.5, 1e-6);
    cr_assert_float_eq(q->uvs[2 * k + 1], p.y / 2.0 + 0.5, 1e-6);
  }
  ss_mesh_destroy(q);
  ss_mesh *c;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(1, 1, 1), 2, &c, &err), SS_OK);
  /* Every face is a 3 x 3 vertex grid whose uvs are the grid positions / 2,
   * and u, v each follow one in-face coordinate linearly. */
  for (size_t f = 0; f < 6; ++f) {
    for (size_t k = 0; k < 9; ++k) {
      size_t vtx = 9 * f + k;
      cr_assert_float_eq(c->uvs[2 * vtx], (double)(k % 3) / 2.0, 1e-6);
      cr_assert_float_eq(c->uvs[2 * vtx + 1], (double)(k / 3) / 2.0, 1e-6);
    }
  }
  ss_mesh_destroy(c);
}

Test(shape_uv, hits_on_the_sphere_interpolate_its_spherical_uvs) {
  ss_mesh *m;
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(1.0, 6, &m, &err), SS_OK);
  const ss_mesh *meshes[1] = {m};
  ss_accel *a;
  cr_assert_eq(ss_accel_create(meshes, 1, &a, &err), SS_OK);
  for (int k = 0; k < 40; ++k) {
    double theta = 0.2 + 2.7 * k / 39.0, phi = 0.37 + 0.61 * k; /* crosses the seam */
    ss_vec3 dir = ss_vec3_make(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
    ss_ray ray = {ss_vec3_scale(dir, 3.0), ss_vec3_neg(dir), 0.0, INFINITY};
    ss_hit hit;
    cr_assert(ss_accel_intersect(a, &ray, &hit));
    double u, v;
    spherical(hit.p, &u, &v);
    double du = fabs(hit.st[0] - u);
    du = fmin(du, fabs(du - 1.0));
    /* A tessellation of 81920 triangles: the linear interpolation departs
     * from the exact angles by well under a degree. */
    cr_assert(du < 2e-3, "phi %g: u %g, expected %g", phi, hit.st[0], u);
    cr_assert_float_eq(hit.st[1], v, 2e-3);
  }
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}
