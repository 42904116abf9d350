/* Phase functions sample exactly what they evaluate (chi-square on the
 * sphere), integrate to 1, have mean cosine g, and reject invalid g.
 * Alpha is Sidak-corrected over the chi-square tests of this file. */
#include "subsurf/chi2.h"
#include "subsurf/phase.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <string.h>

#define NCHI2 11 /* 1 isotropic + 5 HG + 3 Gaussian + 2 tilted */
#define SAMPLES 1000000

static double alpha(void) { return ss_chi2_sidak_alpha(0.01, NCHI2); }

typedef struct {
  ss_phase phase;
  ss_vec3 dir; /* propagation direction before scattering */
} phase_ctx;

static int phase_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *d) {
  const phase_ctx *c = ctx;
  *d = ss_phase_sample(&c->phase, c->dir, u1, u2);
  return fabs(ss_vec3_length(*d) - 1.0) < 1e-9;
}

static double phase_pdf(void *ctx, ss_vec3 d) {
  const phase_ctx *c = ctx;
  return ss_phase_pdf(&c->phase, ss_vec3_dot(c->dir, d));
}

static void init_phase(ss_phase *p, ss_phase_type type, double g) {
  ss_error err = {0};
  cr_assert_eq(ss_phase_init(p, type, g, &err), SS_OK, "%s g %g: %s", ss_phase_type_name(type), g,
               err.message);
}

/* theta edges at pi (k/80)^3 put cells of a few microradians at the forward
 * peak, which for g = 0.99 is about 1e-2 rad wide. */
/* Each test draws its own random sequence (seed), so that one unlucky stream
 * cannot line up across tests. */
static void check_chi2(ss_phase_type type, double g, ss_vec3 dir, double theta_power,
                       uint64_t seed) {
  phase_ctx c;
  init_phase(&c.phase, type, g);
  c.dir = dir;
  ss_chi2_sphere_options o;
  ss_chi2_sphere_options_default(&o);
  o.samples = SAMPLES;
  o.theta_power = theta_power;
  o.seed = seed;
  ss_chi2_result res;
  ss_chi2_test_sphere(phase_sample, phase_pdf, &c, &o, &res);
  cr_assert_eq(res.invalid, 0u, "%s g %g: non-unit samples", ss_phase_type_name(type), g);
  cr_assert_gt(res.p_value, alpha(), "%s g %g: %s", ss_phase_type_name(type), g, res.message);
  cr_assert_float_eq(res.pdf_integral, 1.0, 1e-4, "%s g %g: %s", ss_phase_type_name(type), g,
                     res.message);
}

static const ss_vec3 up = {0.0, 0.0, 1.0};

Test(phase, isotropic_passes_chi2) { check_chi2(SS_PHASE_ISOTROPIC, 0.0, up, 1.0, 100); }

Test(phase, hg_passes_chi2_for_every_g) {
  const double gs[5] = {0.0, 0.3, 0.9, 0.99, -0.5};
  for (int i = 0; i < 5; ++i) {
    check_chi2(SS_PHASE_HG, gs[i], up, 3.0, 200 + (uint64_t)i);
  }
}

Test(phase, gaussian_passes_chi2_for_every_g) {
  const double gs[4] = {0.3, 0.9, 0.99, 0.0};
  for (int i = 0; i < 4; ++i) {
    check_chi2(SS_PHASE_GAUSS, gs[i], up, 3.0, 300 + (uint64_t)i);
  }
}

/* An oblique incoming direction exercises the frame that carries the sampled
 * cosine around the incoming direction. */
Test(phase, sampling_follows_an_oblique_incoming_direction) {
  ss_vec3 dir = ss_vec3_normalize(ss_vec3_make(0.6, -0.3, -0.5));
  check_chi2(SS_PHASE_HG, 0.3, dir, 1.0, 400);
  check_chi2(SS_PHASE_GAUSS, 0.3, dir, 1.0, 401);
}

/* ---- quadrature over mu = cos(theta) ---- */

