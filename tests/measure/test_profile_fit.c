/* Fitting media to radial exitance profiles: synthetic profiles of known
 * media, from the half-space reference and from the models themselves, give
 * the media back within the fit's standard errors. */
#include "subsurf/halfspace.h"
#include "subsurf/profile_fit.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_POINTS 64

typedef struct {
  size_t n;
  double r[MAX_POINTS], value[MAX_POINTS], error[MAX_POINTS];
  double r_lo[MAX_POINTS], r_hi[MAX_POINTS];
  int annuli; /* the values are averages over [r_lo, r_hi) */
} profile;

/* The reference's radial profile of a medium (sigma_s' = sigma_s, g 0) at
 * eta 1.3, times an exposure: its bins' averages, at their geometric
 * centres. */
static void reference_profile(double sigma_s_prime, double sigma_a, double exposure, uint64_t paths,
                              double rmin, double rmax, int bins, profile *out) {
  ss_halfspace_params hp;
  ss_halfspace_params_default(&hp);
  hp.medium = ss_medium_optics_gray(sigma_s_prime, sigma_a, 0.0, SS_PHASE_HG);
  hp.eta = 1.3;
  hp.paths = paths;
  hp.seed = 21;
  hp.rmin = rmin;
  hp.rmax = rmax;
  hp.rbins = bins + 1;
  hp.xbins = hp.ybins = 1;
  ss_halfspace_result *h;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(&hp, &h, &err), SS_OK, "%s", err.message);
  out->n = 0;
  out->annuli = 1;
  for (int i = 1; i <= bins; ++i) {
    if (h->radial[i].error > 0.0) {
      out->r[out->n] = sqrt(h->r_lo[i] * h->r_hi[i]);
      out->r_lo[out->n] = h->r_lo[i];
      out->r_hi[out->n] = h->r_hi[i];
      out->value[out->n] = exposure * h->radial[i].value;
      out->error[out->n] = exposure * h->radial[i].error;
      out->n++;
    }
  }
  ss_halfspace_result_destroy(h);
}

static ss_fit_data fit_data(const profile *d, int with_errors) {
  ss_fit_data data = {.n = d->n,
                      .r = d->r,
                      .value = d->value,
                      .error = with_errors ? d->error : NULL,
                      .r_lo = d->annuli ? d->r_lo : NULL,
                      .r_hi = d->annuli ? d->r_hi : NULL};
  return data;
}

static ss_fit_result fit(const ss_fit_params *p, const profile *d, int with_errors) {
  ss_fit_data data = fit_data(d, with_errors);
  ss_fit_result r;
  ss_error err;
  cr_assert_eq(ss_fit_run(p, &data, &r, &err), SS_OK, "%s", err.message);
  return r;
}

static void expect_within(const char *what, double got, double stderr_, double truth, double k) {
  cr_expect(fabs(got - truth) < k * stderr_, "%s: %g +- %g, true %g", what, got, stderr_, truth);
  cr_expect(stderr_ > 0.0 && stderr_ < 0.3 * truth, "%s: standard error %g of %g", what, stderr_,
            truth);
}

/* Two media of the measured table's range (albedo 0.98 and 0.8, mean free
 * paths 0.66 and 2.5 mm) with an unknown exposure: the exact model gives
 * sigma_a and sigma_s' back within 3 standard errors, and so it does with
 * the exposure known. */
