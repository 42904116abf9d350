/* Estimators with standard errors: Welford's running mean/variance for
 * independent samples, and batch tallies for histograms filled by Monte Carlo
 * paths (each batch of paths is one independent sample of the bin means). */
#ifndef SUBSURF_STATS_H
#define SUBSURF_STATS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
  uint64_t n;
  double mean;
  double m2; /* sum of squared deviations from the mean */
} ss_running_stats;

void ss_running_stats_init(ss_running_stats *s);
/* Welford 1962, with Knuth's update for the second moment. */
void ss_running_stats_add(ss_running_stats *s, double x);
/* Chan et al. 1979: merges b into a as if all of b's samples were added. */
void ss_running_stats_merge(ss_running_stats *a, const ss_running_stats *b);
double ss_running_stats_variance(const ss_running_stats *s); /* sample variance */
double ss_running_stats_stderr(const ss_running_stats *s);   /* of the mean */

/* Tallies of `nbins` quantities accumulated over paths grouped in batches.
 * For batch j with n_j paths and per-bin sum S_j, the tally keeps sum S_j and
 * sum S_j^2 / n_j; the mean per path is sum S / N and its squared standard
 * error is (sum S_j^2/n_j - N m^2) / ((B - 1) N), the batch-means estimate,
 * which stays valid when one path adds to a bin many times. */
typedef struct {
  size_t nbins;
  uint64_t paths;
  uint64_t batches;
  double *sum;
  double *sum_sq_per_batch;
} ss_batch_tally;

int ss_batch_tally_init(ss_batch_tally *t, size_t nbins);
void ss_batch_tally_free(ss_batch_tally *t);
/* Adds one finished batch of `paths` paths whose per-bin sums are `batch_sum`. */
void ss_batch_tally_add_batch(ss_batch_tally *t, const double *batch_sum, uint64_t paths);
double ss_batch_tally_mean(const ss_batch_tally *t, size_t bin);
double ss_batch_tally_stderr(const ss_batch_tally *t, size_t bin);

#endif
