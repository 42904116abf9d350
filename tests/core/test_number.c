/* The one number grammar (number.h): what people write as decimals reads
 * exactly as strtod reads it; everything else is refused. */
#include "subsurf/number.h"

#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>

Test(number, decimal_forms_read_as_strtod_reads_them) {
  const char *good[] = {"0", "5", "+3", "-2.5", ".5", "5.", "1e5", "1E-5", "-1.25e+3", "007"};
  for (size_t i = 0; i < sizeof good / sizeof good[0]; ++i) {
    double v = NAN;
    cr_expect(ss_number_parse(good[i], &v), "'%s' refused", good[i]);
    cr_expect_eq(v, strtod(good[i], NULL), "'%s' read as %g", good[i], v);
  }
}

Test(number, anything_but_a_finite_decimal_is_refused) {
  const char *bad[] = {"",       " 5",   "5 ",  "0x10", "nan",   "inf", "-inf", "1e309",
                       "-1e400", "5x",   "e5",  "1e",   "1e+",   "+",   "-",    ".",
                       "1,5",    "1..2", "--1", "+-1",  "1e5.5", "\t1", "1\n"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    double v = 42.0;
    cr_expect(!ss_number_parse(bad[i], &v), "'%s' accepted", bad[i]);
    cr_expect_eq(v, 42.0, "'%s' changed the output", bad[i]);
  }
}

Test(number, subnormals_read_as_themselves_and_negative_zero_as_zero) {
  double v;
  cr_assert(ss_number_parse("1e-320", &v));
  cr_expect(v > 0.0 && v < DBL_MIN, "1e-320 read as %g", v);
  cr_assert(ss_number_parse("-0", &v));
  cr_expect(v == 0.0 && !signbit(v), "-0 kept its sign");
  cr_assert(ss_number_parse("1.7976931348623157e308", &v));
  cr_expect_eq(v, DBL_MAX);
}

Test(number, a_field_of_a_list_reads_by_its_length) {
  double v;
  cr_expect(ss_number_parse_n("12,34", 2, &v) && v == 12.0);
  cr_expect(!ss_number_parse_n("12,34", 3, &v));
  cr_expect(!ss_number_parse_n("12,34", 0, &v));
}
