/* The random walk of layered surfaces (ss_layer_mc) against adding-doubling
 * and the slab tracer, and its conservation and reciprocity. */
#include "subsurf/halfspace.h"
#include "subsurf/layer.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>

#define DEG (SS_PI / 180.0)

static void one_layer(ss_layer_params *p, double tau, double albedo, double g, double eta) {
  ss_layer_params_default(p);
  p->layers[0].tau = tau;
  p->layers[0].albedo = albedo;
  cr_assert_eq(ss_phase_init(&p->layers[0].phase, SS_PHASE_HG, g, NULL), SS_OK);
  p->eta = eta;
  p->threads = 1;
  p->paths = 200000;
  p->seed = 3;
}

/* Two layers (HG over Gaussian) behind eta, over `bottom`. */
static void two_layers(ss_layer_params *p, double albedo, double eta, ss_layer_bottom bottom) {
  one_layer(p, 0.8, albedo, 0.5, eta);
  p->n_layers = 2;
  p->layers[1].tau = 2.0;
  p->layers[1].albedo = albedo;
  cr_assert_eq(ss_phase_init(&p->layers[1].phase, SS_PHASE_GAUSS, 0.6, NULL), SS_OK);
  p->bottom = bottom;
  p->bottom_albedo = 0.6;
  p->theta_i = 35.0 * DEG;
  p->n_theta_o = 3;
  p->theta_o[0] = 0.0;
  p->theta_o[1] = 30.0 * DEG;
  p->theta_o[2] = -70.0 * DEG;
}

static ss_layer_mc_result walk(const ss_layer_params *p) {
  ss_layer_mc_result r;
  ss_error err;
  cr_assert_eq(ss_layer_mc(p, &r, &err), SS_OK, "%s", err.message);
  cr_assert_eq(r.paths, p->paths);
  return r;
}

static ss_layer_result adding(const ss_layer_params *p) {
  ss_layer_result r;
  ss_error err;
  cr_assert_eq(ss_layer_adding(p, &r, &err), SS_OK, "%s", err.message);
  return r;
}

/* Within 4 standard errors (and a rounding floor). */
static void expect_near(double exact, double value, double error, const char *what, int k) {
  cr_expect(fabs(value - exact) <= 4.0 * error + 1e-9,
            "%s[%d]: walk %.6f +- %.6f, adding-doubling %.6f", what, k, value, error, exact);
}

static void expect_agreement(const ss_layer_params *p) {
  ss_layer_result a = adding(p);
  ss_layer_mc_result m = walk(p);
  const ss_layer_result *v = &m.value, *e = &m.error;
  cr_expect(fabs(v->specular - a.specular) < 1e-12);
  expect_near(a.reflectance, v->reflectance, e->reflectance, "reflectance", 0);
  expect_near(a.reflectance_unscattered, v->reflectance_unscattered, e->reflectance_unscattered,
              "reflectance_unscattered", 0);
  expect_near(a.transmittance, v->transmittance, e->transmittance, "transmittance", 0);
  expect_near(a.transmittance_unscattered, v->transmittance_unscattered,
              e->transmittance_unscattered, "transmittance_unscattered", 0);
  expect_near(a.absorbed, v->absorbed, e->absorbed, "absorbed", 0);
  for (int k = 0; k < p->n_theta_o; ++k) {
    cr_expect(v->brdf[k] > 0.0);
    expect_near(a.brdf[k], v->brdf[k], e->brdf[k], "brdf", k);
    expect_near(a.btdf[k], v->btdf[k], e->btdf[k], "btdf", k);
  }
}

Test(layer_mc, agrees_with_adding_doubling_for_a_slab) {
  ss_layer_params p;
  one_layer(&p, 1.0, 0.9, 0.7, 1.5);
  p.theta_i = 30.0 * DEG;
  p.n_theta_o = 3;
  p.theta_o[0] = 0.0;
  p.theta_o[1] = 40.0 * DEG;
  p.theta_o[2] = -60.0 * DEG;
  expect_agreement(&p);
}

Test(layer_mc, agrees_with_adding_doubling_for_stacks_over_every_bottom) {
  const ss_layer_bottom bottoms[] = {SS_LAYER_BOTTOM_SAME, SS_LAYER_BOTTOM_MATCHED,
                                     SS_LAYER_BOTTOM_DIFFUSE};
  for (int b = 0; b < 3; ++b) {
    ss_layer_params p;
    two_layers(&p, 0.85, 1.33, bottoms[b]);
    expect_agreement(&p);
  }
}

