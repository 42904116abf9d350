/* Assembly and solution of the diffusion system (src/fem/fem_assemble.c,
 * src/fem/fem_solve.c) against exact solutions of the same equation. */
#include "fem/iso_medium.h"
#include "fem/robin_halfspace.h"
#include "subsurf/fem.h"
#include "subsurf/fresnel.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

static ss_fem_mesh *box(double half, double depth, double hmax, double hmin, ss_vec3 c,
                        double radius, double grade) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = hmax,
                           .size_min = hmin,
                           .refine_center = c,
                           .refine_radius = radius,
                           .refine_grade = grade};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-half, -half, -depth), ss_vec3_make(half, half, 0), &o,
                               &m, &err),
               SS_OK, "%s", err.message);
  return m;
}

static ss_fem_solution *solve(const ss_fem_mesh *m, iso_medium *med, const ss_fem_problem *pb,
                              ss_fem_solver solver) {
  ss_error err = {0};
  ss_fem_solve_options so = {.solver = solver, .tolerance = 1e-10, .max_iterations = 100000};
  ss_fem_solution *s = NULL;
  cr_assert_eq(ss_fem_solve(m, iso, med, pb, &so, &s, &err), SS_OK, "%s", err.message);
  return s;
}

Test(fem_solve, energy_balance_holds_to_solver_tolerance_for_both_solvers) {
  iso_medium med = {1.0, 0.05};
  ss_fem_mesh *m = box(4, 4, 0.8, 0.1, ss_vec3_make(0, 0, 0), 0.3, 2.0);
  ss_fem_problem pb = {.eta = 1.4, .spot_radius = 0.3, .spot_power = 2.0, .volume_source = 0.01};
  for (int solver = SS_FEM_CHOLMOD; solver <= SS_FEM_PCG; ++solver) {
    ss_fem_solution *s = solve(m, &med, &pb, (ss_fem_solver)solver);
    cr_assert_float_eq(s->injected, 2.0 + 0.01 * 8 * 8 * 4, 1e-12);
    /* 1^T K a = 1^T b: the balance is off by at most |1| |b - K a| */
    cr_assert_float_eq(s->absorbed + s->escaped, s->injected, 1e-8 * s->injected,
                       "solver %d: absorbed %g + escaped %g vs injected %g", solver, s->absorbed,
                       s->escaped, s->injected);
    cr_assert_gt(s->absorbed, 0.1 * s->injected);
    cr_assert_gt(s->escaped, 0.1 * s->injected);
    ss_fem_solution_destroy(s);
  }
  ss_fem_mesh_destroy(m);
}

Test(fem_solve, conjugate_gradients_agree_with_cholesky) {
  iso_medium med = {2.0, 0.1};
  ss_fem_mesh *m = box(3, 3, 0.6, 0.1, ss_vec3_make(0, 0, 0), 0.2, 1.0);
  ss_fem_problem pb = {.eta = 1.0, .spot_radius = 0.2, .spot_power = 1.0};
  ss_fem_solution *a = solve(m, &med, &pb, SS_FEM_CHOLMOD), *b = solve(m, &med, &pb, SS_FEM_PCG);
  cr_assert_gt(b->iterations, 0);
  cr_assert_lt(b->residual, 1e-10);
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < m->num_vertices; ++i) {
    num += (a->fluence[i] - b->fluence[i]) * (a->fluence[i] - b->fluence[i]);
    den += a->fluence[i] * a->fluence[i];
  }
  cr_assert_lt(sqrt(num / den), 1e-8);
  ss_fem_solution_destroy(a);
  ss_fem_solution_destroy(b);
  ss_fem_mesh_destroy(m);
}

/* A point source one transport mean free path deep in a block many
 * diffusion lengths wide: the exitance is the exact half-space solution
 * (robin_halfspace.h) within the discretisation error, which is measured
 * below 6 % at this size. */