typedef struct {
  const ss_phase *p;
  int power;
} mu_ctx;

static double mu_integrand(double mu, void *ctx) {
  const mu_ctx *c = ctx;
  return 2.0 * SS_PI * ss_phase_eval(c->p, mu) * (c->power ? mu : 1.0);
}

static double integrate_mu(const ss_phase *p, int power) {
  mu_ctx c = {p, power};
  gsl_function f = {mu_integrand, &c};
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(2000);
  double result = 0.0, abserr = 0.0;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  /* Split near the forward peak so the adaptive rule sees its scale. */
  const double pts[4] = {-1.0, 0.9, 0.9999, 1.0};
  double total = 0.0;
  for (int i = 0; i < 3; ++i) {
    gsl_integration_qag(&f, pts[i], pts[i + 1], 1e-13, 1e-11, 2000, GSL_INTEG_GAUSS61, ws, &result,
                        &abserr);
    total += result;
  }
  gsl_set_error_handler(old);
  gsl_integration_workspace_free(ws);
  return total;
}

static const struct {
  ss_phase_type type;
  double g;
} cases[] = {
    {SS_PHASE_ISOTROPIC, 0.0}, {SS_PHASE_HG, 0.0},     {SS_PHASE_HG, 0.3},
    {SS_PHASE_HG, 0.9},        {SS_PHASE_HG, 0.99},    {SS_PHASE_HG, -0.5},
    {SS_PHASE_HG, -0.99},      {SS_PHASE_GAUSS, 0.3},  {SS_PHASE_GAUSS, 0.9},
    {SS_PHASE_GAUSS, 0.99},    {SS_PHASE_GAUSS, 0.01}, {SS_PHASE_GAUSS, 0.999},
};
#define NCASES (sizeof cases / sizeof cases[0])

Test(phase, each_phase_function_integrates_to_one) {
  for (size_t i = 0; i < NCASES; ++i) {
    ss_phase p;
    init_phase(&p, cases[i].type, cases[i].g);
    double integral = integrate_mu(&p, 0);
    cr_assert_float_eq(integral, 1.0, 1e-8, "%s g %g: %.12f", ss_phase_type_name(p.type), p.g,
                       integral);
  }
}

Test(phase, evaluated_mean_cosine_is_g) {
  for (size_t i = 0; i < NCASES; ++i) {
    ss_phase p;
    init_phase(&p, cases[i].type, cases[i].g);
    double mean = integrate_mu(&p, 1);
    cr_assert_float_eq(mean, cases[i].g, 1e-8, "%s g %g: %.12f", ss_phase_type_name(p.type), p.g,
                       mean);
  }
}

/* The mean of N sampled cosines is within 4.5 standard errors of g. */
Test(phase, sampled_mean_cosine_is_g) {
  ss_rng rng;
  ss_rng_seed(&rng, 31u, 0u);
  for (size_t i = 0; i < NCASES; ++i) {
    ss_phase p;
    init_phase(&p, cases[i].type, cases[i].g);
    enum { N = 400000 };
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < N; ++k) {
      double mu = ss_phase_sample_cos(&p, ss_rng_uniform(&rng));
      cr_assert(mu >= -1.0 && mu <= 1.0, "cosine %g out of range", mu);
      sum += mu;
      sum2 += mu * mu;
    }
    double mean = sum / N, var = sum2 / N - mean * mean;
    double se = sqrt(var / N);
    cr_assert_float_eq(mean, cases[i].g, 4.5 * se + 1e-12, "%s g %g: mean %.6f, stderr %.2g",
                       ss_phase_type_name(p.type), p.g, mean, se);
  }
}

Test(phase, pdf_equals_eval) {
  for (size_t i = 0; i < NCASES; ++i) {
    ss_phase p;
    init_phase(&p, cases[i].type, cases[i].g);
    for (double mu = -1.0; mu <= 1.0; mu += 0.125) {
      cr_assert_eq(ss_phase_pdf(&p, mu), ss_phase_eval(&p, mu));
    }
  }
}

