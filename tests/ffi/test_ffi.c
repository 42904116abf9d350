/* The flat interface (ffi.h) answers what the library it wraps answers, and
 * reports bad input as text (also run under ASan + UBSan, which the Python
 * tests cannot be). */
#include "subsurf/bssrdf.h"
#include "subsurf/ffi.h"
#include "subsurf/halfspace.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

static const double sigma_s[3] = {1.0, 2.0, 4.0};
static const double sigma_a[3] = {0.01, 0.05, 0.2};
static const double g[3] = {0.0, 0.0, 0.0};

Test(ffi, model_answers_equal_the_registry_s) {
  char err[256] = "";
  ss_ffi_model *m =
      ss_ffi_model_create("dipole", sigma_s, sigma_a, g, 1.3, NULL, NULL, 0, err, sizeof err);
  cr_assert_not_null(m, "%s", err);
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  for (int c = 0; c < 3; c++) {
    p.medium.sigma_s.c[c] = sigma_s[c];
    p.medium.sigma_a.c[c] = sigma_a[c];
    p.medium.g.c[c] = 0.0;
  }
  p.medium.phase = SS_PHASE_HG;
  p.eta = 1.3;
  ss_bssrdf *b;
  ss_error e;
  cr_assert_eq(ss_bssrdf_create("dipole", &p, &b, &e), SS_OK, "%s", e.message);

  double a[3], want[3];
  ss_ffi_model_total_reflectance(m, 0.6, a);
  ss_bssrdf_total_reflectance(b, 0.6, want);
  const double x[2] = {0.3, -1.0}, y[2] = {0.0, 0.5};
  double ex[6], ex_want[3];
  ss_ffi_model_exitance(m, 0.6, x, y, 2, ex);
  ss_bssrdf_exitance(b, 0.6, x[1], y[1], ex_want);
  double r = 0.7, v, ms, ss;
  ss_ffi_model_profile(m, 2, &r, 1, &v, &ms, &ss);
  ss_bssrdf_profile_value pv;
  ss_bssrdf_profile(b, 2, r, &pv);
  for (int c = 0; c < 3; c++) {
    cr_expect_eq(a[c], want[c]);
    cr_expect_eq(ex[3 + c], ex_want[c]);
  }
  cr_expect_eq(v, pv.value);
  cr_expect_eq(ms, pv.ms);
  cr_expect_eq(ss, pv.ss);
  cr_expect(ss_ffi_model_flags(m) & SS_BSSRDF_RADIAL);
  ss_bssrdf_destroy(b);
  ss_ffi_model_destroy(m);
}

Test(ffi, bad_models_and_options_are_named_in_the_message) {
  char err[512] = "";
  cr_expect_null(
      ss_ffi_model_create("nope", sigma_s, sigma_a, g, 1.3, NULL, NULL, 0, err, sizeof err));
  cr_expect(strstr(err, "unknown model 'nope'"), "%s", err);
  const char *names[1] = {"beam_samples"}, *values[1] = {"-2"};
  cr_expect_null(
      ss_ffi_model_create("pbd", sigma_s, sigma_a, g, 1.3, names, values, 1, err, sizeof err));
  cr_expect(strstr(err, "beam_samples"), "%s", err);
  const double bad_a[3] = {0.01, NAN, 0.2};
  cr_expect_null(
      ss_ffi_model_create("dipole", sigma_s, bad_a, g, 1.3, NULL, NULL, 0, err, sizeof err));
  cr_expect(strstr(err, "sigma_a"), "%s", err);
  double s[3], a[3], eta;
  cr_expect_neq(ss_ffi_preset("unobtainium", 1.0, 0.0, s, a, &eta, err, sizeof err), 0);
  cr_expect(strstr(err, "unobtainium"), "%s", err);
  cr_expect_eq(ss_ffi_preset("skin1", 2.0, 0.0, s, a, &eta, err, sizeof err), 0, "%s", err);
  cr_expect(s[0] > 0 && a[0] > 0 && eta > 1.0);
}

Test(ffi, halfspace_totals_balance_and_bad_parameters_fail) {
  char err[512] = "";
  double totals[8], radial[8], radial_err[8], lo[8], hi[8];
  cr_assert_eq(ss_ffi_halfspace(sigma_s, sigma_a, g, 1, 1.3, 0.2, INFINITY, 4000, 5, 1, 0.01, 10.0,
                                8, totals, lo, hi, radial, radial_err, err, sizeof err),
               0, "%s", err);
  /* Every path is reflected diffusely, transmitted, specular or absorbed
   * (absorption is tallied by weight under Russian roulette: equal in
   * expectation, within a few standard errors). */
  double sum = totals[0] + totals[2] + totals[4] + totals[6];
  cr_expect(fabs(sum - 1.0) < 4.0 * (totals[1] + totals[7]), "sum %.12f", sum);
  cr_expect(totals[1] > 0 && totals[1] < 0.05);
  cr_expect_eq(lo[0], 0.0);
  cr_expect(fabs(hi[7] - 10.0) < 1e-12);
  cr_expect_neq(ss_ffi_halfspace(sigma_s, sigma_a, g, 3, 1.3, 0.0, INFINITY, 10, 1, 1, 0.01, 10.0,
                                 8, totals, NULL, NULL, NULL, NULL, err, sizeof err),
                0);
  cr_expect(strstr(err, "channel"), "%s", err);
  /* libgomp exits the process (or a thread's stack is never mapped) for
   * tens of thousands of threads: refused before any work. */
  cr_expect_neq(ss_ffi_halfspace(sigma_s, sigma_a, g, 0, 1.3, 0.0, INFINITY, 10, 1, 100000, 0.01,
                                 10.0, 8, totals, NULL, NULL, NULL, NULL, err, sizeof err),
                0);
  cr_expect(strstr(err, "threads must be in [0, 4096] (got 100000)"), "%s", err);
}

Test(ffi, missing_scene_and_image_files_are_named) {
  char err[512] = "";
  cr_expect_null(ss_ffi_scene_load("/nonexistent/scene.json", err, sizeof err));
  cr_expect(strstr(err, "/nonexistent/scene.json"), "%s", err);
  int w, h, c;
  cr_expect_neq(ss_ffi_image_read("/nonexistent/x.exr", &w, &h, &c, NULL, 0, err, sizeof err), 0);
  cr_expect(strstr(err, "/nonexistent/x.exr"), "%s", err);
}
