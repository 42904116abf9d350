#include "subsurf/halfspace.h"
#include "subsurf/sampling.h"

#include "transport/chandrasekhar.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define DEG (SS_PI / 180.0)

static ss_halfspace_result *run(const ss_halfspace_params *p) {
  ss_halfspace_result *r = NULL;
  ss_error err;
  ss_status st = ss_halfspace_run(p, &r, &err);
  cr_assert_eq(st, SS_OK, "ss_halfspace_run failed: %s", err.message);
  return r;
}

static void index_matched_iso(ss_halfspace_params *p, double albedo, double theta_deg) {
  ss_halfspace_params_default(p);
  p->medium.sigma_s = ss_rgb_gray(albedo);
  p->medium.sigma_a = ss_rgb_gray(1.0 - albedo);
  p->theta_i = theta_deg * DEG;
  p->seed = 7;
}

Test(halfspace, index_matched_albedo_equals_one_minus_H_sqrt_one_minus_albedo) {
  const double albedos[] = {0.5, 0.9, 0.99};
  const double thetas[] = {0.0, 60.0};
  for (int a = 0; a < 3; ++a) {
    h_function hf;
    h_solve(&hf, albedos[a]);
    for (int t = 0; t < 2; ++t) {
      ss_halfspace_params p;
      index_matched_iso(&p, albedos[a], thetas[t]);
      p.paths = 400000;
      ss_halfspace_result *r = run(&p);
      double expected = h_albedo(&hf, cos(thetas[t] * DEG));
      double dev = fabs(r->reflectance.value - expected);
      cr_expect(dev < 3.0 * r->reflectance.error,
                "albedo %g theta %g: R = %.6f +- %.6f, exact %.6f", albedos[a], thetas[t],
                r->reflectance.value, r->reflectance.error, expected);
      cr_expect(r->reflectance.error < 2e-3 && r->reflectance.error > 0.0);
      cr_expect_eq(r->specular.value, 0.0);
      ss_halfspace_result_destroy(r);
    }
  }
}

Test(halfspace, exact_direction_radiance_matches_chandrasekhar) {
  h_function hf;
  h_solve(&hf, 0.9);
  const double theta_i[] = {0.0, 45.0};
  for (int t = 0; t < 2; ++t) {
    ss_halfspace_params p;
    index_matched_iso(&p, 0.9, theta_i[t]);
    p.paths = 200000;
    p.n_theta_o = 3;
    p.theta_o[0] = 0.0;
    p.theta_o[1] = 40.0 * DEG;
    p.theta_o[2] = -60.0 * DEG;
    /* One x bin wide enough to hold all the exitant light: its value times
     * its width is int int L dx dy. */
    p.xmin = -200.0;
    p.xmax = 200.0;
    p.xbins = 1;
    ss_halfspace_result *r = run(&p);
    for (int k = 0; k < 3; ++k) {
      double integral = r->directions[k].value * 400.0, err = r->directions[k].error * 400.0;
      double expected = h_radiance(&hf, cos(p.theta_o[k]), cos(p.theta_i));
      cr_expect(fabs(integral - expected) < 3.0 * err + 1e-4 * expected,
                "theta_i %g theta_o %g: int L dA = %.6f +- %.6f, exact %.6f", theta_i[t],
                p.theta_o[k] / DEG, integral, err, expected);
    }
    ss_halfspace_result_destroy(r);
  }
}

static void expect_energy_conserved(const ss_halfspace_params *p, const char *what) {
  ss_halfspace_result *r = run(p);
  double sum = r->reflectance.value + r->transmittance.value + r->absorbed.value +
               r->specular.value + r->truncated.value;
  double bound = 3.0 * (r->reflectance.error + r->transmittance.error + r->absorbed.error) + 1e-12;
  cr_expect(fabs(sum - 1.0) < bound, "%s: R+T+A+S = %.6f (bound %.2g)", what, sum, bound);
  cr_expect_eq(r->truncated.value, 0.0, "%s: no path should be truncated", what);
  ss_halfspace_result_destroy(r);
}

