/* An argument table (arg.h) reads numbers as the command line's grammar does
 * and refuses the others saying what was expected and what was given. */
#include "subsurf/arg.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

static const ss_arg args[] = {
    {"x", SS_ARG_NUMBER, 0, 0},      {"thickness", SS_ARG_NUMBER_OR_INF, 0, 0},
    {"count", SS_ARG_WHOLE, 1, 100}, {"seed", SS_ARG_WHOLE, 0, SS_ARG_U64_END},
    {NULL, SS_ARG_NUMBER, 0, 0},
};

static double parsed(const char *name, const char *text) {
  double v = -12345.0;
  ss_error err;
  cr_assert_eq(ss_arg_parse(ss_arg_find(args, name), text, &v, &err), SS_OK, "%s %s: %s", name,
               text, err.message);
  return v;
}

static void refused(const char *name, const char *text, const char *message) {
  double v = -12345.0;
  ss_error err;
  cr_expect_eq(ss_arg_parse(ss_arg_find(args, name), text, &v, &err), SS_ERR_INVALID_ARGUMENT,
               "%s %s", name, text);
  cr_expect_str_eq(err.message, message);
  cr_expect_eq(v, -12345.0, "%s %s: the value was written on failure", name, text);
}

Test(arg, numbers_and_whole_numbers_read_as_the_command_line_reads_them) {
  cr_expect_eq(parsed("x", "-2.5e-3"), -2.5e-3);
  cr_expect_eq(parsed("thickness", "inf"), INFINITY);
  cr_expect_eq(parsed("thickness", "infinite"), INFINITY);
  cr_expect_eq(parsed("thickness", "0.5"), 0.5);
  cr_expect_eq(parsed("count", "1e2"), 100.0);
  cr_expect_eq(parsed("count", "7.0"), 7.0);
  cr_expect_eq(parsed("seed", "18446744073709549568"), 18446744073709549568.0);
  cr_expect_null(ss_arg_find(args, "nope"));
  cr_expect_null(ss_arg_find(args, NULL));
}

Test(arg, malformed_and_out_of_range_values_are_refused_with_the_text_given) {
  refused("x", "nan", "expected a finite decimal number, got 'nan'");
  refused("x", "inf", "expected a finite decimal number, got 'inf'");
  refused("x", "1e309", "expected a finite decimal number, got '1e309'");
  refused("thickness", "-inf", "expected a finite decimal number or inf, got '-inf'");
  refused("count", "0", "expected a whole number in [1, 100], got '0'");
  refused("count", "101", "expected a whole number in [1, 100], got '101'");
  refused("count", "2.5", "expected a whole number in [1, 100], got '2.5'");
  refused("count", "nan", "expected a whole number in [1, 100], got 'nan'");
  refused("seed", "-1", "expected a whole number >= 0, got '-1'");
  refused("seed", "18446744073709551616",
          "expected a whole number >= 0, got '18446744073709551616'");
}
