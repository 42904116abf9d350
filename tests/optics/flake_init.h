/* Builds a micro-flake distribution in a test, failing the test with the
 * library's message when it is refused. */
#ifndef SUBSURF_TESTS_FLAKE_INIT_H
#define SUBSURF_TESTS_FLAKE_INIT_H

#include "subsurf/microflake.h"

#include <criterion/criterion.h>

static inline void init_flakes(ss_microflake *mf, ss_flake_type type, double p, ss_vec3 axis,
                               ss_flake_albedo albedo) {
  ss_error err = {0};
  cr_assert_eq(ss_microflake_init(mf, type, p, axis, albedo, &err), SS_OK, "%s p %g: %s",
               ss_flake_type_name(type), p, err.message);
}

#endif
