/* The exponentially attenuated volume source of refracted rays
 * (src/fem/fem_rays.c): the rays of a diffuse spot, their load vector, the
 * energy balance, and the exitance against the exact half-space solution of
 * the same sources. */
#include "fem/fem_internal.h"
#include "fem/iso_medium.h"
#include "fem/robin_halfspace.h"
#include "subsurf/fem.h"
#include "subsurf/fresnel.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define STRATA 16 /* depth strata per ray, as in fem_rays.c */

static double constant_sigma(void *ctx, ss_vec3 w) {
  (void)w;
  return *(const double *)ctx;
}

/* The rays of a diffuse spot of `radius` at the origin of the plane z = 0,
 * 4 rings and 4 direction strata, constant extinction *sigma (*out, *n). */
static void spot_rays(double radius, double power, double *sigma, ss_fem_ray **out, size_t *n) {
  ss_error err = {0};
  cr_assert_eq(ss_fem_spot_rays(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, 1), radius, power, 1, 4,
                                4, constant_sigma, sigma, out, n, &err),
               SS_OK, "%s", err.message);
}

static ss_fem_mesh *box(double half, double depth, double hmax, double hmin, double radius) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = hmax,
                           .size_min = hmin,
                           .refine_center = ss_vec3_make(0, 0, 0),
                           .refine_radius = radius,
                           .refine_grade = 6.0};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-half, -half, -depth), ss_vec3_make(half, half, 0), &o,
                               &m, &err),
               SS_OK, "%s", err.message);
  return m;
}

static ss_fem_solution *solve(const ss_fem_mesh *m, iso_medium *med, const ss_fem_problem *pb) {
  ss_error err = {0};
  ss_fem_solve_options so = {.solver = SS_FEM_CHOLMOD};
  ss_fem_solution *s = NULL;
  cr_assert_eq(ss_fem_solve(m, iso, med, pb, &so, &s, &err), SS_OK, "%s", err.message);
  return s;
}

Test(fem_rays, a_diffuse_spot_shares_its_power_over_cosine_distributed_inward_rays) {
  double sigma = 2.0;
  ss_fem_ray *r = NULL;
  size_t n = 0;
  ss_error err = {0};
  ss_vec3 c = ss_vec3_make(1, 2, 3), nrm = ss_vec3_make(0, 0.6, 0.8);
  cr_assert_eq(ss_fem_spot_rays(c, nrm, 0.5, 3.0, 1, 6, 8, constant_sigma, &sigma, &r, &n, &err),
               SS_OK, "%s", err.message);
  cr_assert_eq(n, 6 * 12 * 8 * 16);
  double power = 0.0, mean_cos = 0.0, mean_offset = 0.0;
  for (size_t i = 0; i < n; ++i) {
    ss_vec3 d = ss_vec3_sub(r[i].origin, c);
    cr_assert_lt(fabs(ss_vec3_dot(d, nrm)), 1e-12, "origins in the tangent plane");
    cr_assert_lt(ss_vec3_length(d), 0.5, "origins inside the disc");
    cr_assert_float_eq(ss_vec3_length(r[i].dir), 1.0, 1e-12);
    cr_assert_lt(ss_vec3_dot(r[i].dir, nrm), 0.0, "rays go inward");
    cr_assert_eq(r[i].sigma, sigma);
    power += r[i].power;
    mean_cos -= ss_vec3_dot(r[i].dir, nrm) / (double)n;
    mean_offset += ss_vec3_dot(d, d) / (double)n;
  }
  cr_assert_float_eq(power, 3.0, 1e-12);
  /* cosine-distributed: E[cos theta] = 2/3; uniform disc: E[r^2] = R^2/2
   * (the strata's midpoints carry an error below 1 % at these counts) */
  cr_assert_float_eq(mean_cos, 2.0 / 3.0, 0.01 * 2.0 / 3.0, "mean cosine %g", mean_cos);
  cr_assert_float_eq(mean_offset, 0.125, 1e-9, "mean r^2 %g", mean_offset);
  free(r);
  cr_assert_neq(ss_fem_spot_rays(c, ss_vec3_make(0, 0, 0), 0.5, 1.0, 1, 6, 8, constant_sigma,
                                 &sigma, &r, &n, &err),
                SS_OK);
  cr_assert_null(r);
}

/* A vertical ray: the load vector's sum is the ray's power and, since linear
 * shape functions reproduce linear functions, its first moment sum b_i x_i
 * is that of the strata; their mean depth approximates 1/sigma. */
