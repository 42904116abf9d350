/* The one-interface manifold solver (src/render/manifold.h): Newton's method
 * from the straight-line seed lands on a point where Snell's law holds at
 * the shading normal, and the Jacobian d omega_0 / d y of the generalised
 * geometry term equals central finite differences of solved paths, for
 * targets at a point and at infinity. */
#include "render/manifold.h"
#include "render/scene_builder.h"

#include "subsurf/fresnel.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define ETA 1.3 /* test_add_translucent's */

/* A unit icosphere (smooth normals) behind a smooth boundary of ETA. */
static ss_scene *sphere_scene(unsigned subdivisions) {
  ss_error err;
  ss_scene *s;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  int mi = test_add_translucent(s, ss_rgb_gray(1.0), ss_rgb_gray(0.1), SS_BOUNDARY_SMOOTH, "");
  ss_mesh *mesh;
  cr_assert_eq(ss_shape_icosphere(1.0, subdivisions, &mesh, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", mesh, mi, NULL, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static int solve(const ss_scene *s, ss_vec3 x0, const ss_manifold_target *y,
                 ss_manifold_vertex *x1) {
  ss_ray ray = {x0, y->at_infinity ? y->w : ss_vec3_sub(y->p, x0), 0.0, INFINITY};
  ss_hit seed;
  cr_assert(ss_accel_intersect(s->accel, &ray, &seed));
  uint64_t rays = 0;
  return ss_manifold_solve(s, x0, &seed, y, ETA, 50, 1e-12, x1, &rays);
}

static ss_vec3 omega0(ss_vec3 x0, const ss_manifold_vertex *x1) {
  return ss_vec3_normalize(ss_vec3_sub(x1->p, x0));
}

/* Inside points and targets (points outside, and directions). */
static const double X0[][3] = {{0.2, -0.1, 0.3}, {-0.5, 0.4, -0.2}, {0.0, 0.0, 0.7}};
static const double Y[][3] = {{3.0, 2.0, 2.0}, {-1.0, 4.0, 0.5}, {0.5, -0.3, 5.0}};

/* Target j: the point Y[j], or (at infinity) the direction toward it. */
static ss_manifold_target target(int j, int at_infinity) {
  ss_vec3 p = ss_vec3_make(Y[j][0], Y[j][1], Y[j][2]);
  ss_manifold_target y = {p, ss_vec3_normalize(p), at_infinity};
  return y;
}

Test(manifold, newton_lands_where_snell_holds_at_the_shading_normal) {
  ss_scene *s = sphere_scene(5);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int inf = 0; inf < 2; ++inf) {
        ss_vec3 x0 = ss_vec3_make(X0[i][0], X0[i][1], X0[i][2]);
        ss_manifold_target y = target(j, inf);
        ss_manifold_vertex x1;
        cr_assert(solve(s, x0, &y, &x1), "x0 %d y %d inf %d: no solution", i, j, inf);
        double dist;
        ss_vec3 wo = ss_manifold_target_dir(&y, x1.p, &dist);
        ss_vec3 wt;
        ss_vec3 wi = ss_vec3_normalize(ss_vec3_sub(x0, x1.p));
        cr_assert(ss_refract(wi, x1.n, ETA, &wt));
        cr_expect(ss_vec3_length(ss_vec3_sub(wt, wo)) < 1e-8, "x0 %d y %d inf %d: |wt - wo| = %g",
                  i, j, inf, ss_vec3_length(ss_vec3_sub(wt, wo)));
        cr_expect(fabs(ss_vec3_length(x1.p) - 1.0) < 2e-3, "not on the sphere");
      }
    }
  }
  ss_scene_destroy(s);
}

Test(manifold, jacobian_equals_finite_differences_of_solved_paths) {
  ss_scene *s = sphere_scene(7);
  const double h = 1e-4;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int inf = 0; inf < 2; ++inf) {
        ss_vec3 x0 = ss_vec3_make(X0[i][0], X0[i][1], X0[i][2]);
        ss_manifold_target y = target(j, inf);
        ss_manifold_vertex x1;
        cr_assert(solve(s, x0, &y, &x1));
        ss_frame f = ss_frame_from_normal(inf ? y.w : ss_vec3_normalize(y.p));
        double J = ss_manifold_jacobian(x0, &x1, &y, ETA, f.s, f.t);
        /* Central differences of omega_0 in the frame around it. */
        ss_frame g = ss_frame_from_normal(omega0(x0, &x1));
        ss_vec3 t[2] = {f.s, f.t};
        double K[2][2];
        for (int k = 0; k < 2; ++k) {
          ss_vec3 w[2];
          for (int sgn = 0; sgn < 2; ++sgn) {
            ss_manifold_target yk = y;
            double e = sgn ? -h : h;
            if (inf) {
              yk.w = ss_vec3_normalize(ss_vec3_madd(y.w, t[k], e));
            } else {
              yk.p = ss_vec3_madd(y.p, t[k], e);
            }
            ss_manifold_vertex xk;
            cr_assert(solve(s, x0, &yk, &xk));
            w[sgn] = omega0(x0, &xk);
          }
          ss_vec3 dw = ss_vec3_scale(ss_vec3_sub(w[0], w[1]), 0.5 / h);
          K[0][k] = ss_vec3_dot(dw, g.s);
          K[1][k] = ss_vec3_dot(dw, g.t);
        }
        double fd = fabs(K[0][0] * K[1][1] - K[0][1] * K[1][0]);
        cr_expect(fabs(J / fd - 1.0) < 0.02, "x0 %d y %d inf %d: J %g, finite differences %g", i, j,
                  inf, J, fd);
      }
    }
  }
  ss_scene_destroy(s);
}