Test(fem_solve, exitance_matches_the_exact_robin_halfspace_solution) {
  iso_medium med = {1.0, 0.1};
  double st = 1.1, z0 = 1.0 / st, eta = 1.3, A = ss_fresnel_A(eta);
  ss_fem_mesh *m = box(10, 10, 1.0, 0.1, ss_vec3_make(0, 0, -z0), 1.0, 6.0);
  ss_fem_problem pb = {.eta = eta, .point = ss_vec3_make(0, 0, -z0), .point_power = 1.0};
  ss_fem_solution *s = solve(m, &med, &pb, SS_FEM_CHOLMOD);
  for (double r = 0.5; r <= 6.0; r *= 1.5) {
    double fem = 0.0;
    cr_assert(ss_fem_interpolate(m, s->exitance, ss_vec3_make(r, 0, 0), &fem));
    double exact = robin_halfspace_exitance(1.0, z0, 1.0, 0.1, A, r);
    cr_assert_float_eq(fem, exact, 0.06 * exact, "r = %g: fem %g, exact %g", r, fem, exact);
  }
  ss_fem_solution_destroy(s);
  ss_fem_mesh_destroy(m);
}

/* The cube [-a, a]^3 with a uniform source Q and the Robin condition
 * phi + 2 A D dphi/dn = 0: separation of variables in y and z with the
 * eigenfunctions cos(k y), k tan(k a) = 1/(2 A D), and the 1D solution in x
 * in closed form, u(x) = (1 - cosh(mu x)/(cosh(mu a) + 2 A D mu sinh(mu a)))
 * / lambda, mu = sqrt(lambda / D), lambda = sigma_a + D (k_m^2 + k_n^2). */
#define CUBE_TERMS 120
typedef struct {
  double a, D, sigma_a, A, k[CUBE_TERMS], c[CUBE_TERMS];
} cube_series;

static void cube_init(cube_series *cs, double a, double D, double sigma_a, double A) {
  cs->a = a;
  cs->D = D;
  cs->sigma_a = sigma_a;
  cs->A = A;
  double h = 1.0 / (2.0 * A * D);
  for (int l = 0; l < CUBE_TERMS; ++l) {
    /* k tan(k a) = h has one root in (l pi, l pi + pi/2) / a: bisection */
    double lo = l * SS_PI / a + 1e-15, hi = (l * SS_PI + SS_PI / 2) / a - 1e-15;
    for (int it = 0; it < 200; ++it) {
      double mid = 0.5 * (lo + hi);
      if (mid * tan(mid * a) < h) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    double k = 0.5 * (lo + hi);
    cs->k[l] = k;
    /* projection of 1: int cos / int cos^2 over [-a, a] */
    cs->c[l] = (2.0 * sin(k * a) / k) / (a + sin(2.0 * k * a) / (2.0 * k));
  }
}

static double cube_phi(const cube_series *cs, double Q, ss_vec3 p) {
  double s = 0.0, cy[CUBE_TERMS], cz[CUBE_TERMS];
  for (int l = 0; l < CUBE_TERMS; ++l) {
    cy[l] = cs->c[l] * cos(cs->k[l] * p.y);
    cz[l] = cs->c[l] * cos(cs->k[l] * p.z);
  }
  for (int m = 0; m < CUBE_TERMS; ++m) {
    for (int n = 0; n < CUBE_TERMS; ++n) {
      double lambda = cs->sigma_a + cs->D * (cs->k[m] * cs->k[m] + cs->k[n] * cs->k[n]);
      double mu = sqrt(lambda / cs->D);
      /* cosh(mu x)/cosh(mu a) without overflow */
      double ratio = exp(mu * (fabs(p.x) - cs->a)) * (1.0 + exp(-2.0 * mu * fabs(p.x))) /
                     (1.0 + exp(-2.0 * mu * cs->a));
      double u = (1.0 - ratio / (1.0 + 2.0 * cs->A * cs->D * mu * tanh(mu * cs->a))) / lambda;
      s += cy[m] * cz[n] * u;
    }
  }
  return Q * s;
}

/* Relative L2 error at the vertices (weighted by their share of volume). */
static double cube_error(double h, const cube_series *cs, iso_medium *med, double *hmax) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = h, .size_min = h};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-cs->a, -cs->a, -cs->a),
                               ss_vec3_make(cs->a, cs->a, cs->a), &o, &m, &err),
               SS_OK, "%s", err.message);
  ss_fem_problem pb = {.eta = 1.3, .volume_source = 1.0};
  ss_fem_solution *s = solve(m, med, &pb, SS_FEM_CHOLMOD);
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < m->num_vertices; ++i) {
    ss_vec3 p = ss_vec3_make(m->positions[3 * i], m->positions[3 * i + 1], m->positions[3 * i + 2]);
    double exact = cube_phi(cs, 1.0, p), d = s->fluence[i] - exact;
    num += d * d;
    den += exact * exact;
  }
  *hmax = ss_fem_mesh_max_edge(m);
  ss_fem_solution_destroy(s);
  ss_fem_mesh_destroy(m);
  return sqrt(num / den);
}

