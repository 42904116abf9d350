/* The sample trimmed mean (Frederickx2017 sec. 7.3; see trimmed_mean.h). */
#include "subsurf/trimmed_mean.h"

#include <math.h>
#include <stdlib.h>

size_t ss_trimmed_count(size_t n, double trim) { return (size_t)floor(trim * (double)n); }

static int valid(size_t n, double trim) {
  return n >= 1 && trim >= 0.0 && trim < 0.5 && 2 * ss_trimmed_count(n, trim) < n;
}

/* Insertion sort: K (passes) is small, and it is in place and allocation free. */
static void sort(double *v, size_t n) {
  for (size_t i = 1; i < n; ++i) {
    double x = v[i];
    size_t j = i;
    for (; j > 0 && v[j - 1] > x; --j) {
      v[j] = v[j - 1];
    }
    v[j] = x;
  }
}

double ss_trimmed_mean(double *values, size_t n, double trim) {
  if (!valid(n, trim)) {
    return NAN;
  }
  size_t drop = ss_trimmed_count(n, trim);
  if (drop > 0) {
    sort(values, n);
  }
  double sum = 0.0;
  for (size_t i = drop; i < n - drop; ++i) {
    sum += values[i];
  }
  return sum / (double)(n - 2 * drop);
}

ss_status ss_trimmed_mean_passes(const float *const *passes, size_t k, size_t count, double trim,
                                 float *out, ss_error *err) {
  if (k == 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "trimmed mean: no passes");
  }
  if (!(trim >= 0.0 && trim < 0.5) || !valid(k, trim)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "trimmed mean: trim must lie in [0, 0.5) and keep a pass of %zu, got %g", k,
                        trim);
  }
  double *v = malloc(k * sizeof *v);
  if (!v) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "trimmed mean: out of memory");
  }
  for (size_t i = 0; i < count; ++i) {
    for (size_t j = 0; j < k; ++j) {
      v[j] = passes[j][i];
    }
    out[i] = (float)ss_trimmed_mean(v, k, trim);
  }
  free(v);
  return SS_OK;
}
