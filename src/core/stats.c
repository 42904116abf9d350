#include "subsurf/stats.h"

#include <math.h>
#include <stdlib.h>

void ss_running_stats_init(ss_running_stats *s) {
  s->n = 0;
  s->mean = 0.0;
  s->m2 = 0.0;
}

void ss_running_stats_add(ss_running_stats *s, double x) {
  s->n += 1;
  double delta = x - s->mean;
  s->mean += delta / (double)s->n;
  s->m2 += delta * (x - s->mean);
}

void ss_running_stats_merge(ss_running_stats *a, const ss_running_stats *b) {
  if (b->n == 0) {
    return;
  }
  uint64_t n = a->n + b->n;
  double delta = b->mean - a->mean;
  a->mean += delta * (double)b->n / (double)n;
  a->m2 += b->m2 + delta * delta * (double)a->n * (double)b->n / (double)n;
  a->n = n;
}

double ss_running_stats_variance(const ss_running_stats *s) {
  return s->n > 1 ? s->m2 / (double)(s->n - 1) : 0.0;
}

double ss_running_stats_stderr(const ss_running_stats *s) {
  return s->n > 1 ? sqrt(ss_running_stats_variance(s) / (double)s->n) : 0.0;
}

int ss_batch_tally_init(ss_batch_tally *t, size_t nbins) {
  t->nbins = nbins;
  t->paths = 0;
  t->batches = 0;
  t->sum = calloc(nbins ? nbins : 1, sizeof *t->sum);
  t->sum_sq_per_batch = calloc(nbins ? nbins : 1, sizeof *t->sum_sq_per_batch);
  if (!t->sum || !t->sum_sq_per_batch) {
    ss_batch_tally_free(t);
    return -1;
  }
  return 0;
}

void ss_batch_tally_free(ss_batch_tally *t) {
  free(t->sum);
  free(t->sum_sq_per_batch);
  t->sum = t->sum_sq_per_batch = NULL;
  t->nbins = 0;
}

void ss_batch_tally_add_batch(ss_batch_tally *t, const double *batch_sum, uint64_t paths) {
  if (paths == 0) {
    return;
  }
  for (size_t i = 0; i < t->nbins; ++i) {
    t->sum[i] += batch_sum[i];
    t->sum_sq_per_batch[i] += batch_sum[i] * batch_sum[i] / (double)paths;
  }
  t->paths += paths;
  t->batches += 1;
}

double ss_batch_tally_mean(const ss_batch_tally *t, size_t bin) {
  return t->paths ? t->sum[bin] / (double)t->paths : 0.0;
}

double ss_batch_tally_stderr(const ss_batch_tally *t, size_t bin) {
  if (t->batches < 2) {
    return 0.0;
  }
  double n = (double)t->paths;
  double m = t->sum[bin] / n;
  double ss = t->sum_sq_per_batch[bin] - n * m * m;
  if (ss < 0.0) {
    ss = 0.0;
  }
  return sqrt(ss / ((double)(t->batches - 1) * n));
}