Test(phase, gauss_mu_from_g_inverts_g_from_mu) {
  const double gs[] = {1e-6, 1e-3, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999, 0.9999};
  for (size_t i = 0; i < sizeof gs / sizeof gs[0]; ++i) {
    double mu = ss_gauss_mu_from_g(gs[i]);
    cr_assert_gt(mu, 0.0);
    cr_assert_float_eq(ss_gauss_g_from_mu(mu), gs[i], 1e-10 * gs[i], "g %g -> mu %g -> g %.15g",
                       gs[i], mu, ss_gauss_g_from_mu(mu));
  }
  for (double lmu = -4.0; lmu <= 4.0; lmu += 0.25) {
    double mu = pow(10.0, lmu);
    cr_assert_float_eq(ss_gauss_mu_from_g(ss_gauss_g_from_mu(mu)), mu, 1e-8 * mu, "mu %g", mu);
  }
  /* g decreases with mu, and the branches of g(mu) join continuously. */
  for (double lmu = -4.0; lmu < 4.0; lmu += 0.01) {
    cr_assert_gt(ss_gauss_g_from_mu(pow(10.0, lmu)), ss_gauss_g_from_mu(pow(10.0, lmu + 0.01)));
  }
  const double joints[2] = {0.01, 10.0};
  for (int j = 0; j < 2; ++j) {
    double a = ss_gauss_g_from_mu(joints[j] * (1.0 - 1e-12));
    double b = ss_gauss_g_from_mu(joints[j] * (1.0 + 1e-12));
    cr_assert_float_eq(a, b, 1e-9 * a, "jump at mu = %g: %.15g vs %.15g", joints[j], a, b);
  }
}

static void assert_rejected(ss_phase_type type, double g) {
  ss_phase p;
  ss_error err = {0};
  cr_assert_eq(ss_phase_init(&p, type, g, &err), SS_ERR_INVALID_ARGUMENT, "%s g %g accepted",
               ss_phase_type_name(type), g);
  cr_assert_not_null(strstr(err.message, "g"), "message names g: '%s'", err.message);
  cr_assert_gt(strlen(err.message), 10u);
}

Test(phase, invalid_g_is_rejected_with_a_message) {
  const double bad[] = {1.0, -1.0, 1.5, -2.0, NAN, INFINITY, -INFINITY};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    assert_rejected(SS_PHASE_HG, bad[i]);
    assert_rejected(SS_PHASE_GAUSS, bad[i]);
    assert_rejected(SS_PHASE_ISOTROPIC, bad[i]);
  }
  assert_rejected(SS_PHASE_ISOTROPIC, 0.5);
  assert_rejected(SS_PHASE_GAUSS, -0.3);
  ss_phase p;
  ss_error err = {0};
  cr_assert_eq(ss_phase_init(&p, (ss_phase_type)42, 0.0, &err), SS_ERR_INVALID_ARGUMENT);
}

Test(phase, names_round_trip) {
  ss_phase_type t;
  cr_assert(ss_phase_type_from_name("iso", &t) && t == SS_PHASE_ISOTROPIC);
  cr_assert(ss_phase_type_from_name("isotropic", &t) && t == SS_PHASE_ISOTROPIC);
  cr_assert(ss_phase_type_from_name("hg", &t) && t == SS_PHASE_HG);
  cr_assert(ss_phase_type_from_name("gauss", &t) && t == SS_PHASE_GAUSS);
  cr_assert(ss_phase_type_from_name("gaussian", &t) && t == SS_PHASE_GAUSS);
  cr_assert_not(ss_phase_type_from_name("mie", &t));
  const ss_phase_type all[3] = {SS_PHASE_ISOTROPIC, SS_PHASE_HG, SS_PHASE_GAUSS};
  for (int i = 0; i < 3; ++i) {
    cr_assert(ss_phase_type_from_name(ss_phase_type_name(all[i]), &t) && t == all[i]);
  }
}