Test(halfspace, slabs_conserve_energy_for_every_phase_function_and_eta) {
  struct {
    ss_phase_type phase;
    double g;
  } phases[] = {
      {SS_PHASE_ISOTROPIC, 0.0}, {SS_PHASE_HG, 0.9}, {SS_PHASE_HG, -0.5}, {SS_PHASE_GAUSS, 0.9}};
  const double etas[] = {1.0, 1.33, 0.75, 1.8};
  const double thetas[] = {0.0, 70.0};
  for (int ph = 0; ph < 4; ++ph) {
    for (int e = 0; e < 4; ++e) {
      for (int t = 0; t < 2; ++t) {
        ss_halfspace_params p;
        ss_halfspace_params_default(&p);
        p.medium.phase = phases[ph].phase;
        p.medium.g = ss_rgb_gray(phases[ph].g);
        p.medium.sigma_s = ss_rgb_gray(2.0);
        p.medium.sigma_a = ss_rgb_gray(0.3);
        p.eta = etas[e];
        p.theta_i = thetas[t] * DEG;
        p.thickness = 1.5;
        p.paths = 20000;
        p.seed = (uint64_t)(ph * 100 + e * 10 + t);
        char what[96];
        snprintf(what, sizeof what, "phase %s g %g eta %g theta %g",
                 ss_phase_type_name(p.medium.phase), p.medium.g.c[0], p.eta, thetas[t]);
        expect_energy_conserved(&p, what);
      }
    }
  }
}

Test(halfspace, conservative_slab_loses_nothing) {
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.sigma_s = ss_rgb_gray(3.0);
  p.medium.sigma_a = ss_rgb_gray(0.0);
  p.eta = 1.0;
  p.thickness = 2.0;
  p.paths = 20000;
  ss_halfspace_result *r = run(&p);
  cr_expect_eq(r->absorbed.value, 0.0);
  cr_expect(fabs(r->reflectance.value + r->transmittance.value - 1.0) < 1e-12, "R + T = %.15f",
            r->reflectance.value + r->transmittance.value);
  ss_halfspace_result_destroy(r);
}

Test(halfspace, total_internal_reflection_traps_light_in_a_thick_slab) {
  /* Grazing-incidence light inside a dense slab is reflected many times;
   * energy must still balance and the specular part follows Fresnel. */
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.sigma_s = ss_rgb_gray(0.5);
  p.medium.sigma_a = ss_rgb_gray(0.05);
  p.eta = 2.0;
  p.theta_i = 80.0 * DEG;
  p.thickness = 0.5;
  p.paths = 40000;
  ss_halfspace_result *r = run(&p);
  double sin_t = sin(80.0 * DEG) / 2.0, cos_i = cos(80.0 * DEG), cos_t = sqrt(1 - sin_t * sin_t);
  double rs = (cos_i - 2.0 * cos_t) / (cos_i + 2.0 * cos_t);
  double rp = (2.0 * cos_i - cos_t) / (2.0 * cos_i + cos_t);
  cr_expect(fabs(r->specular.value - 0.5 * (rs * rs + rp * rp)) < 1e-12);
  ss_halfspace_result_destroy(r);
  expect_energy_conserved(&p, "eta 2 grazing");
}

Test(halfspace, forward_peaked_nearly_conservative_medium_terminates_with_sound_statistics) {
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.phase = SS_PHASE_HG;
  p.medium.g = ss_rgb_gray(0.99);
  p.medium.sigma_s = ss_rgb_gray(0.999);
  p.medium.sigma_a = ss_rgb_gray(0.001);
  p.eta = 1.33;
  p.paths = 4000;
  p.seed = 3;
  ss_halfspace_result *small = run(&p);
  p.paths = 16000;
  ss_halfspace_result *large = run(&p);
  cr_expect_eq(large->paths, 16000u);
  cr_expect_eq(large->truncated.value, 0.0);
  double sum = large->reflectance.value + large->absorbed.value + large->specular.value;
  cr_expect(fabs(sum - 1.0) < 3.0 * (large->reflectance.error + large->absorbed.error),
            "R+A+S = %.5f", sum);
  /* The standard error shrinks as 1/sqrt(N): quadrupling N halves it. */
  double ratio = small->reflectance.error / large->reflectance.error;
  cr_expect(ratio > 1.5 && ratio < 2.7, "stderr ratio %.3f for 4x the paths", ratio);
  /* Similarity: R depends mostly on the reduced albedo; it must be well
   * inside (0, 1) and far from the g = 0 answer with the same albedo. */
  cr_expect(large->reflectance.value > 0.2 && large->reflectance.value < 0.6, "R = %.4f",
            large->reflectance.value);
  ss_halfspace_result_destroy(small);
  ss_halfspace_result_destroy(large);
}

