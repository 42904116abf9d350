/* Every entry point that takes a thread count refuses what libgomp cannot
 * give (tens of thousands of threads exit the process) with the limit named,
 * and a team is never larger than the limit. */
#include "subsurf/threads.h"

#include <criterion/criterion.h>
#include <limits.h>
#include <omp.h>
#include <string.h>

Test(threads, counts_outside_zero_to_the_limit_are_refused_with_the_range_named) {
  ss_error err;
  cr_expect_eq(ss_threads_check(0, &err), SS_OK);
  cr_expect_eq(ss_threads_check(SS_THREADS_MAX, &err), SS_OK);
  const int bad[] = {-1, SS_THREADS_MAX + 1, 100000, INT_MAX, INT_MIN};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    cr_expect_eq(ss_threads_check(bad[i], &err), SS_ERR_INVALID_ARGUMENT, "%d", bad[i]);
    cr_expect(strstr(err.message, "threads must be in [0, 4096]"), "%s", err.message);
  }
}

Test(threads, a_team_is_never_larger_than_the_limit_even_when_openmp_asks_for_more) {
  cr_expect_eq(ss_threads_team(3), 3);
  cr_expect_eq(ss_threads_team(1 << 20), SS_THREADS_MAX);
  omp_set_num_threads(100000);
  cr_expect_eq(ss_threads_team(0), SS_THREADS_MAX);
  omp_set_num_threads(2);
  cr_expect_eq(ss_threads_team(0), 2);
}
