/* The manifold solver (src/render/manifold.h), for chains of one and two
 * refraction vertices: Newton's method from the straight-line seed lands on
 * points where Snell's law holds at every shading normal, and the Jacobian
 * d omega_0 / d y of the generalised geometry term equals central finite
 * differences of solved paths, for targets at a point and at infinity. The
 * chains of two: out of a core nested in a shell (two meshes), and through
 * a ball lens from outside (one mesh entered and left). On a flat face
 * under the sun, also past the critical angle (the seed in total internal
 * reflection), the solution is the closed form's. */
#include "render/manifold.h"
#include "render/scene_builder.h"

#include "subsurf/fresnel.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define ETA 1.3     /* test_add_translucent's */
#define N_CORE 1.33 /* the nested core's index */
#define N_SHELL 1.5 /* the shell's */
#define N_LENS 1.2  /* the ball lens's (focal length 3 from its centre) */
#define R_CORE 0.6  /* the core's radius (the shell's is 1) */
#define TOLERANCE 1e-12

/* A unit icosphere (smooth normals) behind a smooth boundary of ETA and,
 * when `core`, a sphere of radius R_CORE inside it (bare geometry: the
 * solver reads only the meshes). */
static ss_scene *sphere_scene(unsigned subdivisions, int core) {
  ss_error err;
  ss_scene *s;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  int mi = test_add_translucent(s, ss_rgb_gray(1.0), ss_rgb_gray(0.1), SS_BOUNDARY_SMOOTH, "");
  ss_mesh *mesh;
  cr_assert_eq(ss_shape_icosphere(1.0, subdivisions, &mesh, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", mesh, core ? -1 : mi, NULL, &err), SS_OK, "%s",
               err.message);
  if (core) {
    cr_assert_eq(ss_shape_icosphere(R_CORE, subdivisions, &mesh, &err), SS_OK);
    cr_assert_eq(ss_scene_add_shape(s, "core", mesh, -1, NULL, &err), SS_OK, "%s", err.message);
  }
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

/* The kinds of chain tested. */
typedef enum { ONE, NESTED, LENS } kind;

/* The chain's vertex count, index ratios and sides (manifold.h). */
static ss_manifold_chain chain_of(kind k) {
  ss_manifold_chain c;
  memset(&c, 0, sizeof c);
  switch (k) {
  case ONE:
    c.k = 1;
    c.eta[0] = ETA;
    break;
  case NESTED:
    c.k = 2;
    c.eta[0] = N_CORE / N_SHELL;
    c.eta[1] = N_SHELL;
    break;
  case LENS:
    c.k = 2;
    c.eta[0] = 1.0 / N_LENS;
    c.eta[1] = N_LENS;
    c.enters[0] = 1;
    break;
  }
  return c;
}

/* Seeds the chain with the straight line's first crossings and solves it. */
static int solve(const ss_scene *s, kind k, ss_vec3 x0, const ss_manifold_target *y,
                 ss_manifold_chain *c) {
  *c = chain_of(k);
  ss_ray ray = {x0, y->at_infinity ? y->w : ss_vec3_sub(y->p, x0), 0.0, INFINITY};
  for (int i = 0; i < c->k; ++i) {
    ss_hit seed;
    cr_assert(ss_accel_intersect(s->accel, &ray, &seed));
    cr_assert(ss_manifold_chain_vertex(s, c, i, seed.geom_id, seed.prim_id, seed.b1, seed.b2));
    ray = ss_ray_spawn(seed.p, seed.ng, ray.d);
  }
  uint64_t rays = 0;
  return ss_manifold_chain_solve(s, x0, c, y, 50, TOLERANCE, &rays);
}

static ss_vec3 omega0(ss_vec3 x0, const ss_manifold_chain *c) {
  return ss_vec3_normalize(ss_vec3_sub(c->x[0].p, x0));
}

/* Vertices x0 (inside the core, which lies inside the unit sphere; for the
 * lens: outside it, on the far side from the targets, within its focal
 * length, away from any caustic) and targets. */
static const double X0[][3] = {{0.2, -0.1, 0.3}, {-0.3, 0.25, -0.1}, {0.0, 0.0, 0.45}};
static const double X0_LENS[][3] = {{-0.1, -0.05, -1.6}, {0.08, 0.05, -1.7}, {0.0, 0.03, -1.8}};
static const double Y[][3] = {{3.0, 2.0, 2.0}, {-1.0, 4.0, 0.5}, {0.5, -0.3, 5.0}};
static const double Y_LENS[][3] = {{0.2, 0.1, 4.0}, {-0.15, 0.1, 3.0}, {0.1, -0.2, 2.5}};

static ss_vec3 vertex_x0(kind k, int i) {
  const double *p = k == LENS ? X0_LENS[i] : X0[i];
  return ss_vec3_make(p[0], p[1], p[2]);
}

/* Target j: the point, or (at infinity) the direction toward it. */
static ss_manifold_target target(kind k, int j, int at_infinity) {
  const double *q = k == LENS ? Y_LENS[j] : Y[j];
  ss_vec3 p = ss_vec3_make(q[0], q[1], q[2]);
  ss_manifold_target y = {p, ss_vec3_normalize(p), at_infinity};
  return y;
}

/* Snell's law at every vertex of a solved chain (1e-8), on the meshes. */
static void expect_snell(const ss_manifold_chain *c, ss_vec3 x0, const ss_manifold_target *y,
                         const char *what) {
  for (int i = 0; i < c->k; ++i) {
    double dist;
    ss_vec3 wo = i + 1 < c->k ? ss_vec3_normalize(ss_vec3_sub(c->x[i + 1].p, c->x[i].p))
                              : ss_manifold_target_dir(y, c->x[i].p, &dist);
    ss_vec3 wi = ss_vec3_normalize(ss_vec3_sub(i ? c->x[i - 1].p : x0, c->x[i].p));
    ss_vec3 wt;
    cr_assert(ss_refract(wi, c->x[i].n, c->eta[i], &wt), "%s vertex %d: no refraction", what, i);
    double e = ss_vec3_length(ss_vec3_sub(wt, wo));
    cr_expect(e < 1e-8, "%s vertex %d: |wt - wo| = %g", what, i, e);
    double r = ss_vec3_length(c->x[i].p);
    cr_expect(fabs(r - 1.0) < 2e-3 || fabs(r - R_CORE) < 2e-3, "%s vertex %d: not on a sphere",
              what, i);
  }
}

static void newton_lands_where_snell_holds(kind k) {
  ss_scene *s = sphere_scene(5, k == NESTED);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int inf = 0; inf < 2; ++inf) {
        char what[64];
        snprintf(what, sizeof what, "chain %d x0 %d y %d inf %d", (int)k, i, j, inf);
        ss_vec3 x0 = vertex_x0(k, i);
        ss_manifold_target y = target(k, j, inf);
        ss_manifold_chain c;
        cr_assert(solve(s, k, x0, &y, &c), "%s: no solution", what);
        expect_snell(&c, x0, &y, what);
        if (k == NESTED) {
          cr_expect(fabs(ss_vec3_length(c.x[0].p) - R_CORE) < 2e-3, "%s: x1 off the core", what);
        }
      }
    }
  }
  ss_scene_destroy(s);
}