Test(halfspace, fixed_seed_gives_identical_results_for_one_and_two_threads) {
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.phase = SS_PHASE_HG;
  p.medium.g = ss_rgb_gray(0.7);
  p.eta = 1.33;
  p.theta_i = 30.0 * DEG;
  p.paths = 30000;
  p.seed = 11;
  p.n_theta_o = 2;
  p.theta_o[0] = 0.0;
  p.theta_o[1] = 60.0 * DEG;
  p.want_map = 1;
  p.xbins = p.ybins = 16;
  p.threads = 1;
  ss_halfspace_result *a = run(&p);
  p.threads = 2;
  ss_halfspace_result *b = run(&p);
  cr_expect_eq(memcmp(&a->reflectance, &b->reflectance, sizeof a->reflectance), 0);
  cr_expect_eq(memcmp(&a->absorbed, &b->absorbed, sizeof a->absorbed), 0);
  cr_expect_eq(memcmp(a->radial, b->radial, (size_t)a->rbins * sizeof *a->radial), 0);
  cr_expect_eq(memcmp(a->directions, b->directions, 2 * (size_t)a->xbins * sizeof *a->directions),
               0);
  cr_expect_eq(memcmp(a->map, b->map, 256 * sizeof *a->map), 0);
  cr_expect_eq(a->scatter_events, b->scatter_events);
  ss_halfspace_result_destroy(a);
  ss_halfspace_result_destroy(b);
}

Test(halfspace, radial_exitance_integrates_to_the_reflectance) {
  ss_halfspace_params p;
  index_matched_iso(&p, 0.95, 0.0);
  p.paths = 20000;
  p.rmin = 1e-3;
  p.rmax = 1e4;
  p.rbins = 80;
  ss_halfspace_result *r = run(&p);
  double total = 0.0;
  for (int i = 0; i < r->rbins; ++i) {
    total += r->radial[i].value * SS_PI * (r->r_hi[i] * r->r_hi[i] - r->r_lo[i] * r->r_lo[i]);
  }
  cr_expect(fabs(total - r->reflectance.value) < 1e-9, "%.9f vs %.9f", total, r->reflectance.value);
  ss_halfspace_result_destroy(r);
}

Test(halfspace, time_limit_and_cancel_give_partial_results) {
  ss_halfspace_params p;
  index_matched_iso(&p, 0.999, 0.0);
  p.paths = 1000000000ull;
  p.time_limit = 0.2;
  ss_halfspace_result *r = run(&p);
  cr_expect(r->partial);
  cr_expect(!r->interrupted);
  cr_expect(r->paths > 0 && r->paths < p.paths);
  ss_halfspace_result_destroy(r);
  volatile sig_atomic_t cancel = 1;
  p.time_limit = 0.0;
  p.cancel = &cancel;
  r = run(&p);
  cr_expect(r->interrupted && r->partial);
  cr_expect_eq(r->paths, 0u);
  ss_halfspace_result_destroy(r);
}

