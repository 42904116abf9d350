#include "subsurf/sampling.h"

#include <stdlib.h>
#include <string.h>

ss_vec3 ss_sample_uniform_sphere(double u1, double u2) {
  return ss_spherical_direction(1.0 - 2.0 * u1, 2.0 * SS_PI * u2);
}
double ss_pdf_uniform_sphere(void) { return SS_INV_4PI; }

ss_vec3 ss_sample_uniform_hemisphere(double u1, double u2) {
  return ss_spherical_direction(u1, 2.0 * SS_PI * u2);
}
double ss_pdf_uniform_hemisphere(void) { return 0.5 * SS_INV_PI; }

/* Malley's method: project a uniform disk sample up to the hemisphere. */
ss_vec3 ss_sample_cosine_hemisphere(double u1, double u2) {
  double x, y;
  ss_sample_concentric_disk(u1, u2, &x, &y);
  return ss_vec3_make(x, y, sqrt(fmax(0.0, 1.0 - x * x - y * y)));
}
double ss_pdf_cosine_hemisphere(double cos_theta) {
  return cos_theta > 0.0 ? cos_theta * SS_INV_PI : 0.0;
}

ss_vec3 ss_sample_uniform_cone(double u1, double u2, double cos_max) {
  double cos_theta = 1.0 - u1 * (1.0 - cos_max);
  return ss_spherical_direction(cos_theta, 2.0 * SS_PI * u2);
}
double ss_pdf_uniform_cone(double cos_max) { return 1.0 / (2.0 * SS_PI * (1.0 - cos_max)); }

void ss_sample_concentric_disk(double u1, double u2, double *x, double *y) {
  double a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
  if (a == 0.0 && b == 0.0) {
    *x = *y = 0.0;
    return;
  }
  double r, theta;
  if (fabs(a) > fabs(b)) {
    r = a;
    theta = 0.25 * SS_PI * (b / a);
  } else {
    r = b;
    theta = 0.5 * SS_PI - 0.25 * SS_PI * (a / b);
  }
  *x = r * cos(theta);
  *y = r * sin(theta);
}

void ss_sample_uniform_triangle(double u1, double u2, double *b0, double *b1) {
  if (u2 > u1) {
    *b0 = 0.5 * u1;
    *b1 = u2 - *b0;
  } else {
    *b1 = 0.5 * u2;
    *b0 = u1 - *b1;
  }
}

int ss_distribution1d_init(ss_distribution1d *d, const double *func, size_t n) {
  memset(d, 0, sizeof *d);
  d->func = malloc(n * sizeof *d->func);
  d->cdf = malloc((n + 1) * sizeof *d->cdf);
  if (!d->func || !d->cdf || n == 0) {
    ss_distribution1d_free(d);
    return -1;
  }
  d->n = n;
  memcpy(d->func, func, n * sizeof *func);
  d->cdf[0] = 0.0;
  for (size_t i = 0; i < n; ++i) {
    d->cdf[i + 1] = d->cdf[i] + func[i] / (double)n;
  }
  d->integral = d->cdf[n];
  if (!(d->integral > 0.0)) {
    ss_distribution1d_free(d);
    return -1;
  }
  for (size_t i = 1; i <= n; ++i) {
    d->cdf[i] /= d->integral;
  }
  return 0;
}

void ss_distribution1d_free(ss_distribution1d *d) {
  free(d->func);
  free(d->cdf);
  memset(d, 0, sizeof *d);
}

/* Largest i with cdf[i] <= u, by bisection. */
static size_t find_interval(const double *cdf, size_t n, double u) {
  size_t lo = 0, hi = n;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (cdf[mid] <= u) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

size_t ss_distribution1d_sample_discrete(const ss_distribution1d *d, double u, double *prob) {
  size_t i = find_interval(d->cdf, d->n, u);
  if (prob) {
    *prob = d->func[i] / (d->integral * (double)d->n);
  }
  return i;
}

double ss_distribution1d_sample_continuous(const ss_distribution1d *d, double u, double *pdf) {
  size_t i = find_interval(d->cdf, d->n, u);
  double du = u - d->cdf[i];
  double width = d->cdf[i + 1] - d->cdf[i];
  if (width > 0.0) {
    du /= width;
  }
  if (pdf) {
    *pdf = d->func[i] / d->integral;
  }
  return ((double)i + du) / (double)d->n;
}
