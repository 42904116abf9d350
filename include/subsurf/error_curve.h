/* An estimator's error against its cost, from a sequence of passes:
 * a least-squares line through (log t, log e), the cost at which that line
 * reaches a given error, and the error the passes converge to (the bias
 * floor of e = c + k / n, n the samples per pixel: an unbiased Monte Carlo
 * estimator's MSE falls as 1/n, a biased one's to its squared bias). */
#ifndef SUBSURF_ERROR_CURVE_H
#define SUBSURF_ERROR_CURVE_H

/* Fits log e = a + b log t over the points with t > 0 and e > 0. Returns
 * the number of points used; a and b are set when it is >= 2 with distinct t.
 */
int ss_loglog_fit(const double *t, const double *e, int n, double *a, double *b);

/* The t at which log e = a + b log t reaches `e`: exp((log e - a) / b);
 * INFINITY when b >= 0 (the error does not fall) or e <= 0. */
double ss_loglog_time_to(double a, double b, double e);

/* c of the least-squares fit e = c + k / n over the points, clamped to
 * [0, the smallest e]; with fewer than two distinct n, the last e. */
double ss_error_floor(const double *n, const double *e, int count);

/* The time at which the error reaches `target`. When a pass reached it,
 * the passes say when (log-log between the bracketing passes; before the
 * first pass, e ~ 1/t). Otherwise the fit e = c + k / t (c clamped to >= 0)
 * extrapolates: k / (target - c); INFINITY when target <= c (the
 * estimator's bias floor lies above it), when k <= 0, or with fewer than two
 * distinct t. A power law through the same points would reach any target,
 * however far below the floor. */
double ss_error_time_to(const double *t, const double *e, int count, double target);

#endif
