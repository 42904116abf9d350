/* The adaptive integral over the path length s of the forward scattering
 * dipole (fwddip_model.h): Gauss-Kronrod (7, 15) in u = log s. */
#include "bssrdf/fwddip_model.h"

#include <math.h>
#include <stdlib.h>

#define PS_LO 1e-6
#define PS_HI 1e4
#define PANELS_PER_DECADE 2
#define BALLISTIC_STEPS 10 /* breakpoints d (1 +- 4^-k), k = 1..10 */
#define MAX_PANELS 1000
#define MAX_BREAKS                                                                                 \
  (10 * PANELS_PER_DECADE + 2 + SS_FWDDIP_MAX_BALLISTIC * (2 * BALLISTIC_STEPS + 1))

/* Kronrod nodes on [0, 1) of the 15-point rule and their weights; the odd
 * entries (1, 3, 5, 7) are the 7-point Gauss nodes (Piessens et al. 1983,
 * QUADPACK's qk15). */
static const double xgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
static const double wgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double wg[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

typedef struct {
  double a, b, value, error;
} panel;

typedef struct {
  const ss_fwddip_medium *m;
  ss_fwddip_s_fn f;
  void *ctx;
} integrand;

/* f(e^u) e^u: the integrand in u = log s. */
static double at(const integrand *g, double u) {
  double s = exp(u);
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(g->m->p * s, &k);
  return g->f(g->ctx, &k, s) * s;
}

static panel kronrod(const integrand *g, double a, double b) {
  double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double fc = at(g, c), k15 = wgk[7] * fc, g7 = wg[3] * fc;
  for (int j = 0; j < 7; ++j) {
    double f = at(g, c - h * xgk[j]) + at(g, c + h * xgk[j]);
    k15 += wgk[j] * f;
    if (j & 1) {
      g7 += wg[j / 2] * f;
    }
  }
  panel p = {a, b, k15 * h, fabs((k15 - g7) * h)};
  return p;
}

static int compare_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The starting breakpoints in u: the decades of p s and the ballistic lengths. */
static int breakpoints(const ss_fwddip_medium *m, const double *ballistic, int n_ballistic,
                       double *u) {
  double lo = log(PS_LO / m->p), hi = log(PS_HI / m->p);
  int n = 0, panels = 10 * PANELS_PER_DECADE;
  for (int i = 0; i <= panels; ++i) {
    u[n++] = lo + (hi - lo) * i / panels;
  }
  for (int b = 0; b < n_ballistic && b < SS_FWDDIP_MAX_BALLISTIC; ++b) {
    double d = ballistic[b];
    if (!(d * m->p > 2.0 * PS_LO && d * m->p < 0.5 * PS_HI)) {
      continue;
    }
    u[n++] = log(d);
    for (int k = 1; k <= BALLISTIC_STEPS; ++k) {
      double step = pow(4.0, -k);
      u[n++] = log(d) + log1p(step);
      u[n++] = log(d) + log1p(-step);
    }
  }
  qsort(u, (size_t)n, sizeof u[0], compare_double);
  return n;
}

double ss_fwddip_integrate_s(const ss_fwddip_medium *m, ss_fwddip_s_fn f, void *ctx,
                             const double *ballistic, int n_ballistic, double rtol) {
  static _Thread_local panel panels[MAX_PANELS];
  double u[MAX_BREAKS];
  integrand g = {m, f, ctx};
  int nb = breakpoints(m, ballistic, n_ballistic, u), n = 0;
  double total = 0.0, error = 0.0;
  for (int i = 0; i + 1 < nb; ++i) {
    if (u[i + 1] > u[i]) {
      panels[n] = kronrod(&g, u[i], u[i + 1]);
      total += panels[n].value;
      error += panels[n].error;
      ++n;
    }
  }
  while (error > rtol * fabs(total) && n + 1 < MAX_PANELS) {
    int worst = 0;
    for (int i = 1; i < n; ++i) {
      if (panels[i].error > panels[worst].error) {
        worst = i;
      }
    }
    panel old = panels[worst];
    double mid = 0.5 * (old.a + old.b);
    panels[worst] = kronrod(&g, old.a, mid);
    panels[n] = kronrod(&g, mid, old.b);
    total += panels[worst].value + panels[n].value - old.value;
    error += panels[worst].error + panels[n].error - old.error;
    ++n;
  }
  return total;
}
