/* The burley model's own identities (Christensen & Burley 2015): the profile
 * integrates to its albedo, the sampler inverts the closed-form radial cdf
 * exactly, the sampling density is the normalised profile, the albedo is the
 * exact one (a material given as albedo + mfp gets that albedo back), and
 * the fits scale the profile as the paper writes them. The interface's
 * contract (chi-square of sample_entry against pdf_entry, max_radius, totals)
 * is test_conformance's. */
#include "bssrdf/bssrdf_test_util.h"
#include "subsurf/albedo_inversion.h"
#include "subsurf/albedo_table.h"

#include <gsl/gsl_integration.h>

static ss_bssrdf *make_burley(double alpha, double sigma_t, double eta, double g, const char *fit) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, alpha * sigma_t, (1.0 - alpha) * sigma_t, g);
  p.eta = eta;
  ss_error err;
  if (fit) {
    cr_assert_eq(ss_bssrdf_params_set_option(&p, ss_bssrdf_model_find("burley"), "fit", fit, &err),
                 SS_OK);
  }
  ss_bssrdf *b = NULL;
  cr_assert_eq(ss_bssrdf_create("burley", &p, &b, &err), SS_OK, "%s", err.message);
  return b;
}

static double ring_profile(double r, void *ctx) {
  ss_bssrdf_profile_value v;
  ss_bssrdf_profile(ctx, 0, r, &v);
  return 2.0 * SS_PI * r * v.value;
}

/* d = l / s(A) from the paper's searchlight fit (eq. 6), l = 1/sigma_t'. */
static double searchlight_d(double A, double sigma_t_prime) {
  return 1.0 / sigma_t_prime / (1.85 - A + 7.0 * pow(fabs(A - 0.8), 3.0));
}

Test(burley, profile_integrates_to_its_albedo) {
  const double albedos[] = {0.2, 0.8, 0.99, 0.9999};
  const double etas[] = {1.0, 1.33, 1.5};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) {
      ss_bssrdf *b = make_burley(albedos[i], 2.0, etas[j], 0.0, NULL);
      gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
      gsl_function f = {ring_profile, b};
      double val, abserr, rd[3], total[3];
      gsl_integration_qagiu(&f, 0.0, 1e-12, 1e-10, 1000, ws, &val, &abserr);
      gsl_integration_workspace_free(ws);
      ss_bssrdf_rd(b, rd);
      ss_bssrdf_total_reflectance(b, 1.0, total);
      /* the core below 1e-6 d is clamped: 5e-7 of the total */
      cr_expect(fabs(val - rd[0]) < 1e-6 * rd[0], "albedo %g eta %g: %.9f vs %.9f", albedos[i],
                etas[j], val, rd[0]);
      cr_expect(fabs(total[0] - rd[0] * ss_albedo_max(etas[j])) < 1e-12);
      ss_bssrdf_destroy(b);
    }
  }
}

Test(burley, sampler_inverts_the_closed_form_cdf_exactly) {
  const double albedo = 0.9, sigma_t = 1.5, eta = 1.33;
  ss_bssrdf *b = make_burley(albedo, sigma_t, eta, 0.0, NULL);
  double total[3], rd[3];
  ss_bssrdf_total_reflectance(b, 1.0, total);
  ss_bssrdf_rd(b, rd);
  double d = searchlight_d(total[0], sigma_t);
  ss_bssrdf_sample_ctx ctx = default_sample_ctx();
  for (int i = 0; i <= 1000; ++i) {
    double u = i < 1000 ? i / 1000.0 : 1.0 - 1e-12;
    ss_bssrdf_entry e;
    cr_assert(ss_bssrdf_sample_entry(b, &ctx, 0, u, 0.25, &e));
    /* Christensen & Burley 2015: cdf 1 - e^{-r/d}/4 - 3 e^{-r/(3d)}/4. */
    double cdf = 1.0 - 0.25 * exp(-e.r / d) - 0.75 * exp(-e.r / (3.0 * d));
    cr_expect(fabs(cdf - u) < 1e-13, "u %.15g: cdf(r = %.15g) = %.15g", u, e.r, cdf);
    cr_expect(fabs(e.phi - 0.5 * SS_PI) < 1e-15);
    if (e.r > 1e-6 * d) {
      ss_bssrdf_profile_value v;
      ss_bssrdf_profile(b, 0, e.r, &v);
      cr_expect(fabs(e.pdf - v.value / rd[0]) < 1e-12 * e.pdf, "pdf %g vs R / A %g", e.pdf,
                v.value / rd[0]);
    }
  }
  ss_bssrdf_destroy(b);
}

Test(burley, material_albedo_comes_back_as_the_models_total_reflectance) {
  const double albedos[] = {0.05, 0.3, 0.6, 0.9};
  const double gs[] = {0.0, 0.45, 0.85};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) {
      double ss, sa;
      ss_error err;
      cr_assert_eq(ss_albedo_to_coefficients(SS_ALBEDO_INVERSION_EXACT, albedos[i], 0.7, gs[j], 1.4,
                                             &ss, &sa, &err),
                   SS_OK, "%s", err.message);
      ss_bssrdf *b = make_burley(ss / (ss + sa), ss + sa, 1.4, gs[j], NULL);
      double total[3];
      ss_bssrdf_total_reflectance(b, 1.0, total);
      cr_expect(fabs(total[0] - albedos[i]) < 1e-9, "albedo %g g %g: %.12f", albedos[i], gs[j],
                total[0]);
      ss_bssrdf_destroy(b);
    }
  }
}

/* The fits change only d: the max radius (26.77 d) scales by the ratio of s. */
Test(burley, fits_scale_the_profile_as_the_paper_writes_them) {
  const double alpha = 0.95, sigma_t = 1.0, eta = 1.2;
  ss_bssrdf *sl = make_burley(alpha, sigma_t, eta, 0.0, "searchlight");
  ss_bssrdf *df = make_burley(alpha, sigma_t, eta, 0.0, "diffuse");
  ss_bssrdf *dm = make_burley(alpha, sigma_t, eta, 0.0, "dmfp");
  double total[3];
  ss_bssrdf_total_reflectance(sl, 1.0, total);
  double A = total[0];
  double s_sl = 1.85 - A + 7.0 * pow(fabs(A - 0.8), 3.0);
  double s_df = 1.9 - A + 3.5 * (A - 0.8) * (A - 0.8);
  double s_dm = 3.5 + 100.0 * pow(A - 0.33, 4.0);
  double sigma_tr = sqrt(3.0 * (1.0 - alpha) * sigma_t * sigma_t);
  double r_sl = ss_bssrdf_max_radius(sl, 0);
  cr_expect(fabs(r_sl - 26.76797 * searchlight_d(A, sigma_t)) < 1e-3 * r_sl, "%g", r_sl);
  cr_expect(fabs(ss_bssrdf_max_radius(df, 0) / r_sl - s_sl / s_df) < 1e-12);
  cr_expect(fabs(ss_bssrdf_max_radius(dm, 0) / r_sl - s_sl / s_dm * sigma_t / sigma_tr) < 1e-12);
  ss_bssrdf_destroy(sl);
  ss_bssrdf_destroy(df);
  ss_bssrdf_destroy(dm);
}

Test(burley, refuses_media_outside_the_albedo_table) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, 0.9, 0.1, 0.0);
  p.eta = 2.5;
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("burley", &p, &b, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "burley: eta 2.5 is outside the albedo table's range"), "%s",
            err.message);
}