Test(profile_fit, exact_model_recovers_reference_media) {
  const double media[][2] = {{1.5, 0.03}, {0.32, 0.08}}; /* sigma_s', sigma_a */
  for (int m = 0; m < 2; ++m) {
    double mfp = 1.0 / (media[m][0] + media[m][1]);
    profile d;
    reference_profile(media[m][0], media[m][1], 2.5, 200000, 0.2 * mfp, 12.0 * mfp, 20, &d);
    ss_fit_params p;
    ss_fit_params_default(&p);
    ss_fit_result r = fit(&p, &d, 1);
    cr_expect(r.converged, "medium %d did not converge", m);
    expect_within("sigma_s'", r.sigma_s_prime, r.sigma_s_prime_stderr, media[m][0], 3.0);
    expect_within("sigma_a", r.sigma_a, r.sigma_a_stderr, media[m][1], 3.0);
    expect_within("scale", r.scale, r.scale_stderr, 2.5, 3.0);
    cr_expect(r.chi2 / r.dof < 2.0, "medium %d: chi2 %g for %d degrees of freedom", m, r.chi2,
              r.dof);
    /* the exposure known: the table's absolute level (sigma_t'^2 per unit area) */
    for (size_t i = 0; i < d.n; ++i) {
      d.value[i] /= 2.5;
      d.error[i] /= 2.5;
    }
    p.absolute = 1;
    r = fit(&p, &d, 1);
    expect_within("sigma_s' (absolute)", r.sigma_s_prime, r.sigma_s_prime_stderr, media[m][0], 3.0);
    expect_within("sigma_a (absolute)", r.sigma_a, r.sigma_a_stderr, media[m][1], 3.0);
  }
}

/* A model's own profile with 2 % Gaussian noise: the fit (with and without
 * the standard errors, with the scale free and fixed) returns the medium
 * within 3.5 standard errors; the bootstrap's errors agree with the
 * Jacobian's within a factor 2. */
Test(profile_fit, models_recover_their_own_profiles) {
  const ss_fit_model models[] = {SS_FIT_DIPOLE, SS_FIT_BETTER_DIPOLE, SS_FIT_EXACT};
  const double sigma_s_prime = 2.2, sigma_a = 0.05, scale = 0.7;
  for (int m = 0; m < 3; ++m) {
    ss_fit_params p;
    ss_fit_params_default(&p);
    p.model = models[m];
    p.bootstrap = 40;
    profile d = {.n = 40};
    for (size_t i = 0; i < d.n; ++i) {
      d.r[i] = 0.2 * pow(60.0, i / 39.0);
    }
    ss_error err;
    cr_assert_eq(
        ss_fit_eval(&p, sigma_a, sigma_s_prime, scale, d.r, NULL, NULL, d.n, d.value, &err), SS_OK);
    ss_rng rng;
    ss_rng_seed(&rng, 5, (uint64_t)m);
    for (size_t i = 0; i < d.n; ++i) {
      /* Box-Muller */
      double u1 = 1.0 - ss_rng_uniform(&rng), u2 = ss_rng_uniform(&rng);
      double z = sqrt(-2.0 * log(u1)) * cos(2.0 * 3.14159265358979 * u2);
      d.error[i] = 0.02 * d.value[i];
      d.value[i] *= 1.0 + 0.02 * z;
    }
    for (int with_errors = 0; with_errors < 2; ++with_errors) {
      ss_fit_result r = fit(&p, &d, with_errors);
      const char *name = ss_fit_model_name(models[m]);
      cr_expect(r.converged, "%s did not converge", name);
      expect_within("sigma_s'", r.sigma_s_prime, r.sigma_s_prime_stderr, sigma_s_prime, 3.5);
      expect_within("sigma_a", r.sigma_a, r.sigma_a_stderr, sigma_a, 3.5);
      expect_within("scale", r.scale, r.scale_stderr, scale, 3.5);
      double ratio = r.sigma_a_boot_stderr / r.sigma_a_stderr;
      cr_expect(ratio > 0.5 && ratio < 2.0, "%s: bootstrap %g against Jacobian %g", name,
                r.sigma_a_boot_stderr, r.sigma_a_stderr);
    }
    /* the scale known: the data divided by it are per unit incident power */
    for (size_t i = 0; i < d.n; ++i) {
      d.value[i] /= scale;
      d.error[i] /= scale;
    }
    p.absolute = 1;
    ss_fit_result r = fit(&p, &d, 1);
    expect_within("sigma_a (absolute)", r.sigma_a, r.sigma_a_stderr, sigma_a, 3.5);
    cr_expect_eq(r.scale, 1.0);
    cr_expect_eq(r.dof, (int)r.used - 2);
  }
}

