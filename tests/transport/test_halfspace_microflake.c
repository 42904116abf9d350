/* The half-space reference in micro-flake media (Jakob et al. 2010): uniform
 * flakes are the isotropic medium, oriented flakes conserve energy and give a
 * reciprocal BRDF (the next-event estimate toward exact directions with
 * direction-dependent extinction), and bad flake parameters are refused. */
#include "subsurf/halfspace.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#define DEG (SS_PI / 180.0)

static ss_halfspace_result *run(const ss_halfspace_params *p) {
  ss_halfspace_result *r = NULL;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(p, &r, &err), SS_OK, "ss_halfspace_run failed: %s", err.message);
  return r;
}

static void flake_medium(ss_halfspace_params *p, ss_flake_type type, ss_vec3 axis) {
  ss_halfspace_params_default(p);
  p->medium.sigma_s = ss_rgb_gray(1.8);
  p->medium.sigma_a = ss_rgb_gray(0.2);
  p->medium.flakes = (ss_medium_flakes){.type = type, .p = 20.0, .axis = axis};
  p->seed = 3;
}

static void expect_close(ss_estimate a, ss_estimate b, const char *what) {
  double bound = 3.5 * sqrt(a.error * a.error + b.error * b.error);
  cr_expect(fabs(a.value - b.value) < bound, "%s: %.6f +- %.6f vs %.6f +- %.6f", what, a.value,
            a.error, b.value, b.error);
}

Test(halfspace_microflake, uniform_flakes_are_the_isotropic_medium) {
  ss_halfspace_params flakes, iso;
  flake_medium(&flakes, SS_FLAKE_UNIFORM, ss_vec3_make(0.3, 0.1, 1.0));
  flakes.eta = 1.33;
  flakes.thickness = 2.0;
  flakes.theta_i = 30.0 * DEG;
  flakes.paths = 100000;
  flakes.n_theta_o = 1;
  flakes.theta_o[0] = 20.0 * DEG;
  flakes.xmin = -100.0;
  flakes.xmax = 100.0;
  flakes.xbins = 1;
  iso = flakes;
  iso.medium.flakes.type = SS_FLAKE_NONE;
  iso.seed = 4;
  ss_halfspace_result *a = run(&flakes), *b = run(&iso);
  expect_close(a->reflectance, b->reflectance, "reflectance");
  expect_close(a->transmittance, b->transmittance, "transmittance");
  expect_close(a->directions[0], b->directions[0], "radiance toward 20 deg");
  ss_halfspace_result_destroy(a);
  ss_halfspace_result_destroy(b);
}

Test(halfspace_microflake, oriented_slabs_conserve_energy) {
  const ss_flake_type types[] = {SS_FLAKE_SURFACE, SS_FLAKE_FIBER};
  const double etas[] = {1.0, 1.33};
  for (int t = 0; t < 2; ++t) {
    for (int e = 0; e < 2; ++e) {
      ss_halfspace_params p;
      flake_medium(&p, types[t], ss_vec3_make(0.6, 0.3, 0.74));
      p.eta = etas[e];
      p.thickness = 1.5;
      p.theta_i = 40.0 * DEG;
      p.paths = 20000;
      ss_halfspace_result *r = run(&p);
      double sum = r->reflectance.value + r->transmittance.value + r->absorbed.value +
                   r->specular.value + r->truncated.value;
      double bound = 3.0 * (r->reflectance.error + r->transmittance.error + r->absorbed.error);
      cr_expect(fabs(sum - 1.0) < bound, "%s eta %g: R+T+A+S = %.6f", ss_flake_type_name(types[t]),
                etas[e], sum);
      ss_halfspace_result_destroy(r);
      /* Lossless flakes: nothing is absorbed, every path leaves. */
      p.medium.sigma_s = ss_rgb_gray(2.0);
      p.medium.sigma_a = ss_rgb_gray(0.0);
      r = run(&p);
      cr_expect_eq(r->absorbed.value, 0.0);
      cr_expect(fabs(r->reflectance.value + r->transmittance.value + r->specular.value - 1.0) <
                    1e-9,
                "%s eta %g: lossless slab R+T+S = %.12f", ss_flake_type_name(types[t]), etas[e],
                r->reflectance.value + r->transmittance.value + r->specular.value);
      ss_halfspace_result_destroy(r);
    }
  }
}

/* Index matched, the half-space's BRDF int L dA per unit power is
 * reciprocal. A beam toward +x at theta_i seen toward theta_o, reversed and
 * mirrored in x (so that the beam again travels toward +x), is a beam at
 * theta_o seen toward theta_i with the flake axis mirrored in x. */
static double brdf(ss_flake_type type, ss_vec3 axis, double theta_i, double theta_o, uint64_t seed,
                   double *error) {
  ss_halfspace_params p;
  flake_medium(&p, type, axis);
  p.theta_i = theta_i * DEG;
  p.n_theta_o = 1;
  p.theta_o[0] = theta_o * DEG;
  p.xmin = -200.0;
  p.xmax = 200.0;
  p.xbins = 1;
  p.paths = 150000;
  p.seed = seed;
  ss_halfspace_result *r = run(&p);
  double v = r->directions[0].value * 400.0;
  *error = r->directions[0].error * 400.0;
  ss_halfspace_result_destroy(r);
  return v;
}

Test(halfspace_microflake, oriented_half_space_brdf_is_reciprocal) {
  const ss_flake_type types[] = {SS_FLAKE_SURFACE, SS_FLAKE_FIBER};
  ss_vec3 axis = ss_vec3_make(0.6, 0.3, 0.74), mirrored = ss_vec3_make(-0.6, 0.3, 0.74);
  for (int t = 0; t < 2; ++t) {
    double ea, eb;
    double a = brdf(types[t], axis, 10.0, 55.0, 11, &ea);
    double b = brdf(types[t], mirrored, 55.0, 10.0, 12, &eb);
    cr_expect(fabs(a - b) < 3.5 * sqrt(ea * ea + eb * eb),
              "%s: f(10 -> 55) = %.6f +- %.6f, "
              "f(55 -> 10) mirrored = %.6f +- %.6f",
              ss_flake_type_name(types[t]), a, ea, b, eb);
    cr_expect(ea < 0.02 * a, "%s: relative error %.3g too large to test",
              ss_flake_type_name(types[t]), ea / a);
  }
}

Test(halfspace_microflake, bad_flake_parameters_name_the_option) {
  ss_halfspace_params p;
  ss_error err;
  flake_medium(&p, SS_FLAKE_FIBER, ss_vec3_make(0, 0, 0));
  cr_assert_neq(ss_halfspace_validate(&p, &err), SS_OK);
  cr_expect(strstr(err.message, "medium-axis") != NULL, "%s", err.message);
  flake_medium(&p, SS_FLAKE_FIBER, ss_vec3_make(1, 0, 0));
  p.medium.flakes.p = 2000.0;
  cr_assert_neq(ss_halfspace_validate(&p, &err), SS_OK);
  cr_expect(strstr(err.message, "flake-p") != NULL, "%s", err.message);
  flake_medium(&p, SS_FLAKE_FIBER, ss_vec3_make(1, 0, 0));
  p.medium.g = ss_rgb_gray(0.5);
  p.medium.phase = SS_PHASE_HG;
  cr_assert_neq(ss_halfspace_validate(&p, &err), SS_OK);
  cr_expect(strstr(err.message, "g:") == err.message, "%s", err.message);
}