Test(layer_mc, lossless_stacks_conserve_energy) {
  const ss_layer_bottom bottoms[] = {SS_LAYER_BOTTOM_SAME, SS_LAYER_BOTTOM_MATCHED,
                                     SS_LAYER_BOTTOM_DIFFUSE};
  for (int b = 0; b < 3; ++b) {
    ss_layer_params p;
    two_layers(&p, 1.0, 1.5, bottoms[b]);
    p.bottom_albedo = 1.0;
    p.paths = 20000;
    ss_layer_mc_result m = walk(&p);
    const ss_layer_result *v = &m.value;
    double out = v->specular + v->reflectance + v->reflectance_unscattered + v->transmittance +
                 v->transmittance_unscattered;
    cr_expect(fabs(out - 1.0) < 1e-12 && fabs(v->absorbed) < 1e-12, "bottom %d: R + T = %.15f", b,
              out);
  }
}

Test(layer_mc, totals_equal_the_slab_tracer) {
  ss_layer_params p;
  one_layer(&p, 2.0, 0.95, 0.6, 1.33);
  p.theta_i = 50.0 * DEG;
  ss_halfspace_params h;
  ss_halfspace_params_default(&h);
  h.medium.sigma_s = ss_rgb_gray(0.95);
  h.medium.sigma_a = ss_rgb_gray(0.05);
  h.medium.phase = SS_PHASE_HG;
  h.medium.g = ss_rgb_gray(0.6);
  h.eta = 1.33;
  h.thickness = 2.0;
  h.theta_i = p.theta_i;
  h.paths = 200000;
  h.seed = 5;
  h.threads = 1;
  ss_halfspace_result *t = NULL;
  cr_assert_eq(ss_halfspace_run(&h, &t, NULL), SS_OK);
  ss_layer_mc_result m = walk(&p);
  const ss_layer_result *v = &m.value, *e = &m.error;
  double r = v->reflectance + v->reflectance_unscattered;
  double re = hypot(e->reflectance, e->reflectance_unscattered);
  double tr = v->transmittance + v->transmittance_unscattered;
  double te = hypot(e->transmittance, e->transmittance_unscattered);
  cr_expect(fabs(r - t->reflectance.value) < 4.0 * hypot(re, t->reflectance.error),
            "R %.6f against the tracer's %.6f", r, t->reflectance.value);
  cr_expect(fabs(tr - t->transmittance.value) < 4.0 * hypot(te, t->transmittance.error),
            "T %.6f against the tracer's %.6f", tr, t->transmittance.value);
  cr_expect(fabs(v->absorbed - t->absorbed.value) < 4.0 * hypot(e->absorbed, t->absorbed.error),
            "absorbed %.6f against the tracer's %.6f", v->absorbed, t->absorbed.value);
  ss_halfspace_result_destroy(t);
}

Test(layer_mc, brdf_and_btdf_are_reciprocal) {
  const double a = 20.0 * DEG, b = 55.0 * DEG;
  ss_layer_mc_result r[2];
  for (int k = 0; k < 2; ++k) {
    ss_layer_params p;
    two_layers(&p, 0.9, 1.33, SS_LAYER_BOTTOM_SAME);
    p.seed = 20 + (uint64_t)k;
    p.theta_i = k ? b : a;
    p.n_theta_o = 1;
    p.theta_o[0] = k ? -a : -b;
    r[k] = walk(&p);
  }
  double d = r[0].value.brdf[0] - r[1].value.brdf[0];
  cr_expect(fabs(d) < 4.0 * hypot(r[0].error.brdf[0], r[1].error.brdf[0]), "brdf %.6f against %.6f",
            r[0].value.brdf[0], r[1].value.brdf[0]);
  d = r[0].value.btdf[0] - r[1].value.btdf[0];
  cr_expect(fabs(d) < 4.0 * hypot(r[0].error.btdf[0], r[1].error.btdf[0]), "btdf %.6f against %.6f",
            r[0].value.btdf[0], r[1].value.btdf[0]);
}

Test(layer_mc, results_do_not_depend_on_the_thread_count) {
  ss_layer_params p;
  two_layers(&p, 0.9, 1.5, SS_LAYER_BOTTOM_DIFFUSE);
  p.paths = 30000;
  ss_layer_mc_result one = walk(&p);
  p.threads = 2;
  ss_layer_mc_result two = walk(&p);
  cr_expect(one.value.reflectance == two.value.reflectance);
  cr_expect(one.error.reflectance == two.error.reflectance);
  cr_expect(one.value.brdf[2] == two.value.brdf[2]);
}

Test(layer_mc, cancel_stops_the_walk_with_what_it_has) {
  ss_layer_params p;
  one_layer(&p, 1.0, 0.9, 0.0, 1.0);
  volatile sig_atomic_t stop = 1;
  p.cancel = &stop;
  ss_layer_mc_result r;
  cr_assert_eq(ss_layer_mc(&p, &r, NULL), SS_OK);
  cr_expect(r.interrupted && r.paths < p.paths);
}
