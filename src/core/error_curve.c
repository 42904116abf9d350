/* Error curves (error_curve.h). */
#include "subsurf/error_curve.h"

#include <math.h>

/* Least squares y = a + b x; 0 when the x do not vary. */
static int line_fit(const double *x, const double *y, int n, double *a, double *b) {
  double mx = 0.0, my = 0.0;
  for (int i = 0; i < n; ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxx = 0.0, sxy = 0.0;
  for (int i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (!(sxx > 0.0)) {
    return 0;
  }
  *b = sxy / sxx;
  *a = my - *b * mx;
  return 1;
}

int ss_loglog_fit(const double *t, const double *e, int n, double *a, double *b) {
  double x[64], y[64];
  int m = 0;
  for (int i = 0; i < n && m < 64; ++i) {
    if (t[i] > 0.0 && e[i] > 0.0 && isfinite(t[i]) && isfinite(e[i])) {
      x[m] = log(t[i]);
      y[m++] = log(e[i]);
    }
  }
  return m >= 2 && line_fit(x, y, m, a, b) ? m : 0;
}

double ss_loglog_time_to(double a, double b, double e) {
  if (!(b < 0.0) || !(e > 0.0)) {
    return INFINITY;
  }
  return exp((log(e) - a) / b);
}

double ss_error_floor(const double *n, const double *e, int count) {
  double x[64], c = 0.0, k = 0.0;
  int m = count < 64 ? count : 64;
  for (int i = 0; i < m; ++i) {
    x[i] = 1.0 / n[i];
  }
  if (m < 2 || !line_fit(x, e, m, &c, &k)) {
    return m > 0 ? e[m - 1] : NAN;
  }
  /* Heavy-tailed passes (a firefly in a late pass) can tilt the line so
   * that c exceeds every error observed; the floor is never above those. */
  double lowest = e[0];
  for (int i = 1; i < m; ++i) {
    lowest = fmin(lowest, e[i]);
  }
  return c > 0.0 ? fmin(c, lowest) : 0.0;
}

/* The time at which the passes themselves first reached `target`,
 * interpolated log-log between the bracketing passes (before the first
 * pass: the 1/t law); -1 when no pass reached it. */
static double observed_time_to(const double *t, const double *e, int count, double target) {
  for (int i = 0; i < count; ++i) {
    if (!(t[i] > 0.0 && e[i] > 0.0 && e[i] <= target)) {
      continue;
    }
    if (i == 0 || !(t[i - 1] > 0.0 && e[i - 1] > target)) {
      return t[i] * e[i] / target;
    }
    double f = log(target / e[i - 1]) / log(e[i] / e[i - 1]);
    return t[i - 1] * exp(f * log(t[i] / t[i - 1]));
  }
  return -1.0;
}

double ss_error_time_to(const double *t, const double *e, int count, double target) {
  double seen = observed_time_to(t, e, count, target);
  if (seen >= 0.0) {
    return seen;
  }
  double x[64], y[64], c = 0.0, k = 0.0;
  int m = 0;
  for (int i = 0; i < count && m < 64; ++i) {
    if (t[i] > 0.0 && isfinite(t[i]) && isfinite(e[i])) {
      x[m] = 1.0 / t[i];
      y[m++] = e[i];
    }
  }
  if (m < 2 || !line_fit(x, y, m, &c, &k) || !(k > 0.0)) {
    return INFINITY;
  }
  c = c > 0.0 ? c : 0.0;
  return target > c ? k / (target - c) : INFINITY;
}
