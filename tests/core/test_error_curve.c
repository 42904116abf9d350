/* Error curves (error_curve.h) on exact power laws and exact bias floors:
 * the fit recovers the exponent and constant, the time to an error inverts
 * the line, the floor of e = c + k / n is c, and the time to an error below
 * a biased estimator's floor is infinite. */
#include "subsurf/error_curve.h"

#include <criterion/criterion.h>
#include <math.h>

Test(error_curve, loglog_fit_recovers_an_exact_power_law_and_inverts_it) {
  double t[6], e[6];
  for (int i = 0; i < 6; ++i) {
    t[i] = 0.1 * pow(2.0, i);
    e[i] = 3.0 * pow(t[i], -0.5);
  }
  double a, b;
  cr_assert_eq(ss_loglog_fit(t, e, 6, &a, &b), 6);
  cr_expect_float_eq(b, -0.5, 1e-12);
  cr_expect_float_eq(a, log(3.0), 1e-12);
  cr_expect_float_eq(ss_loglog_time_to(a, b, 3.0 * pow(7.0, -0.5)), 7.0, 1e-9);
  cr_expect(isinf(ss_loglog_time_to(a, 0.1, 1.0)), "a rising error never gets there");
}

Test(error_curve, points_without_positive_time_or_error_are_left_out) {
  double t[4] = {0.0, 1.0, 2.0, 4.0}, e[4] = {5.0, 0.0, 1.0, 0.5};
  double a, b;
  cr_expect_eq(ss_loglog_fit(t, e, 4, &a, &b), 2);
  cr_expect_float_eq(b, -1.0, 1e-12);
  cr_expect_eq(ss_loglog_fit(t, e, 2, &a, &b), 0);
}

Test(error_curve, floor_is_the_bias_of_an_error_falling_as_one_over_n) {
  double n[5] = {1, 2, 4, 8, 16}, biased[5], unbiased[5];
  for (int i = 0; i < 5; ++i) {
    biased[i] = 0.3 + 2.0 / n[i];
    unbiased[i] = 2.0 / n[i];
  }
  cr_expect_float_eq(ss_error_floor(n, biased, 5), 0.3, 1e-12);
  cr_expect_float_eq(ss_error_floor(n, unbiased, 5), 0.0, 1e-12);
  cr_expect_eq(ss_error_floor(n, biased, 1), biased[0]);
  /* A firefly in the last pass tilts the line above every observed error. */
  double tail[5] = {2.0, 1.0, 0.5, 0.25, 0.9};
  cr_expect_leq(ss_error_floor(n, tail, 5), 0.25, "floor %g above the errors",
                ss_error_floor(n, tail, 5));
}

Test(error_curve, time_to_an_error_respects_the_bias_floor) {
  double t[5] = {1, 2, 4, 8, 16}, biased[5], unbiased[5];
  for (int i = 0; i < 5; ++i) {
    biased[i] = 0.02 + 1.0 / t[i];
    unbiased[i] = 1.0 / t[i];
  }
  cr_expect_float_eq(ss_error_time_to(t, biased, 5, 0.03), 100.0, 1e-9);
  cr_expect(isinf(ss_error_time_to(t, biased, 5, 0.01)), "below the floor: never");
  cr_expect_float_eq(ss_error_time_to(t, unbiased, 5, 0.01), 100.0, 1e-9);
  cr_expect(isinf(ss_error_time_to(t, unbiased, 1, 0.01)), "one point fits nothing");
  double rising[3] = {0.1, 0.2, 0.4};
  cr_expect(isinf(ss_error_time_to(t, rising, 3, 0.05)), "an error that grows never gets there");
}

Test(error_curve, time_to_an_error_the_passes_reached_is_read_off_the_passes) {
  /* A floor fitted above a target the passes already reached must not hide
   * it: the run reached 0.5 between t = 2 and t = 4. */
  double t[4] = {1, 2, 4, 8}, e[4] = {1.0, 0.8, 0.4, 0.39};
  double at = ss_error_time_to(t, e, 4, 0.5);
  cr_expect(at > 2.0 && at < 4.0, "reached between the second and third pass, got %g", at);
  cr_expect_float_eq(at, 2.0 * exp(log(0.5 / 0.8) / log(0.5) * log(2.0)), 1e-12);
  cr_expect_float_eq(ss_error_time_to(t, e, 4, 2.0), 0.5, 1e-12, "before the first pass: 1/t");
}
