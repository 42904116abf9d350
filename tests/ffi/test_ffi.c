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
      ss_ffi_model_create("dipole", sigma_s, sigma_a, g, 1.3, NULL, NULL, 0, NULL, err, sizeof err);
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
  cr_assert_eq(ss_ffi_model_total_reflectance(m, 0.6, a, err, sizeof err), 0, "%s", err);
  ss_bssrdf_total_reflectance(b, 0.6, want);
  const double x[2] = {0.3, -1.0}, y[2] = {0.0, 0.5};
  double ex[6], ex_want[3];
  cr_assert_eq(ss_ffi_model_exitance(m, 0.6, x, y, 2, ex, err, sizeof err), 0, "%s", err);
  ss_bssrdf_exitance(b, 0.6, x[1], y[1], ex_want);
  double r = 0.7, v, ms, ss;
  cr_assert_eq(ss_ffi_model_profile(m, 2, &r, 1, &v, &ms, &ss, err, sizeof err), 0, "%s", err);
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
      ss_ffi_model_create("nope", sigma_s, sigma_a, g, 1.3, NULL, NULL, 0, NULL, err, sizeof err));
  cr_expect(strstr(err, "unknown model 'nope'"), "%s", err);
  const char *names[1] = {"beam_samples"}, *values[1] = {"-2"};
  cr_expect_null(ss_ffi_model_create("pbd", sigma_s, sigma_a, g, 1.3, names, values, 1, NULL, err,
                                     sizeof err));
  cr_expect(strstr(err, "beam_samples"), "%s", err);
  const double bad_a[3] = {0.01, NAN, 0.2};
  cr_expect_null(
      ss_ffi_model_create("dipole", sigma_s, bad_a, g, 1.3, NULL, NULL, 0, NULL, err, sizeof err));
  cr_expect(strstr(err, "sigma-a"), "%s", err);
  double s[3], a[3], eta;
  cr_expect_neq(ss_ffi_preset("unobtainium", 1.0, 0.0, s, a, &eta, err, sizeof err), 0);
  cr_expect(strstr(err, "unobtainium"), "%s", err);
  cr_expect_eq(ss_ffi_preset("skin1", 2.0, 0.0, s, a, &eta, err, sizeof err), 0, "%s", err);
  cr_expect(s[0] > 0 && a[0] > 0 && eta > 1.0);
  /* --scale's range: (0, 1e6]. */
  cr_expect_neq(ss_ffi_preset("skin1", 2e6, 0.0, s, a, &eta, err, sizeof err), 0);
  cr_expect(strstr(err, "scale must be in (0, 1e+06] (got 2e+06)"), "%s", err);
  cr_expect_neq(ss_ffi_preset("skin1", 1.0, NAN, s, a, &eta, err, sizeof err), 0);
  cr_expect(strstr(err, "g must be in (-1, 1) (got nan)"), "%s", err);
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