Test(manifold, newton_lands_where_snell_holds_at_the_shading_normal) {
  newton_lands_where_snell_holds(ONE);
}

Test(manifold, a_chain_of_two_satisfies_snell_at_both_vertices) {
  newton_lands_where_snell_holds(NESTED);
  newton_lands_where_snell_holds(LENS);
}

static void jacobian_equals_finite_differences(kind k, unsigned subdivisions) {
  ss_scene *s = sphere_scene(subdivisions, k == NESTED);
  const double h = 1e-4;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int inf = 0; inf < 2; ++inf) {
        ss_vec3 x0 = vertex_x0(k, i);
        ss_manifold_target y = target(k, j, inf);
        ss_manifold_chain c;
        cr_assert(solve(s, k, x0, &y, &c));
        ss_frame f = ss_frame_from_normal(inf ? y.w : ss_vec3_normalize(y.p));
        double J = ss_manifold_chain_jacobian(x0, &c, &y, f.s, f.t);
        /* Central differences of omega_0 in the frame around it. */
        ss_frame g = ss_frame_from_normal(omega0(x0, &c));
        ss_vec3 t[2] = {f.s, f.t};
        double K[2][2];
        for (int q = 0; q < 2; ++q) {
          ss_vec3 w[2];
          for (int sgn = 0; sgn < 2; ++sgn) {
            ss_manifold_target yk = y;
            double e = sgn ? -h : h;
            if (inf) {
              yk.w = ss_vec3_normalize(ss_vec3_madd(y.w, t[q], e));
            } else {
              yk.p = ss_vec3_madd(y.p, t[q], e);
            }
            ss_manifold_chain ck;
            cr_assert(solve(s, k, x0, &yk, &ck));
            w[sgn] = omega0(x0, &ck);
          }
          ss_vec3 dw = ss_vec3_scale(ss_vec3_sub(w[0], w[1]), 0.5 / h);
          K[0][q] = ss_vec3_dot(dw, g.s);
          K[1][q] = ss_vec3_dot(dw, g.t);
        }
        double fd = fabs(K[0][0] * K[1][1] - K[0][1] * K[1][0]);
        cr_expect(fabs(J / fd - 1.0) < 0.02,
                  "chain %d x0 %d y %d inf %d: J %g, finite differences %g", (int)k, i, j, inf, J,
                  fd);
      }
    }
  }
  ss_scene_destroy(s);
}