/* The automatic rmin leaves out the points nearer the beam than one
 * transport mean free path of the fitted medium. */
Test(profile_fit, automatic_rmin_is_one_transport_mean_free_path) {
  ss_fit_params p;
  ss_fit_params_default(&p);
  p.model = SS_FIT_DIPOLE;
  profile d = {.n = 40};
  for (size_t i = 0; i < d.n; ++i) {
    d.r[i] = 0.01 * pow(1000.0, i / 39.0);
  }
  ss_error err;
  cr_assert_eq(ss_fit_eval(&p, 0.1, 0.7, 1.0, d.r, NULL, NULL, d.n, d.value, &err), SS_OK);
  ss_fit_result r = fit(&p, &d, 0);
  cr_expect(r.rmin >= 1.25 && r.rmin < 1.25 * pow(1000.0, 1.0 / 39.0), "rmin %g", r.rmin);
  cr_expect(fabs(r.sigma_a - 0.1) < 1e-4 && fabs(r.sigma_s_prime - 0.7) < 1e-3, "%g %g", r.sigma_a,
            r.sigma_s_prime);
  p.rmin = 0.0;
  r = fit(&p, &d, 0);
  cr_expect_eq(r.used, d.n);
}

static void expect_refused(const profile *d, int with_errors, const char *needle) {
  ss_fit_params p;
  ss_fit_params_default(&p);
  p.model = SS_FIT_DIPOLE;
  p.rmin = 0.0;
  ss_fit_data data = fit_data(d, with_errors);
  ss_fit_result r;
  ss_error err;
  cr_expect_eq(ss_fit_run(&p, &data, &r, &err), SS_ERR_INVALID_ARGUMENT, "expected '%s'", needle);
  cr_expect(strstr(err.message, needle) != NULL, "'%s' lacks '%s'", err.message, needle);
}

Test(profile_fit, refuses_bad_profiles) {
  profile d = {.n = 6};
  for (size_t i = 0; i < d.n; ++i) {
    d.r[i] = 1.0 + (double)i;
    d.value[i] = exp(-(double)i);
    d.error[i] = 0.01;
  }
  d.value[2] = -1.0;
  expect_refused(&d, 1, "point 3: exitance -1");
  d.value[2] = NAN;
  expect_refused(&d, 1, "point 3: exitance nan");
  d.value[2] = 0.0;
  expect_refused(&d, 0, "point 3: exitance 0 (expected finite and > 0 without standard errors)");
  d.value[2] = 0.1;
  d.r[4] = 2.0;
  expect_refused(&d, 1, "point 5: radius 2");
  d.r[4] = 5.0;
  d.error[0] = 0.0;
  expect_refused(&d, 1, "point 1: standard error 0");
  d.error[0] = 0.01;
  d.annuli = 1;
  for (size_t i = 0; i < d.n; ++i) {
    d.r_lo[i] = d.r[i] - 0.5;
    d.r_hi[i] = d.r[i] + 0.5;
  }
  d.r_hi[3] = 3.5;
  expect_refused(&d, 1, "point 4: annulus [3.5, 3.5]");
  d.annuli = 0;
  d.n = 3;
  expect_refused(&d, 1, "3 points between");
}

Test(profile_fit, refuses_a_table_of_another_eta) {
  ss_fit_params p;
  ss_fit_params_default(&p);
  p.eta = 1.5;
  profile d = {.n = 5, .r = {1, 2, 3, 4, 5}, .value = {1, 0.5, 0.2, 0.1, 0.05}};
  ss_fit_data data = {.n = d.n, .r = d.r, .value = d.value};
  ss_fit_result r;
  ss_error err;
  cr_expect_eq(ss_fit_run(&p, &data, &r, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "built-in profile table is for eta 1.3") != NULL, "%s",
            err.message);
}