Test(fem_solve, fluence_converges_at_second_order_under_refinement) {
  iso_medium med = {1.0, 0.5};
  cube_series cs;
  cube_init(&cs, 2.0, 1.0 / (3.0 * 1.5), 0.5, ss_fresnel_A(1.3));
  double h1, h2;
  double e1 = cube_error(0.6, &cs, &med, &h1), e2 = cube_error(0.3, &cs, &med, &h2);
  double rate = log(e1 / e2) / log(h1 / h2);
  cr_log_info("errors %g (h %g), %g (h %g): rate %g", e1, h1, e2, h2, rate);
  cr_assert_lt(e1, 0.05);
  /* linear elements: O(h^2) in L2 */
  cr_assert(rate > 1.6 && rate < 2.6, "rate %g (errors %g, %g)", rate, e1, e2);
}

Test(fem_solve, bad_media_and_sources_are_named) {
  ss_fem_mesh *m = box(1, 1, 0.5, 0.5, ss_vec3_make(0, 0, 0), 0, 0);
  ss_error err = {0};
  ss_fem_solve_options so = {.solver = SS_FEM_CHOLMOD};
  ss_fem_solution *s = NULL;
  iso_medium neg = {1.0, -0.5};
  ss_fem_problem pb = {.eta = 1.3, .volume_source = 1.0};
  cr_assert_eq(ss_fem_solve(m, iso, &neg, &pb, &so, &s, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "element 0"), "%s", err.message);
  cr_assert_null(s);
  iso_medium ok = {1.0, 0.5};
  pb.point = ss_vec3_make(0, 0, 5);
  pb.point_power = 1.0;
  cr_assert_eq(ss_fem_solve(m, iso, &ok, &pb, &so, &s, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "outside the mesh"), "%s", err.message);
  ss_fem_problem spot = {
      .eta = 1.3, .spot_center = {0, 0, 9}, .spot_radius = 0.1, .spot_power = 1.0};
  cr_assert_eq(ss_fem_solve(m, iso, &ok, &spot, &so, &s, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "does not touch the boundary"), "%s", err.message);
  ss_fem_mesh_destroy(m);
}

/* A vertex no tetrahedron uses has an empty row in K: the system is
 * singular (every element has boundary faces with the Robin term, so a
 * closed mesh with mu0 = 0, or one in several pieces, is still definite).
 * Both solvers say so and return no solution. */
Test(fem_solve, a_singular_system_is_reported_by_both_solvers) {
  const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 5, 5};
  const uint32_t tet[] = {0, 1, 2, 3};
  ss_fem_mesh *m = NULL;
  ss_error err = {0};
  cr_assert_eq(ss_fem_mesh_create(pos, 5, tet, 1, &m, &err), SS_OK, "%s", err.message);
  iso_medium med = {1.0, 0.0};
  ss_fem_problem pb = {.eta = 1.3, .volume_source = 1.0};
  for (int k = 0; k < 2; ++k) {
    ss_fem_solve_options so = {
        .solver = k ? SS_FEM_PCG : SS_FEM_CHOLMOD, .tolerance = 1e-10, .max_iterations = 1000};
    ss_fem_solution *s = NULL;
    cr_assert_eq(ss_fem_solve(m, iso, &med, &pb, &so, &s, &err), SS_ERR_INVALID_ARGUMENT,
                 "solver %d", k);
    cr_assert(strstr(err.message, "singular"), "solver %d: %s", k, err.message);
    cr_assert_null(s);
  }
  ss_fem_mesh_destroy(m);
}
