/* Adding-doubling and the first-order closed forms of layered surfaces
 * (layer.h), against exact identities and the slab tracer. */
#include "subsurf/halfspace.h"
#include "subsurf/layer.h"
#include "subsurf/sampling.h"

#include "transport/chandrasekhar.h"

#include <criterion/criterion.h>
#include <math.h>

#define DEG (SS_PI / 180.0)

static void one_layer(ss_layer_params *p, double tau, double albedo, ss_phase_type type, double g,
                      double eta) {
  ss_layer_params_default(p);
  p->layers[0].tau = tau;
  p->layers[0].albedo = albedo;
  cr_assert_eq(ss_phase_init(&p->layers[0].phase, type, g, NULL), SS_OK);
  p->eta = eta;
  p->threads = 1;
}

static ss_layer_result solve(const ss_layer_params *p, int first_order) {
  ss_layer_result r;
  ss_error err;
  ss_status st = first_order ? ss_layer_first_order(p, &r, &err) : ss_layer_adding(p, &r, &err);
  cr_assert_eq(st, SS_OK, "%s", err.message);
  return r;
}

Test(layer, lossless_stack_conserves_energy) {
  ss_layer_params p;
  one_layer(&p, 0.8, 1.0, SS_PHASE_HG, 0.5, 1.5);
  p.n_layers = 2;
  p.layers[1].tau = 2.0;
  p.layers[1].albedo = 1.0;
  ss_phase_init(&p.layers[1].phase, SS_PHASE_GAUSS, 0.6, NULL);
  p.theta_i = 35.0 * DEG;
  const ss_layer_bottom bottoms[] = {SS_LAYER_BOTTOM_SAME, SS_LAYER_BOTTOM_MATCHED};
  for (int b = 0; b < 2; ++b) {
    p.bottom = bottoms[b];
    ss_layer_result r = solve(&p, 0);
    cr_expect(fabs(r.absorbed) < 1e-6, "bottom %d: R + T = 1 - %g", b, r.absorbed);
    cr_expect(r.reflectance > 0.05 && r.transmittance > 0.05);
  }
  p.bottom = SS_LAYER_BOTTOM_DIFFUSE;
  p.bottom_albedo = 1.0;
  ss_layer_result r = solve(&p, 0);
  cr_expect(fabs(r.absorbed) < 1e-6, "white base: absorbed %g", r.absorbed);
}

Test(layer, thick_isotropic_layer_gives_chandrasekhar_albedo) {
  h_function hf;
  h_solve(&hf, 0.8);
  ss_layer_params p;
  one_layer(&p, 100.0, 0.8, SS_PHASE_ISOTROPIC, 0.0, 1.0);
  p.bottom = SS_LAYER_BOTTOM_MATCHED;
  p.n_theta_o = 1;
  p.theta_o[0] = -25.0 * DEG;
  const double thetas[] = {0.0, 60.0, 80.0};
  for (int t = 0; t < 3; ++t) {
    p.theta_i = thetas[t] * DEG;
    ss_layer_result r = solve(&p, 0);
    double mu0 = cos(p.theta_i);
    cr_expect(fabs(r.reflectance - h_albedo(&hf, mu0)) < 1e-5, "theta %g: R %.7f, exact %.7f",
              thetas[t], r.reflectance, h_albedo(&hf, mu0));
    /* Chandrasekhar's S: f = albedo H(mu) H(mu0) / (4 pi (mu + mu0)). */
    double f = h_radiance(&hf, cos(p.theta_o[0]), mu0);
    cr_expect(fabs(r.brdf[0] / f - 1.0) < 1e-4, "theta %g: f %.7f, exact %.7f", thetas[t],
              r.brdf[0], f);
  }
}

Test(layer, brdf_and_btdf_are_reciprocal) {
  ss_layer_params p;
  one_layer(&p, 2.0, 0.95, SS_PHASE_HG, 0.6, 1.33);
  p.n_theta_o = 2;
  const double a = 20.0 * DEG, b = 55.0 * DEG;
  double f[2][2];
  for (int k = 0; k < 2; ++k) {
    p.theta_i = k ? b : a;
    p.theta_o[0] = k ? a : b;   /* forward: dphi = 0 */
    p.theta_o[1] = k ? -a : -b; /* backward */
    ss_layer_result r = solve(&p, 0);
    f[k][0] = r.brdf[1];
    f[k][1] = r.btdf[0];
  }
  cr_expect(fabs(f[0][0] / f[1][0] - 1.0) < 1e-6, "brdf %.9f against %.9f", f[0][0], f[1][0]);
  cr_expect(fabs(f[0][1] / f[1][1] - 1.0) < 1e-6, "btdf %.9f against %.9f", f[0][1], f[1][1]);
}

