/* Piecewise-constant 2D distributions: a marginal over rows and one
 * conditional per row (pbrt-v3 sec. 13.6.7), for sampling images. */
#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_distribution2d_free(ss_distribution2d *d) {
  if (d->rows) {
    for (size_t v = 0; v < d->nv; ++v) {
      ss_distribution1d_free(&d->rows[v]);
    }
  }
  free(d->rows);
  ss_distribution1d_free(&d->marginal);
  memset(d, 0, sizeof *d);
}

int ss_distribution2d_init(ss_distribution2d *d, const double *func, size_t nu, size_t nv) {
  memset(d, 0, sizeof *d);
  if (nu == 0 || nv == 0) {
    return -1;
  }
  d->rows = calloc(nv, sizeof *d->rows);
  double *integrals = malloc(nv * sizeof *integrals), *ones = malloc(nu * sizeof *ones);
  int rc = d->rows && integrals && ones ? 0 : -1;
  d->nu = nu;
  d->nv = nv;
  for (size_t i = 0; i < nu && ones; ++i) {
    ones[i] = 1.0;
  }
  for (size_t v = 0; v < nv && rc == 0; ++v) {
    const double *row = func + v * nu;
    double sum = 0.0;
    for (size_t u = 0; u < nu; ++u) {
      sum += row[u];
    }
    integrals[v] = sum / (double)nu;
    /* A black row is never picked by the marginal; its uniform conditional
     * only keeps every row's sampling data well formed. */
    rc = ss_distribution1d_init(&d->rows[v], sum > 0.0 ? row : ones, nu);
  }
  if (rc == 0) {
    rc = ss_distribution1d_init(&d->marginal, integrals, nv);
  }
  free(integrals);
  free(ones);
  if (rc != 0) {
    ss_distribution2d_free(d);
  }
  return rc;
}

void ss_distribution2d_sample(const ss_distribution2d *d, double u1, double u2, double *u,
                              double *v, double *pdf) {
  double pdf_v, pdf_u;
  *v = ss_distribution1d_sample_continuous(&d->marginal, u2, &pdf_v);
  size_t row = (size_t)fmin(*v * (double)d->nv, (double)(d->nv - 1));
  *u = ss_distribution1d_sample_continuous(&d->rows[row], u1, &pdf_u);
  *pdf = pdf_v * pdf_u;
}

/* The cell of coordinate x in [0, 1] among n. */
static size_t cell(double x, size_t n) {
  double c = floor(x * (double)n);
  return c <= 0.0 ? 0 : c >= (double)(n - 1) ? n - 1 : (size_t)c;
}

double ss_distribution2d_pdf(const ss_distribution2d *d, double u, double v) {
  size_t row = cell(v, d->nv);
  double m = d->marginal.func[row];
  if (!(m > 0.0)) {
    return 0.0;
  }
  /* func(u, v) / integral, the integral of the whole being the marginal's. */
  return d->rows[row].func[cell(u, d->nu)] / d->marginal.integral;
}