Test(ffi, number_arguments_are_read_with_the_command_line_s_table_and_words) {
  char err[256] = "";
  double v = 0.0;
  cr_expect_eq(ss_ffi_arg_parse("halfspace", "threads", "8", &v, err, sizeof err), 0, "%s", err);
  cr_expect_eq(v, 8.0);
  cr_expect_eq(ss_ffi_arg_parse("halfspace", "thickness", "inf", &v, err, sizeof err), 0);
  cr_expect_eq(v, INFINITY);
  cr_expect_eq(ss_ffi_arg_parse("render", "spp", "1e3", &v, err, sizeof err), 0);
  cr_expect_eq(v, 1000.0);
  cr_expect_eq(ss_ffi_arg_parse("render", "threads", "100000", &v, err, sizeof err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect_str_eq(err, "expected a whole number in [0, 4096], got '100000'");
  cr_expect_neq(ss_ffi_arg_parse("render", "spp", "-1", &v, err, sizeof err), 0);
  cr_expect_str_eq(err, "expected a whole number in [1, 1073741824], got '-1'");
  cr_expect_neq(ss_ffi_arg_parse("halfspace", "sigma-s", "nan", &v, err, sizeof err), 0);
  cr_expect_str_eq(err, "expected a finite decimal number, got 'nan'");
  cr_expect_neq(ss_ffi_arg_parse("halfspace", "nope", "1", &v, err, sizeof err), 0);
  cr_expect(strstr(err, "nope"), "%s", err);
  cr_expect_neq(ss_ffi_arg_parse("nope", "spp", "1", &v, err, sizeof err), 0);
  cr_expect_neq(ss_ffi_arg_parse(NULL, NULL, NULL, &v, err, sizeof err), 0);
}

/* A thickness of 0, -1 or NaN used to mean a half-space. */
Test(ffi, halfspace_thickness_is_a_slab_s_or_infinite_never_a_silent_half_space) {
  char err[512] = "";
  double totals[8];
  const double bad[] = {0.0, -1.0, NAN, -INFINITY, 2e6};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    cr_expect_eq(ss_ffi_halfspace(sigma_s, sigma_a, g, 0, 1.3, 0.0, bad[i], 10, 1, 1, 0.01, 10.0, 8,
                                  totals, NULL, NULL, NULL, NULL, err, sizeof err),
                 SS_ERR_INVALID_ARGUMENT, "thickness %g", bad[i]);
    cr_expect(strstr(err, "thickness must be in (0, 1e+06] or inf"), "%s", err);
  }
}

Test(ffi, model_queries_outside_the_command_line_s_ranges_are_refused_before_evaluation) {
  char err[256] = "";
  int status = -1;
  ss_ffi_model *m = ss_ffi_model_create("dipole", sigma_s, sigma_a, g, 1.3, NULL, NULL, 0, &status,
                                        err, sizeof err);
  cr_assert_not_null(m, "%s", err);
  cr_expect_eq(status, SS_OK);
  double r[2] = {1.0, NAN}, v[2], out[6];
  cr_expect_eq(ss_ffi_model_profile(m, 0, r, 2, v, NULL, NULL, err, sizeof err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err, "r must be in [0, 1e+06] (got nan)"), "%s", err);
  r[1] = 1e300;
  cr_expect_neq(ss_ffi_model_profile(m, 0, r, 2, v, NULL, NULL, err, sizeof err), 0);
  r[1] = -1.0;
  cr_expect_neq(ss_ffi_model_profile(m, 0, r, 2, v, NULL, NULL, err, sizeof err), 0);
  cr_expect_neq(ss_ffi_model_profile(m, 3, r, 1, v, NULL, NULL, err, sizeof err), 0);
  cr_expect(strstr(err, "channel"), "%s", err);
  const double cos_bad[] = {0.0, -0.5, 1.5, NAN, INFINITY};
  for (size_t i = 0; i < sizeof cos_bad / sizeof cos_bad[0]; ++i) {
    cr_expect_neq(ss_ffi_model_total_reflectance(m, cos_bad[i], out, err, sizeof err), 0);
    cr_expect(strstr(err, "cos_i must be in (0, 1]"), "%s", err);
  }
  const double x[1] = {INFINITY}, y[1] = {0.0};
  cr_expect_neq(ss_ffi_model_exitance(m, 1.0, x, y, 1, out, err, sizeof err), 0);
  cr_expect(strstr(err, "x must be in"), "%s", err);
  const double x0[1] = {0.5}, w_down[3] = {0.0, 0.0, -1.0}, w_long[3] = {0.0, 0.0, 2.0},
               w_nan[3] = {NAN, 0.0, 1.0};
  cr_expect_neq(ss_ffi_model_radiance(m, 1.0, x0, y, w_down, 1, out, err, sizeof err), 0);
  cr_expect(strstr(err, "w_o must be unit vectors with z > 0"), "%s", err);
  cr_expect_neq(ss_ffi_model_radiance(m, 1.0, x0, y, w_long, 1, out, err, sizeof err), 0);
  cr_expect_neq(ss_ffi_model_radiance(m, 1.0, x0, y, w_nan, 1, out, err, sizeof err), 0);
  ss_ffi_model_destroy(m);
  const double bad_a[3] = {0.01, -1.0, 0.2};
  cr_expect_null(ss_ffi_model_create("dipole", sigma_s, bad_a, g, 1.3, NULL, NULL, 0, &status, err,
                                     sizeof err));
  cr_expect_eq(status, SS_ERR_INVALID_ARGUMENT, "%s", err);
}
