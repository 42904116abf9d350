/* The robust per-pixel estimator of Frederickx2017 sec. 7.3
 * (after Wilcox2005): of K independent estimates, drop the
 * floor(trim K) lowest and the floor(trim K) highest and average the rest.
 * It trades a small bias (none for a symmetric distribution) for a large
 * reduction of the variance that rare outliers cause; trim = 0 is the mean. */
#ifndef SUBSURF_TRIMMED_MEAN_H
#define SUBSURF_TRIMMED_MEAN_H

#include "subsurf/status.h"

#include <stddef.h>

/* How many values of n each end drops: floor(trim n). */
size_t ss_trimmed_count(size_t n, double trim);

/* The trimmed mean of values[0..n) (reordered in place). trim must lie in
 * [0, 0.5) and leave at least one value; n >= 1. Returns NaN otherwise. */
double ss_trimmed_mean(double *values, size_t n, double trim);

/* Per pixel (or any element) over K passes: out[i] = trimmed mean of
 * passes[0][i] .. passes[K-1][i], for i < count (RGB images are count =
 * 3 width height floats). Errors name the argument: trim outside [0, 0.5)
 * or dropping every pass, K = 0. */
ss_status ss_trimmed_mean_passes(const float *const *passes, size_t k, size_t count, double trim,
                                 float *out, ss_error *err);

#endif