Test(halfspace, invalid_parameters_are_rejected_with_the_option_named) {
  ss_halfspace_params p;
  ss_error err;
  ss_halfspace_params_default(&p);
  p.medium.sigma_s = ss_rgb_gray(-1.0);
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "sigma-s") != NULL, "%s", err.message);
  ss_halfspace_params_default(&p);
  p.medium.sigma_a = ss_rgb_gray(NAN);
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "sigma-a") != NULL, "%s", err.message);
  ss_halfspace_params_default(&p);
  p.medium.phase = SS_PHASE_HG;
  p.medium.g = ss_rgb_gray(1.0);
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "g") != NULL, "%s", err.message);
  ss_halfspace_params_default(&p);
  p.eta = 0.0;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "eta") != NULL, "%s", err.message);
  ss_halfspace_params_default(&p);
  p.theta_i = 95.0 * DEG;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "theta-i") != NULL, "%s", err.message);
  ss_halfspace_params_default(&p);
  p.thickness = -2.0;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "thickness") != NULL, "%s", err.message);
  /* libgomp exits the process for tens of thousands of threads. */
  ss_halfspace_params_default(&p);
  p.threads = 100000;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "threads must be in [0, 4096] (got 100000)"), "%s", err.message);
}

Test(halfspace, slab_exact_direction_radiance_integrates_to_the_reflectance) {
  /* At normal incidence the exitant radiance is azimuthally symmetric, so
   * R = 2 pi int_0^1 I(mu) mu dmu with I(mu) = int L dA; in a slab with a
   * refracting boundary I includes the images bounced between the faces. */
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.phase = SS_PHASE_HG;
  p.medium.g = ss_rgb_gray(0.5);
  p.medium.sigma_s = ss_rgb_gray(1.0);
  p.medium.sigma_a = ss_rgb_gray(0.1);
  p.eta = 1.33;
  p.thickness = 1.0;
  p.paths = 100000;
  p.xmin = -100.0;
  p.xmax = 100.0;
  p.xbins = 1;
  p.n_theta_o = SS_HALFSPACE_MAX_DIRECTIONS;
  gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(p.n_theta_o);
  double mu[SS_HALFSPACE_MAX_DIRECTIONS], w[SS_HALFSPACE_MAX_DIRECTIONS];
  for (int k = 0; k < p.n_theta_o; ++k) {
    gsl_integration_glfixed_point(0.0, 1.0, (size_t)k, &mu[k], &w[k], t);
    p.theta_o[k] = acos(mu[k]);
  }
  gsl_integration_glfixed_table_free(t);
  ss_halfspace_result *r = run(&p);
  double integral = 0.0;
  for (int k = 0; k < p.n_theta_o; ++k) {
    integral += 2.0 * SS_PI * w[k] * mu[k] * r->directions[k].value * 200.0;
  }
  cr_expect(fabs(integral - r->reflectance.value) < 3.0 * r->reflectance.error + 2e-3,
            "2 pi int I mu dmu = %.5f, R = %.5f +- %.5f", integral, r->reflectance.value,
            r->reflectance.error);
  ss_halfspace_result_destroy(r);
}

/* --max-depth N keeps paths that scatter up to N times: N = 1 is first-order
 * light, whose index-matched isotropic albedo is (albedo/2) [1 - mu0 ln(1 +
 * 1/mu0)] (Chandrasekhar 1950, the first term of his S function); the paths
 * that would scatter a second time are "truncated". */
Test(halfspace, max_depth_one_gives_the_single_scattering_albedo) {
  const double thetas[] = {0.0, 60.0};
  for (int t = 0; t < 2; ++t) {
    ss_halfspace_params p;
    index_matched_iso(&p, 0.8, thetas[t]);
    p.paths = 200000;
    p.max_depth = 1;
    ss_halfspace_result *r = run(&p);
    double mu0 = cos(thetas[t] * DEG);
    double expected = 0.4 * (1.0 - mu0 * log(1.0 + 1.0 / mu0));
    cr_expect(fabs(r->reflectance.value - expected) < 4.0 * r->reflectance.error,
              "theta %g: R1 = %.6f +- %.6f, exact %.6f", thetas[t], r->reflectance.value,
              r->reflectance.error, expected);
    double sum = r->reflectance.value + r->absorbed.value + r->truncated.value;
    cr_expect(fabs(sum - 1.0) < 1e-12, "R + A + truncated = %.15f", sum);
    cr_expect(r->scatter_events <= p.paths, "%llu events", (unsigned long long)r->scatter_events);
    ss_halfspace_result_destroy(r);
  }
}
