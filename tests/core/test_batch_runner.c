#include "subsurf/batch_runner.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#define NBINS 5

/* Batches of uneven length (1 to 2000 draws) whose sums depend on the order
 * of floating-point additions: only an in-order merge is reproducible. */
static uint64_t uneven_batch(void *ctx, int64_t batch, double *sums, uint64_t *events) {
  (void)ctx;
  ss_rng rng;
  ss_rng_seed(&rng, 99, (uint64_t)batch);
  uint64_t n = 1 + ss_rng_next_u32(&rng) % 2000;
  for (uint64_t i = 0; i < n; ++i) {
    double x = ss_rng_uniform(&rng);
    sums[i % NBINS] += x * 1e-3 + x * x * 1e7;
  }
  *events += n;
  return n;
}

static void run_with(int threads, ss_batch_tally *t, uint64_t *events) {
  cr_assert_eq(ss_batch_tally_init(t, NBINS), 0);
  ss_error err;
  cr_assert_eq(ss_batch_run(t, 3000, threads, uneven_batch, NULL, NULL, events, &err), SS_OK);
}

Test(batch_runner, results_are_bit_identical_for_any_thread_count) {
  ss_batch_tally ref;
  uint64_t ev_ref;
  run_with(1, &ref, &ev_ref);
  const int threads[] = {2, 3, 8};
  for (int k = 0; k < 3; ++k) {
    ss_batch_tally t;
    uint64_t ev;
    run_with(threads[k], &t, &ev);
    cr_expect_eq(t.paths, ref.paths);
    cr_expect_eq(t.batches, 3000u);
    cr_expect_eq(ev, ev_ref);
    cr_expect_eq(memcmp(t.sum, ref.sum, NBINS * sizeof *t.sum), 0, "threads %d", threads[k]);
    cr_expect_eq(memcmp(t.sum_sq_per_batch, ref.sum_sq_per_batch, NBINS * sizeof *t.sum), 0);
    ss_batch_tally_free(&t);
  }
  ss_batch_tally_free(&ref);
}

static uint64_t skip_odd(void *ctx, int64_t batch, double *sums, uint64_t *events) {
  (void)ctx;
  (void)events;
  if (batch % 2) {
    return 0;
  }
  sums[0] = 1.0;
  return 10;
}

static void count_merges(void *ctx, uint64_t done) {
  uint64_t *last = ctx;
  cr_expect(done > *last, "progress must grow: %llu after %llu", (unsigned long long)done,
            (unsigned long long)*last);
  *last = done;
}

Test(batch_runner, skipped_batches_are_not_counted_and_progress_grows) {
  ss_batch_tally t;
  cr_assert_eq(ss_batch_tally_init(&t, 1), 0);
  uint64_t last = 0;
  ss_error err;
  cr_assert_eq(ss_batch_run(&t, 101, 4, skip_odd, count_merges, &last, NULL, &err), SS_OK);
  cr_expect_eq(t.batches, 51u);
  cr_expect_eq(t.paths, 510u);
  cr_expect_eq(last, 510u);
  cr_expect(fabs(ss_batch_tally_mean(&t, 0) - 0.1) < 1e-15);
  ss_batch_tally_free(&t);
}