Test(layer, two_halves_added_equal_one_layer_doubled) {
  ss_layer_params one, two;
  one_layer(&one, 1.4, 0.9, SS_PHASE_HG, 0.4, 1.5);
  one.theta_i = 40.0 * DEG;
  one.n_theta_o = 2;
  one.theta_o[0] = 10.0 * DEG;
  one.theta_o[1] = -70.0 * DEG;
  two = one;
  two.n_layers = 2;
  two.layers[0].tau = two.layers[1].tau = 0.7;
  two.layers[1] = two.layers[0];
  ss_layer_result r1 = solve(&one, 0), r2 = solve(&two, 0);
  cr_expect(fabs(r1.reflectance - r2.reflectance) < 1e-7);
  cr_expect(fabs(r1.transmittance - r2.transmittance) < 1e-7);
  for (int k = 0; k < 2; ++k) {
    cr_expect(fabs(r1.brdf[k] / r2.brdf[k] - 1.0) < 1e-6);
    cr_expect(fabs(r1.btdf[k] / r2.btdf[k] - 1.0) < 1e-6);
  }
}

Test(layer, doubling_from_a_thin_start_equals_the_direct_thin_layer) {
  /* A layer of tau 1e-4 from Blinn's single scattering directly (no
   * doubling) differs from the doubled one only by double scattering,
   * O(tau) relative; deeper layers converge as the start thins. */
  ss_layer_params p;
  one_layer(&p, 1e-4, 1.0, SS_PHASE_HG, 0.3, 1.0);
  p.n_theta_o = 1;
  p.theta_o[0] = 30.0 * DEG;
  p.thin_tau = 1.0;
  ss_layer_result direct = solve(&p, 0);
  cr_expect_eq(direct.doublings, 0);
  p.thin_tau = ldexp(1.0, -30);
  ss_layer_result doubled = solve(&p, 0);
  cr_expect(doubled.doublings > 10);
  cr_expect(fabs(direct.brdf[0] / doubled.brdf[0] - 1.0) < 1e-3, "%.9g against %.9g",
            direct.brdf[0], doubled.brdf[0]);
  cr_expect(fabs(direct.reflectance / doubled.reflectance - 1.0) < 1e-3);
  p.layers[0].tau = 3.0;
  p.thin_tau = ldexp(1.0, -20);
  ss_layer_result coarse = solve(&p, 0);
  p.thin_tau = ldexp(1.0, -30);
  ss_layer_result fine = solve(&p, 0);
  cr_expect(fabs(coarse.brdf[0] / fine.brdf[0] - 1.0) < 2e-5);
  cr_expect(fabs(fine.absorbed) < 1e-7);
}

Test(layer, first_order_matches_adding_at_low_albedo) {
  ss_layer_params p;
  one_layer(&p, 1.5, 1e-3, SS_PHASE_HG, 0.3, 1.5);
  p.theta_i = 25.0 * DEG;
  p.n_theta_o = 3;
  p.theta_o[0] = 0.0;
  p.theta_o[1] = 45.0 * DEG;
  p.theta_o[2] = -60.0 * DEG;
  const ss_layer_bottom bottoms[] = {SS_LAYER_BOTTOM_SAME, SS_LAYER_BOTTOM_MATCHED,
                                     SS_LAYER_BOTTOM_DIFFUSE};
  for (int b = 0; b < 3; ++b) {
    p.bottom = bottoms[b];
    p.bottom_albedo = 1e-3;
    ss_layer_result ad = solve(&p, 0), fo = solve(&p, 1);
    for (int k = 0; k < 3; ++k) {
      cr_expect(fabs(fo.brdf[k] / ad.brdf[k] - 1.0) < 3e-3, "bottom %d, %d: brdf %.9g, %.9g", b, k,
                fo.brdf[k], ad.brdf[k]);
      if (b != 2) {
        cr_expect(fabs(fo.btdf[k] / ad.btdf[k] - 1.0) < 3e-3, "bottom %d, %d: btdf %.9g, %.9g", b,
                  k, fo.btdf[k], ad.btdf[k]);
      }
    }
    cr_expect(fabs(fo.reflectance / ad.reflectance - 1.0) < 3e-3, "bottom %d: R %.9g, %.9g", b,
              fo.reflectance, ad.reflectance);
    cr_expect(fabs(fo.transmittance_unscattered - ad.transmittance_unscattered) < 1e-9,
              "%d: %.12g %.12g", b, fo.transmittance_unscattered, ad.transmittance_unscattered);
    cr_expect(fabs(fo.reflectance_unscattered - ad.reflectance_unscattered) < 1e-9);
  }
}

