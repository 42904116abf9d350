/* The Gamma(2) inverse cdf of the radial samplers, by Halley steps, against
 * the lower branch of Lambert's W (GSL, which it replaces) and against its
 * defining equation. */
#include "bssrdf/bssrdf_util.h"

#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_lambert.h>
#include <math.h>

/* The old sampler: x = -1 - W_{-1}(-(1 - u)/e). */
static double lambert_inverse(double u) {
  gsl_sf_result res;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int st = gsl_sf_lambert_Wm1_e(-(1.0 - u) * 0.36787944117144233, &res);
  gsl_set_error_handler(old);
  cr_assert(st == GSL_SUCCESS || isfinite(res.val), "u = %g", u);
  return fmax(0.0, -1.0 - res.val);
}

Test(gamma2_inverse, equals_lambert_w_over_the_unit_interval) {
  double worst = 0.0;
  for (int i = 1; i < 20000; ++i) {
    double u = i / 20000.0;
    double x = ss_gamma2_inverse(u), ref = lambert_inverse(u);
    worst = fmax(worst, fabs(x - ref) / ref);
  }
  /* W_{-1} at double precision, and 1 - u rounded, bound the agreement. */
  cr_expect(worst < 1e-12, "worst relative difference %g", worst);
}

Test(gamma2_inverse, solves_its_equation_in_both_tails) {
  const double us[] = {1e-300, 1e-30, 1e-16,      1e-9,        1e-6,
                       1e-3,   0.5,   1.0 - 1e-6, 1.0 - 1e-12, 1.0 - 0x1p-53};
  for (size_t i = 0; i < sizeof us / sizeof us[0]; ++i) {
    double u = us[i], x = ss_gamma2_inverse(u);
    /* x - log(1 + x) = -log(1 - u), evaluated in long double so that its
     * cancellation for small x does not hide the error of x. The Halley
     * steps evaluate it in double: near x ~ 1e-3 that cancellation costs
     * about three of the sixteen digits, hence 1e-12 relative. */
    long double xl = x, t = -log1pl(-(long double)u), phi = xl - log1pl(xl);
    if (x < 1e-4) {
      phi = xl * xl * (0.5L - xl * (1.0L / 3 - xl * (0.25L - xl * (0.2L - xl / 6))));
    }
    cr_expect(fabsl(phi - t) <= 1e-12L * t, "u = %g: x %.17g phi %.17Lg t %.17Lg", u, x, phi, t);
  }
  cr_expect_eq(ss_gamma2_inverse(0.0), 0.0);
  cr_expect(isfinite(ss_gamma2_inverse(1.0)));
}

Test(gamma2_inverse, is_monotone) {
  double prev = 0.0;
  for (int i = 1; i < 100000; ++i) {
    double x = ss_gamma2_inverse(i / 100000.0);
    cr_assert(x > prev, "i = %d", i);
    prev = x;
  }
}
