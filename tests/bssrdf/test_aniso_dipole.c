/* The anisotropic diffusion dipole (Jakob et al. 2010, sec. 6.3): uniform
 * flakes give the classical dipole to rounding for random media, boundaries
 * and (curved) configurations; the model is reciprocal where the geometry
 * allows it (the axis in the surface or along the normal); fibres in the
 * surface spread light along themselves; the plane total matches the
 * integrated exitance for tilted axes; bad options are refused. (The entry
 * sampler's chi-square and max radius: test_conformance.c.) */
#include "bssrdf/bssrdf_test_util.h"

#include <stdio.h>

static ss_bssrdf *make_flakes(double sigma_s, double sigma_a, double eta, ss_flake_type type,
                              double p, ss_vec3 axis) {
  ss_bssrdf_params bp;
  ss_bssrdf_params_default(&bp);
  ss_bssrdf_params_set_gray(&bp, sigma_s, sigma_a, 0.0);
  bp.eta = eta;
  bp.medium.flakes = (ss_medium_flakes){.type = type, .p = p, .axis = axis};
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("aniso-dipole", &bp, &b, &err), SS_OK, "%s", err.message);
  return b;
}

static ss_vec3 random_unit(ss_rng *rng) {
  return ss_spherical_direction(2.0 * ss_rng_uniform(rng) - 1.0, 2.0 * SS_PI * ss_rng_uniform(rng));
}

static ss_vec3 random_outward(ss_rng *rng, ss_vec3 n) {
  ss_frame f = ss_frame_from_normal(n);
  return ss_frame_to_world(f,
                           ss_sample_uniform_hemisphere(ss_rng_uniform(rng), ss_rng_uniform(rng)));
}

static void expect_close(double a, double b, double rel, const char *what, int trial) {
  cr_assert(fabs(a - b) <= rel * fmax(fabs(a), fabs(b)), "trial %d %s: %.17g vs %.17g", trial, what,
            a, b);
}

/* A property test over random chromatic media (albedo 0.01 to 1, g, eta),
 * uniform flakes given either by the medium or by the model's options with
 * a random axis, and random queries on flat and curved geometry. */
Test(aniso_dipole, uniform_flakes_are_the_classical_dipole_to_rounding) {
  ss_rng rng;
  ss_rng_seed(&rng, 44, 1);
  for (int trial = 0; trial < 24; ++trial) {
    ss_bssrdf_params bp;
    ss_bssrdf_params_default(&bp);
    for (int c = 0; c < 3; ++c) {
      double sigma_t = pow(10.0, 2.0 * ss_rng_uniform(&rng) - 1.0);
      double albedo = 1.0 - pow(10.0, -2.0 * ss_rng_uniform(&rng));
      bp.medium.sigma_s.c[c] = albedo * sigma_t;
      bp.medium.sigma_a.c[c] = (1.0 - albedo) * sigma_t;
      bp.medium.g.c[c] = trial % 2 ? 0.9 * ss_rng_uniform(&rng) : 0.0;
    }
    if (trial % 3 == 0) {
      bp.medium.sigma_a.c[2] = 0.0; /* no absorption: beta = 0 */
    }
    bp.eta = trial % 4 == 0 ? 1.0 : 1.0 + 0.6 * ss_rng_uniform(&rng);
    ss_bssrdf *classic = NULL, *aniso = NULL;
    ss_error err;
    cr_assert_eq(ss_bssrdf_create("dipole", &bp, &classic, &err), SS_OK, "%s", err.message);
    ss_vec3 axis = random_unit(&rng);
    char text[128];
    snprintf(text, sizeof text, "%.17g,%.17g,%.17g", axis.x, axis.y, axis.z);
    const ss_bssrdf_ops *ops = ss_bssrdf_model_find("aniso-dipole");
    cr_assert_eq(ss_bssrdf_params_set_option(&bp, ops, "flake_distribution", "uniform", &err),
                 SS_OK);
    cr_assert_eq(ss_bssrdf_params_set_option(&bp, ops, "flake_axis", text, &err), SS_OK);
    cr_assert_eq(ss_bssrdf_create("aniso-dipole", &bp, &aniso, &err), SS_OK, "%s", err.message);
    for (int k = 0; k < 200; ++k) {
      ss_bssrdf_query q;
      q.n_i = k % 2 ? random_unit(&rng) : ss_vec3_make(0, 0, 1);
      q.n_o = k % 2 ? random_unit(&rng) : q.n_i;
      q.x_i = ss_vec3_make(ss_rng_uniform(&rng), ss_rng_uniform(&rng), 0.0);
      double r = 10.0 * pow(ss_rng_uniform(&rng), 2.0);
      ss_vec3 dir = k % 2 ? random_unit(&rng) : ss_vec3_make(cos(k), sin(k), 0.0);
      q.x_o = ss_vec3_madd(q.x_i, dir, r);
      q.w_i = random_outward(&rng, q.n_i);
      q.w_o = random_outward(&rng, q.n_o);
      q.thickness = 0.0;
      double a[3], b[3];
      ss_bssrdf_eval(classic, &q, a);
      ss_bssrdf_eval(aniso, &q, b);
      for (int c = 0; c < 3; ++c) {
        expect_close(a[c], b[c], 1e-12, "S", trial);
      }
    }
    double a[3], b[3];
    ss_bssrdf_rd(classic, a);
    ss_bssrdf_rd(aniso, b);
    for (int c = 0; c < 3; ++c) {
      expect_close(a[c], b[c], 1e-12, "rd", trial);
    }
    ss_bssrdf_total_reflectance(classic, 0.6, a);
    ss_bssrdf_total_reflectance(aniso, 0.6, b);
    for (int c = 0; c < 3; ++c) {
      expect_close(a[c], b[c], 1e-12, "total", trial);
    }
    ss_bssrdf_destroy(classic);
    ss_bssrdf_destroy(aniso);
  }
}