static ss_halfspace_result *slab_tracer(double tau, double albedo, double g, double eta,
                                        double theta_i, const double *theta_o, int n,
                                        uint64_t depth) {
  ss_halfspace_params h;
  ss_halfspace_params_default(&h);
  h.medium.sigma_s = ss_rgb_gray(albedo);
  h.medium.sigma_a = ss_rgb_gray(1.0 - albedo);
  h.medium.phase = SS_PHASE_HG;
  h.medium.g = ss_rgb_gray(g);
  h.eta = eta;
  h.thickness = tau;
  h.theta_i = theta_i;
  h.n_theta_o = n;
  for (int k = 0; k < n; ++k) {
    h.theta_o[k] = theta_o[k];
  }
  h.xmin = -1e5; /* one x bin holding all of int L dA */
  h.xmax = 1e5;
  h.xbins = 1;
  h.paths = 300000;
  h.max_depth = depth;
  h.seed = 11;
  h.threads = 1;
  ss_halfspace_result *r = NULL;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(&h, &r, &err), SS_OK, "%s", err.message);
  return r;
}

static void expect_within(double value, ss_estimate e, double rel, const char *what) {
  double tol = 4.0 * e.error + rel * fabs(value);
  cr_expect(fabs(value - e.value) < tol, "%s: %.6f against the tracer's %.6f +- %.6f", what, value,
            e.value, e.error);
}

Test(layer, adding_matches_the_slab_tracer) {
  const double theta_o[] = {0.0, 40.0 * DEG, -60.0 * DEG};
  ss_layer_params p;
  one_layer(&p, 1.0, 0.9, SS_PHASE_HG, 0.7, 1.5);
  p.theta_i = 30.0 * DEG;
  p.n_theta_o = 3;
  for (int k = 0; k < 3; ++k) {
    p.theta_o[k] = theta_o[k];
  }
  ss_layer_result r = solve(&p, 0);
  ss_halfspace_result *mc = slab_tracer(1.0, 0.9, 0.7, 1.5, p.theta_i, theta_o, 3, 1000000);
  expect_within(r.reflectance + r.reflectance_unscattered, mc->reflectance, 0.0, "R");
  expect_within(r.transmittance + r.transmittance_unscattered, mc->transmittance, 0.0, "T");
  expect_within(r.absorbed, mc->absorbed, 0.0, "absorbed");
  cr_expect(fabs(r.specular - mc->specular.value) < 1e-12);
  for (int k = 0; k < 3; ++k) {
    ss_estimate f = {mc->directions[k].value * 2e5, mc->directions[k].error * 2e5};
    expect_within(r.brdf[k], f, 1e-3, "brdf");
  }
  ss_halfspace_result_destroy(mc);
}

Test(layer, first_order_equals_the_tracer_limited_to_one_event) {
  const double theta_o[] = {10.0 * DEG, -50.0 * DEG};
  ss_layer_params p;
  one_layer(&p, 0.5, 0.8, SS_PHASE_HG, 0.5, 1.33);
  p.theta_i = 50.0 * DEG;
  p.n_theta_o = 2;
  p.theta_o[0] = theta_o[0];
  p.theta_o[1] = theta_o[1];
  ss_layer_result r = solve(&p, 1);
  ss_halfspace_result *mc = slab_tracer(0.5, 0.8, 0.5, 1.33, p.theta_i, theta_o, 2, 1);
  expect_within(r.reflectance + r.reflectance_unscattered, mc->reflectance, 0.0, "R");
  expect_within(r.transmittance + r.transmittance_unscattered, mc->transmittance, 0.0, "T");
  for (int k = 0; k < 2; ++k) {
    ss_estimate f = {mc->directions[k].value * 2e5, mc->directions[k].error * 2e5};
    expect_within(r.brdf[k], f, 0.0, "brdf");
  }
  ss_halfspace_result_destroy(mc);
}

Test(layer, bad_input_is_refused_naming_the_parameter) {
  ss_layer_params p;
  ss_error err;
  ss_layer_result r;
  ss_layer_params_default(&p);
  p.n_layers = 0;
  cr_expect_eq(ss_layer_adding(&p, &r, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "layers") != NULL, "%s", err.message);
  ss_layer_params_default(&p);
  p.layers[0].tau = -1.0;
  cr_expect_eq(ss_layer_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "optical depth") != NULL, "%s", err.message);
  ss_layer_params_default(&p);
  p.eta = 0.0;
  cr_expect_eq(ss_layer_first_order(&p, &r, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "eta") != NULL, "%s", err.message);
  ss_layer_params_default(&p);
  p.nodes = SS_LAYER_MAX_NODES + 1;
  cr_expect_eq(ss_layer_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "nodes") != NULL, "%s", err.message);
  ss_layer_params_default(&p);
  p.layers[0].albedo = NAN;
  cr_expect_eq(ss_layer_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "albedo") != NULL, "%s", err.message);
}