Test(fem_rays, the_load_keeps_the_power_and_the_first_moment_of_the_strata) {
  ss_fem_mesh *m = box(3, 6, 0.7, 0.2, 1.0);
  double sigma = 1.5;
  ss_fem_ray ray = {ss_vec3_make(0.1, -0.2, 0), ss_vec3_make(0, 0, -1), sigma, 2.0};
  ss_fem_problem pb = {.eta = 1.3, .rays = &ray, .num_rays = 1};
  double *b = calloc(m->num_vertices, sizeof *b), injected = 0.0;
  ss_error err = {0};
  cr_assert_eq(ss_fem_deposit_rays(m, &pb, b, &injected, &err), SS_OK, "%s", err.message);
  double sum = 0.0, mx = 0.0, my = 0.0, mz = 0.0, depth = 0.0;
  for (size_t i = 0; i < m->num_vertices; ++i) {
    sum += b[i];
    mx += b[i] * m->positions[3 * i];
    my += b[i] * m->positions[3 * i + 1];
    mz += b[i] * m->positions[3 * i + 2];
  }
  for (int k = 0; k < STRATA; ++k) {
    depth += -log(1.0 - (k + 0.5) / STRATA) / sigma * 2.0 / STRATA;
  }
  cr_assert_float_eq(injected, 2.0, 1e-12);
  cr_assert_float_eq(sum, 2.0, 1e-12);
  cr_assert_float_eq(mx, 0.2, 1e-9);
  cr_assert_float_eq(my, -0.4, 1e-9);
  cr_assert_float_eq(mz, -depth, 1e-9);
  cr_assert_float_eq(depth / 2.0, 1.0 / sigma, 0.03 / sigma, "mean depth %g", depth / 2.0);
  free(b);
  /* a ray leaving the mesh loses the strata outside it */
  ray.origin = ss_vec3_make(2.9, 0, -0.5);
  ray.dir = ss_vec3_make(1, 0, 0);
  b = calloc(m->num_vertices, sizeof *b);
  cr_assert_eq(ss_fem_deposit_rays(m, &pb, b, &injected, &err), SS_OK, "%s", err.message);
  cr_assert_lt(injected, 0.5 * 2.0);
  cr_assert_gt(injected, 0.0);
  ray.sigma = 0.0;
  cr_assert_eq(ss_fem_deposit_rays(m, &pb, b, &injected, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "ray 0"), "%s", err.message);
  free(b);
  ss_fem_mesh_destroy(m);
}

Test(fem_rays, energy_balance_holds_with_the_ray_source) {
  iso_medium med = {1.0, 0.05};
  ss_fem_mesh *m = box(4, 4, 0.8, 0.1, 0.5);
  double sigma = 1.05;
  ss_fem_ray *r = NULL;
  size_t n = 0;
  spot_rays(0.3, 2.0, &sigma, &r, &n);
  ss_fem_problem pb = {.eta = 1.4, .rays = r, .num_rays = n};
  ss_fem_solution *s = solve(m, &med, &pb);
  cr_assert_float_eq(s->injected, 2.0, 1e-9, "all strata inside: injected %g", s->injected);
  cr_assert_float_eq(s->absorbed + s->escaped, s->injected, 1e-8 * s->injected,
                     "absorbed %g + escaped %g vs injected %g", s->absorbed, s->escaped,
                     s->injected);
  ss_fem_solution_destroy(s);
  free(r);
  ss_fem_mesh_destroy(m);
}

/* A vertical ray's strata are point sources at known depths: the exitance is
 * the sum of the exact half-space solutions of the same Robin problem
 * (robin_halfspace.h) within the discretisation error (6 %, as for one
 * point source in test_fem_solve.c). */
Test(fem_rays, exitance_of_a_ray_matches_the_exact_robin_halfspace_solution) {
  iso_medium med = {1.0, 0.1};
  double sigma = 1.1, eta = 1.3, A = ss_fresnel_A(eta);
  ss_fem_mesh *m = box(10, 10, 1.0, 0.1, 1.5);
  ss_fem_ray ray = {ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, -1), sigma, 1.0};
  ss_fem_problem pb = {.eta = eta, .rays = &ray, .num_rays = 1};
  ss_fem_solution *s = solve(m, &med, &pb);
  for (double r = 0.5; r <= 6.0; r *= 1.5) {
    double fem = 0.0, exact = 0.0;
    cr_assert(ss_fem_interpolate(m, s->exitance, ss_vec3_make(r, 0, 0), &fem));
    for (int k = 0; k < STRATA; ++k) {
      double z = -log(1.0 - (k + 0.5) / STRATA) / sigma;
      exact += robin_halfspace_exitance(1.0 / STRATA, z, 1.0, 0.1, A, r);
    }
    cr_assert_float_eq(fem, exact, 0.06 * exact, "r = %g: fem %g, exact %g", r, fem, exact);
  }
  ss_fem_solution_destroy(s);
  ss_fem_mesh_destroy(m);
}