Test(manifold, jacobian_equals_finite_differences_of_solved_paths) {
  jacobian_equals_finite_differences(ONE, 7);
}

Test(manifold, the_chain_jacobian_equals_finite_differences_of_solved_paths) {
  jacobian_equals_finite_differences(NESTED, 6);
  jacobian_equals_finite_differences(LENS, 6);
}

/* A flat boundary under the sun at theta_i degrees from its normal: the
 * refraction point has a closed form, where the sun's direction refracted
 * into the slab, followed back from x0, meets the face. Past the critical
 * angle of 1/ETA (50.3 degrees) the straight line toward the sun meets the
 * face in total internal reflection: there the plane's normal does not turn
 * and only the continuation of w_t beyond the grazing direction moves with
 * the vertex (manifold.c's link_at; a continuation by the grazing direction
 * alone left the constraint flat along the plane of incidence and Newton's
 * method without a step). */
Test(manifold, a_flat_face_converges_to_the_closed_form_for_any_sun) {
  ss_error err;
  ss_scene *s;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  int mi = test_add_translucent(s, ss_rgb_gray(1.0), ss_rgb_gray(0.1), SS_BOUNDARY_SMOOTH, "");
  ss_mesh *mesh;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(10, 5, 10), 1, &mesh, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(mesh, ss_mat4_translate(ss_vec3_make(0, -2.5, 0)), &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "slab", mesh, mi, NULL, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  const double depth = 0.7, thetas[] = {0.0, 30.0, 50.0, 52.0, 69.0, 80.0};
  const ss_vec3 x0 = ss_vec3_make(0.3, -depth, -0.2);
  for (size_t k = 0; k < sizeof thetas / sizeof *thetas; ++k) {
    /* Toward the sun, in the x-y plane, tilted toward -x. */
    double t = thetas[k] * SS_PI / 180.0, sin_in = sin(t) / ETA;
    ss_manifold_target y = {ss_vec3_make(0, 0, 0), ss_vec3_make(-sin(t), cos(t), 0), 1};
    ss_vec3 expected = ss_vec3_make(x0.x - depth * sin_in / sqrt(1.0 - sin_in * sin_in), 0, x0.z);
    ss_manifold_chain c;
    cr_expect(solve(s, ONE, x0, &y, &c), "sun at %g degrees: no solution", thetas[k]);
    double e = ss_vec3_length(ss_vec3_sub(c.x[0].p, expected));
    cr_expect(e < 1e-9, "sun at %g degrees: x1 (%g %g %g), %g from the closed form", thetas[k],
              c.x[0].p.x, c.x[0].p.y, c.x[0].p.z, e);
  }
  ss_scene_destroy(s);
}
