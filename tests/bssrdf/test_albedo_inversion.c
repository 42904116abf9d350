/* albedo + mfp -> sigma_s, sigma_a (albedo_inversion.h): each inversion is
 * the exact inverse of its own forward quantity (the exact table's albedo,
 * Jensen's R_d, PBD's rho_eff, Christensen & Burley's fit), mfp is kept as
 * 1/sigma_t, and bad values are refused with a message naming them. */
#include "bssrdf/bssrdf_test_util.h"
#include "subsurf/albedo_inversion.h"
#include "subsurf/albedo_table.h"
#include "subsurf/pbd.h"

static double invert(ss_albedo_inversion m, double A, double g, double eta) {
  double ar;
  ss_error err;
  cr_assert_eq(ss_albedo_invert(m, A, g, eta, &ar, &err), SS_OK, "%s", err.message);
  cr_assert(ar >= 0.0 && ar <= 1.0, "alpha' %g", ar);
  return ar;
}

static double unreduce(double ar, double g) { return ar / (1.0 - g + g * ar); }

Test(albedo_inversion, exact_round_trips_through_the_table) {
  for (double A = 0.02; A < 0.96; A += 0.04) {
    double ar = invert(SS_ALBEDO_INVERSION_EXACT, A, 0.7, 1.45);
    double back;
    cr_assert_eq(ss_albedo_exact(unreduce(ar, 0.7), 0.7, 1.45, &back, NULL), SS_OK);
    cr_expect(fabs(back - A) < 1e-11, "%.12f -> %.12f", A, back);
  }
}

Test(albedo_inversion, dipole_inverts_jensens_rd) {
  const double etas[] = {1.0, 1.3, 1.6};
  for (int e = 0; e < 3; ++e) {
    for (double A = 0.05; A < 0.99; A += 0.1) {
      double ar = invert(SS_ALBEDO_INVERSION_DIPOLE, A, 0.0, etas[e]);
      ss_bssrdf *b = make_gray("dipole", ar, 1.0, etas[e], 0.0);
      double rd[3];
      ss_bssrdf_rd(b, rd);
      cr_expect(fabs(rd[0] - A) < 1e-9, "eta %g: R_d %.12f for %.12f", etas[e], rd[0], A);
      ss_bssrdf_destroy(b);
    }
  }
}

Test(albedo_inversion, pbd_inverts_the_effective_albedo) {
  for (double A = 0.1; A < 0.95; A += 0.2) {
    double ar = invert(SS_ALBEDO_INVERSION_PBD, A, 0.5, 1.33);
    double alpha = unreduce(ar, 0.5);
    ss_pbd p;
    cr_assert_eq(ss_pbd_init(&p, alpha, 1.0 - alpha, 0.5, 1.33, 34, NULL), SS_OK);
    cr_expect(fabs(ss_pbd_effective_albedo(&p) - A) < 1e-9, "%.12f for %.12f",
              ss_pbd_effective_albedo(&p), A);
  }
}

/* ChristensenBurley2015: alpha = (1 - s^2)/(1 - g s^2). */
Test(albedo_inversion, burley_is_the_papers_closed_form) {
  for (double C = 0.05; C < 1.0; C += 0.15) {
    double g = 0.6, ss, sa;
    double s = 4.09712 + 4.20863 * C - sqrt(9.59217 + 41.6808 * C + 17.7126 * C * C);
    cr_assert_eq(
        ss_albedo_to_coefficients(SS_ALBEDO_INVERSION_BURLEY, C, 2.0, g, 1.0, &ss, &sa, NULL),
        SS_OK);
    cr_expect(fabs(ss / (ss + sa) - (1.0 - s * s) / (1.0 - g * s * s)) < 1e-12);
    cr_expect(fabs(ss + sa - 0.5) < 1e-15, "mfp 2 is 1/sigma_t");
  }
}

Test(albedo_inversion, more_albedo_needs_more_scattering) {
  for (int m = 0; m < 4; ++m) {
    double prev = -1.0;
    for (double A = 0.05; A < 0.95; A += 0.05) {
      double ar = invert((ss_albedo_inversion)m, A, 0.3, 1.2);
      cr_expect(ar > prev, "%s: alpha' %g after %g at albedo %g",
                ss_albedo_inversion_name((ss_albedo_inversion)m), ar, prev, A);
      prev = ar;
    }
  }
}

static void expect_refused(ss_albedo_inversion m, double A, double mfp, double g, double eta,
                           const char *what) {
  double ss, sa;
  ss_error err;
  cr_expect_eq(ss_albedo_to_coefficients(m, A, mfp, g, eta, &ss, &sa, &err),
               SS_ERR_INVALID_ARGUMENT, "%s", what);
  cr_expect(strstr(err.message, what), "expected '%s' in '%s'", what, err.message);
}

Test(albedo_inversion, bad_values_are_refused_by_name) {
  expect_refused(SS_ALBEDO_INVERSION_EXACT, 0.0, 1.0, 0.0, 1.3, "albedo must lie in (0, 1)");
  expect_refused(SS_ALBEDO_INVERSION_DIPOLE, 1.0, 1.0, 0.0, 1.3, "albedo must lie in (0, 1)");
  expect_refused(SS_ALBEDO_INVERSION_EXACT, NAN, 1.0, 0.0, 1.3, "albedo must lie in (0, 1)");
  expect_refused(SS_ALBEDO_INVERSION_EXACT, 0.5, 0.0, 0.0, 1.3, "mfp must be finite and > 0");
  expect_refused(SS_ALBEDO_INVERSION_EXACT, 0.5, INFINITY, 0.0, 1.3, "mfp must be");
  expect_refused(SS_ALBEDO_INVERSION_EXACT, 0.97, 1.0, 0.0, 1.5, "albedo 0.97 is above 0.96");
  expect_refused(SS_ALBEDO_INVERSION_EXACT, 0.5, 1.0, 0.95, 1.3, "g 0.95 is outside");
  expect_refused(SS_ALBEDO_INVERSION_EXACT, 0.5, 1.0, 0.0, 2.0, "eta 2 is outside");
  expect_refused(SS_ALBEDO_INVERSION_BURLEY, 0.5, 1.0, 1.0, 1.0, "g must lie in (-1, 1)");
}