/* The reason for the ray source: a spot much narrower than a mean free path
 * drives the boundary source's exitance phi/(2A) - Gamma_s/A negative at its
 * centre (the diffusive flux of eq. 37-38 is concentrated on the spot),
 * while the rays' first scattering events spread below it keep it positive
 * on the whole surface. */
Test(fem_rays, a_narrow_spot_gives_positive_exitance_with_rays_not_with_the_boundary_source) {
  iso_medium med = {1.0, 0.01};
  ss_fem_mesh *m = box(4, 4, 0.8, 0.04, 0.4);
  ss_fem_problem pb = {.eta = 1.0, .spot_radius = 0.1, .spot_power = 1.0};
  ss_fem_solution *s = solve(m, &med, &pb);
  double centre = 0.0;
  cr_assert(ss_fem_interpolate(m, s->exitance, ss_vec3_make(0, 0, 0), &centre));
  cr_assert_lt(centre, 0.0, "boundary source: exitance %g at the centre", centre);
  ss_fem_solution_destroy(s);
  double sigma = 1.01;
  ss_fem_ray *r = NULL;
  size_t n = 0;
  spot_rays(0.1, 1.0, &sigma, &r, &n);
  ss_fem_problem pr = {.eta = 1.0, .rays = r, .num_rays = n};
  s = solve(m, &med, &pr);
  for (size_t i = 0; i < m->num_vertices; ++i) {
    if (m->positions[3 * i + 2] == 0.0) {
      cr_assert_geq(s->exitance[i], 0.0, "rays: exitance %g at vertex %zu", s->exitance[i], i);
    }
  }
  ss_fem_solution_destroy(s);
  free(r);
  ss_fem_mesh_destroy(m);
}

/* Point location (fem_grid.c) on the graded mesh of `subsurf fem`'s
 * defaults (elements 0.25 within 1.5 of the spot growing to 2): the cells
 * near the spot get finer grids, a uniform mesh's none, and at 4000 points
 * (half of them near the spot) the grid finds a tetrahedron exactly when the
 * linear search does, with barycentric coordinates that reproduce the
 * point. */
Test(fem_rays, the_point_location_grid_refines_where_the_mesh_is_graded) {
  ss_fem_mesh *graded = box(10.0, 10.0, 2.0, 0.25, 1.5), *uniform = box(4.0, 4.0, 1.0, 1.0, 0.0);
  ss_fem_grid g;
  ss_error err = {0};
  cr_assert_eq(ss_fem_grid_build(uniform, &g, &err), SS_OK, "%s", err.message);
  cr_expect_eq(g.num_fine, 0, "a uniform mesh got %zu finer grids", g.num_fine);
  ss_fem_grid_free(&g);
  cr_assert_eq(ss_fem_grid_build(graded, &g, &err), SS_OK, "%s", err.message);
  cr_expect_gt(g.num_fine, 0, "the graded mesh got no finer grid");
  ss_rng rng;
  ss_rng_seed_item(&rng, 16, 3);
  for (int i = 0; i < 4000; ++i) {
    double r = i % 2 ? 10.2 : 2.0; /* a little outside the box too */
    ss_vec3 x = ss_vec3_make(r * (2.0 * ss_rng_uniform(&rng) - 1.0),
                             r * (2.0 * ss_rng_uniform(&rng) - 1.0), -r * ss_rng_uniform(&rng));
    size_t t, t_lin;
    double l[4], l_lin[4];
    int found = ss_fem_grid_locate(&g, graded, x, &t, l);
    cr_assert_eq(found, ss_fem_locate(graded, x, &t_lin, l_lin), "point %g %g %g", x.x, x.y, x.z);
    ss_vec3 back = ss_vec3_make(0, 0, 0);
    for (int k = 0; found && k < 4; ++k) {
      const double *p = graded->positions + 3 * (size_t)graded->tets[4 * t + (size_t)k];
      back = ss_vec3_add(back, ss_vec3_scale(ss_vec3_make(p[0], p[1], p[2]), l[k]));
    }
    cr_assert(!found || ss_vec3_length(ss_vec3_sub(back, x)) < 1e-9, "point %g %g %g", x.x, x.y,
              x.z);
  }
  ss_fem_grid_free(&g);
  ss_fem_mesh_destroy(graded);
  ss_fem_mesh_destroy(uniform);
}