/* With M n parallel to n the real source lies straight below x_i and the
 * exitance depends on x_o - x_i only through the quadratic form of M, which
 * is even: S is reciprocal. */
Test(aniso_dipole, reciprocal_when_the_axis_is_in_the_surface_or_along_the_normal) {
  const ss_vec3 axes[] = {{1, 0, 0}, {0.6, -0.8, 0}, {0, 0, 1}};
  for (int k = 0; k < 3; ++k) {
    ss_bssrdf *b =
        make_flakes(0.9, 0.05, 1.33, k % 2 ? SS_FLAKE_SURFACE : SS_FLAKE_FIBER, 20.0, axes[k]);
    expect_reciprocal(b, 1e-12);
    ss_bssrdf_destroy(b);
  }
}

/* Fibres along x in the surface (fiber-like flakes: normals across the
 * fibres): diffusion is fastest along the fibres, M's eigenvalue smallest
 * there, so the exitance falls off more slowly along x than along y. */
Test(aniso_dipole, fibres_in_the_surface_spread_light_along_themselves) {
  ss_bssrdf *b = make_flakes(0.99, 0.01, 1.0, SS_FLAKE_FIBER, 20.0, ss_vec3_make(1, 0, 0));
  for (int k = 1; k <= 8; ++k) {
    double r = 0.5 * k, along[3], across[3];
    ss_bssrdf_exitance(b, 1.0, r, 0.0, along);
    ss_bssrdf_exitance(b, 1.0, 0.0, r, across);
    cr_assert_gt(along[0], across[0], "r %g: %g along vs %g across", r, along[0], across[0]);
    double mirrored[3];
    ss_bssrdf_exitance(b, 1.0, -r, 0.0, mirrored);
    expect_close(along[0], mirrored[0], 1e-13, "mirror", k);
  }
  ss_bssrdf_destroy(b);
}

/* The closed-form plane total (each source's flux through the plane in the
 * space transformed by P) against the exitance integrated over the plane,
 * for axes tilted out of the surface (where the pattern is lopsided). */
Test(aniso_dipole, plane_total_is_the_integrated_exitance_for_tilted_axes) {
  const ss_vec3 axes[] = {{1, 0, 1}, {0.3, 0.5, 0.8}};
  for (int k = 0; k < 2; ++k) {
    ss_bssrdf *b =
        make_flakes(0.95, 0.05, 1.33, k ? SS_FLAKE_SURFACE : SS_FLAKE_FIBER, 20.0, axes[k]);
    double total[3], integral[3];
    ss_bssrdf_total_reflectance(b, 1.0, total);
    integrate_exitance(b, 1.0, integral);
    expect_close(total[0], integral[0], 1e-4, "total", k);
    ss_bssrdf_destroy(b);
  }
}

/* How the flakes are given besides the option under test. */
enum { WITH_FIBER_OPTION, WITH_MEDIUM_FLAKES, ALONE };

static void expect_refused(const char *name, const char *value, int setup, const char *needle) {
  ss_bssrdf_params bp;
  ss_bssrdf_params_default(&bp);
  if (setup == WITH_MEDIUM_FLAKES) {
    bp.medium.flakes = (ss_medium_flakes){.type = SS_FLAKE_FIBER, .p = 20, .axis = {1, 0, 0}};
  }
  const ss_bssrdf_ops *ops = ss_bssrdf_model_find("aniso-dipole");
  ss_error err;
  ss_bssrdf *b = NULL;
  if (setup == WITH_FIBER_OPTION && strcmp(name, "flake_distribution") != 0) {
    cr_assert_eq(ss_bssrdf_params_set_option(&bp, ops, "flake_distribution", "fiber", &err), SS_OK);
  }
  ss_status st = ss_bssrdf_params_set_option(&bp, ops, name, value, &err);
  if (st == SS_OK) {
    st = ss_bssrdf_create("aniso-dipole", &bp, &b, &err);
  }
  cr_assert_neq(st, SS_OK, "%s=%s accepted", name, value);
  cr_assert(strstr(err.message, needle), "%s=%s: '%s' lacks '%s'", name, value, err.message,
            needle);
}

Test(aniso_dipole, bad_flake_options_are_refused_with_the_option_named) {
  expect_refused("flake_axis", "1,2", WITH_FIBER_OPTION, "flake_axis");
  expect_refused("flake_axis", "1,2,3,4", WITH_FIBER_OPTION, "flake_axis");
  expect_refused("flake_axis", "0,0,0", WITH_FIBER_OPTION, "flake_axis");
  expect_refused("flake_axis", "nan,0,1", WITH_FIBER_OPTION, "flake_axis");
  expect_refused("flake_axis", "1e300,1e300,0", WITH_FIBER_OPTION, "flake_axis");
  expect_refused("flake_exponent", "-1", WITH_FIBER_OPTION, "flake_exponent");
  expect_refused("flake_exponent", "1e9", WITH_FIBER_OPTION, "flake_exponent");
  expect_refused("flake_distribution", "cloth", WITH_FIBER_OPTION, "flake_distribution");
  expect_refused("flake_distribution", "surface", WITH_MEDIUM_FLAKES, "already has flakes");
  /* an axis or exponent without a distribution of the model's own */
  expect_refused("flake_axis", "1,0,0", ALONE, "only with flake_distribution");
  expect_refused("flake_exponent", "5", WITH_MEDIUM_FLAKES, "only with flake_distribution");
}
