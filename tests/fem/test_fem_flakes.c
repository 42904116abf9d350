/* Finite elements in micro-flake media (Jakob2010 sec. 5.3 and 6.2): the
 * coefficients of src/optics/flake_diffusion.c through ss_fem_coeffs_flakes. */
#include "subsurf/fem.h"
#include "subsurf/flake_diffusion.h"
#include "subsurf/mat3.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>

static ss_status constant(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err) {
  *out = *(const ss_fem_coeffs *)ctx;
  return SS_OK;
}

static ss_microflake flakes(ss_flake_type type, double p, ss_vec3 axis, double albedo) {
  ss_microflake mf;
  ss_error err = {0};
  ss_flake_albedo a = {albedo, albedo, 1.0};
  cr_assert_eq(ss_microflake_init(&mf, type, p, axis, a, &err), SS_OK, "%s", err.message);
  return mf;
}

static ss_fem_mesh *box(ss_vec3 half, double hmax, double hmin, ss_vec3 c) {
  ss_error err = {0};
  ss_fem_mesh_options o = {.size_max = hmax,
                           .size_min = hmin,
                           .refine_center = c,
                           .refine_radius = 1.0,
                           .refine_grade = 6.0};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_scale(half, -1.0), half, &o, &m, &err), SS_OK, "%s",
               err.message);
  return m;
}

static ss_fem_solution *solve(const ss_fem_mesh *m, ss_fem_coeffs *k, const ss_fem_problem *pb) {
  ss_error err = {0};
  ss_fem_solve_options so = {.solver = SS_FEM_CHOLMOD};
  ss_fem_solution *s = NULL;
  cr_assert_eq(ss_fem_solve(m, constant, k, pb, &so, &s, &err), SS_OK, "%s", err.message);
  return s;
}

/* Jakob2010 eq. 14-15 and 34: uniform flakes are the isotropic medium with
 * sigma_t' = sigma_t (g = 0), so the two solutions are one. */
Test(fem_flakes, uniform_flakes_give_the_isotropic_solution) {
  const double sigma_s = 0.9, sigma_a = 0.1;
  ss_microflake mf =
      flakes(SS_FLAKE_UNIFORM, 0.0, ss_vec3_make(0, 0, 1), sigma_s / (sigma_s + sigma_a));
  ss_fem_coeffs kf = ss_fem_coeffs_flakes(&mf, ss_flake_medium_density(sigma_s, sigma_a));
  ss_fem_coeffs ki = ss_fem_coeffs_isotropic(sigma_s, sigma_a);
  ss_fem_mesh *m = box(ss_vec3_make(3, 3, 3), 0.6, 0.15, ss_vec3_make(0, 0, 3));
  ss_fem_problem pb = {.eta = 1.3, .spot_center = {0, 0, 3}, .spot_radius = 0.5, .spot_power = 1};
  ss_fem_solution *a = solve(m, &kf, &pb), *b = solve(m, &ki, &pb);
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < m->num_vertices; ++i) {
    num += (a->fluence[i] - b->fluence[i]) * (a->fluence[i] - b->fluence[i]);
    den += b->fluence[i] * b->fluence[i];
  }
  cr_assert_lt(sqrt(num / den), 1e-6, "relative L2 difference %g", sqrt(num / den));
  cr_assert_float_eq(a->escaped, b->escaped, 1e-6 * b->escaped);
  ss_fem_solution_destroy(a);
  ss_fem_solution_destroy(b);
  ss_fem_mesh_destroy(m);
}

/* Jakob2010 eq. 43: in an unbounded medium the fluence of a point source is
 * Phi det P/(4 pi |P x|) exp(-beta |P x|), P = M^(1/2), beta = sqrt(mu0 /
 * (4 pi)). Fibre-like flakes along x diffuse light along x faster; the
 * finite elements in a cube many diffusion lengths wide reproduce the
 * skewed monopole away from the source within the discretisation error.
 * (With p = 20 the cross-fibre decay length, 1.1, needs elements of 0.15 over
 * a radius of 4: 146 CPU seconds, too slow for make check; p = 2 keeps the
 * diffusion anisotropic, M_yy/M_xx > 1.2, at a few seconds.) */
Test(fem_flakes, point_source_in_fibres_matches_the_anisotropic_monopole) {
  const double sigma_s = 0.9, sigma_a = 0.1;
  ss_microflake mf =
      flakes(SS_FLAKE_FIBER, 2.0, ss_vec3_make(1, 0, 0), sigma_s / (sigma_s + sigma_a));
  ss_fem_coeffs k = ss_fem_coeffs_flakes(&mf, ss_flake_medium_density(sigma_s, sigma_a));
  ss_mat3 M, P;
  for (int i = 0; i < 9; ++i) {
    M.m[i / 3][i % 3] = k.M[i];
  }
  cr_assert(ss_mat3_sym_power(M, 0.5, &P));
  double beta = sqrt(k.mu0 / (4.0 * SS_PI)), detP = ss_mat3_det(P);
  /* the diffusion really is anisotropic: M's x entry differs from y's */
  cr_assert_gt(fabs(M.m[0][0] - M.m[1][1]), 0.2 * M.m[1][1]);
  ss_fem_mesh *m = box(ss_vec3_make(10, 8, 8), 1.0, 0.1, ss_vec3_make(0, 0, 0));
  ss_fem_problem pb = {.eta = 1.0, .point = {0, 0, 0}, .point_power = 1.0};
  ss_fem_solution *s = solve(m, &k, &pb);
  const ss_vec3 dirs[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.57735, 0.57735, 0.57735}};
  for (int d = 0; d < 4; ++d) {
    for (double r = 1.5; r <= 4.0; r += 1.25) {
      ss_vec3 x = ss_vec3_scale(dirs[d], r);
      double fem = 0.0, px = ss_vec3_length(ss_mat3_apply(P, x));
      cr_assert(ss_fem_interpolate(m, s->fluence, x, &fem));
      double exact = detP / (4.0 * SS_PI * px) * exp(-beta * px);
      cr_expect_float_eq(fem, exact, 0.05 * exact, "direction %d, r = %g: fem %g, monopole %g", d,
                         r, fem, exact);
    }
  }
  ss_fem_solution_destroy(s);
  ss_fem_mesh_destroy(m);
}
