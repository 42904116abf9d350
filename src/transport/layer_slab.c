/* A homogeneous layer by doubling (layer_ops.h): the phase function's
 * azimuthal Fourier modes between the nodes, the thin starting layer of
 * exact single scattering (Blinn1982) and the doubling to the full depth
 * (PharrHanrahan2000 sec. 3.4). */
#include "transport/layer_ops.h"

#include "subsurf/sampling.h"

#include <fftw3.h>
#include <math.h>
#include <stdlib.h>

/* The phase function sampled at K + 1 azimuths in [0, pi] (it is even in
 * dphi) and its cosine coefficients by a type-I DCT: the trapezoid rule
 * int_0^2pi p cos(m dphi) dphi = (pi / K) Y_m, exact for the modes far below
 * K. */
static void modes_of(const ss_phase *phase, double a, double b, int K, double *in, double *out,
                     fftw_plan plan) {
  for (int q = 0; q <= K; ++q) {
    double c = a + b * cos(SS_PI * q / K);
    in[q] = ss_phase_eval(phase, c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c));
  }
  fftw_execute_r2r(plan, in, out);
}

static int dct_size(int modes) {
  int K = 64;
  while (K < 4 * modes) {
    K *= 2;
  }
  return K;
}

double *layer_phase_modes(const ss_phase *phase, const layer_nodes *nd, int modes) {
  int n = nd->n, K = dct_size(modes);
  double *coeff = calloc(2 * (size_t)n * (size_t)n * (size_t)modes, sizeof *coeff);
  double *in = fftw_malloc((size_t)(K + 1) * sizeof *in);
  double *out = fftw_malloc((size_t)(K + 1) * sizeof *out);
  fftw_plan plan = in && out ? fftw_plan_r2r_1d(K + 1, in, out, FFTW_REDFT00, FFTW_ESTIMATE) : NULL;
  if (!coeff || !plan) {
    free(coeff);
    fftw_free(in);
    fftw_free(out);
    if (plan) {
      fftw_destroy_plan(plan);
    }
    return NULL;
  }
  const double *mu = nd->mu[LAYER_MED];
  for (int k = 0; k < n; ++k) {
    if (!nd->present[LAYER_MED][k]) {
      continue;
    }
    for (int j = 0; j < n; ++j) {
      if (!nd->present[LAYER_MED][j]) {
        continue;
      }
      double b = sqrt(fmax(0.0, 1.0 - mu[k] * mu[k])) * sqrt(fmax(0.0, 1.0 - mu[j] * mu[j]));
      for (int sign = 0; sign < 2; ++sign) {
        modes_of(phase, (sign ? -1.0 : 1.0) * mu[k] * mu[j], b, K, in, out, plan);
        double *c = coeff + (((size_t)sign * n + k) * n + j) * (size_t)modes;
        for (int m = 0; m < modes; ++m) {
          c[m] = SS_PI / K * out[m];
        }
      }
    }
  }
  fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  return coeff;
}

int layer_phase_mode_count(const ss_phase *phase, double accuracy) {
  if (phase->type == SS_PHASE_ISOTROPIC || (phase->type == SS_PHASE_HG && phase->g == 0.0)) {
    return 1;
  }
  /* At grazing directions (mu = mu' = 0) cos Theta = cos dphi: the phase
   * function's whole angular range lies along the azimuth, where its modes
   * decay slowest. */
  enum { K = 8192 };
  double *in = fftw_malloc((K + 1) * sizeof *in), *out = fftw_malloc((K + 1) * sizeof *out);
  int count = SS_LAYER_MAX_MODES;
  if (in && out) {
    fftw_plan plan = fftw_plan_r2r_1d(K + 1, in, out, FFTW_REDFT00, FFTW_ESTIMATE);
    if (plan) {
      modes_of(phase, 0.0, 1.0, K, in, out, plan);
      int last = 0;
      for (int m = 1; m < K / 2; ++m) {
        if (fabs(out[m]) > accuracy * fabs(out[0])) {
          last = m;
        }
      }
      count = last + 1 < SS_LAYER_MAX_MODES ? last + 1 : SS_LAYER_MAX_MODES;
      fftw_destroy_plan(plan);
    }
  }
  fftw_free(in);
  fftw_free(out);
  return count;
}

/* Blinn1982 (single scattering in a layer of optical depth tau), as
 * f_r = albedo p / (mu + mu0) [1 - exp(-tau (1/mu + 1/mu0))] and
 * f_t = albedo p [exp(-tau/mu) - exp(-tau/mu0)] / (mu - mu0), written with
 * expm1 so that neither cancels for thin layers or mu ~ mu0. */
double layer_blinn_reflect(double tau, double mu, double mu0) {
  return -expm1(-tau * (mu + mu0) / (mu * mu0)) / (mu + mu0);
}

double layer_blinn_transmit(double tau, double mu, double mu0) {
  double x = tau * (mu - mu0) / (mu * mu0);
  double ratio = fabs(x) < 1e-12 ? 1.0 + 0.5 * x : expm1(x) / x;
  return exp(-tau / mu0) * tau / (mu * mu0) * ratio;
}

static void thin_layer(layer_slab *s, const layer_nodes *nd, const ss_layer_medium *medium,
                       const double *coeff, int modes, int m, double tau) {
  int n = nd->n;
  const double *mu = nd->mu[LAYER_MED];
  layer_op_zero(&s->r, n);
  layer_op_zero(&s->t, n);
  for (int i = 0; i < n; ++i) {
    if (!nd->present[LAYER_MED][i]) {
      continue;
    }
    s->t.d[i] = exp(-tau / mu[i]);
    for (int j = 0; j < n; ++j) {
      if (!nd->present[LAYER_MED][j]) {
        continue;
      }
      double same = coeff[(((size_t)0 * n + i) * n + j) * (size_t)modes + (size_t)m];
      double opposite = coeff[(((size_t)1 * n + i) * n + j) * (size_t)modes + (size_t)m];
      double scale = medium->albedo / (nd->eta * nd->eta);
      s->r.s[(size_t)i * n + j] = scale * opposite * layer_blinn_reflect(tau, mu[i], mu[j]);
      s->t.s[(size_t)i * n + j] = scale * same * layer_blinn_transmit(tau, mu[i], mu[j]);
    }
  }
  layer_op_copy(&s->rs, &s->r, n);
  layer_op_copy(&s->ts, &s->t, n);
}

int layer_slab_build(layer_slab *s, const layer_nodes *nd, const ss_layer_medium *medium,
                     const double *coeff, int modes, int m, double thin_tau, layer_work *ws,
                     const volatile sig_atomic_t *cancel) {
  int doublings = 0;
  double tau = medium->tau;
  while (tau > thin_tau && doublings < 200) {
    tau *= 0.5;
    ++doublings;
  }
  layer_slab spare;
  if (!layer_slab_alloc(&spare, nd->n)) {
    return -1;
  }
  layer_slab *cur = s, *next = &spare;
  thin_layer(cur, nd, medium, coeff, modes, m, tau);
  for (int k = 0; k < doublings; ++k) {
    int failed = cancel && *cancel ? -3 : 0;
    if (!failed && !layer_add(next, cur, cur, nd->w[LAYER_MED], 1, ws)) {
      failed = -2;
    }
    if (failed) {
      layer_slab_free(&spare);
      return failed;
    }
    layer_slab *t = cur;
    cur = next;
    next = t;
  }
  if (cur != s) {
    layer_op_copy(&s->r, &cur->r, nd->n);
    layer_op_copy(&s->t, &cur->t, nd->n);
    layer_op_copy(&s->rs, &cur->rs, nd->n);
    layer_op_copy(&s->ts, &cur->ts, nd->n);
  }
  layer_slab_free(&spare);
  /* Doubling squares the beam's attenuation k times, which multiplies the
   * rounding of the thin layer's by 2^k: its exact value instead. */
  for (int i = 0; i < nd->n; ++i) {
    if (nd->present[LAYER_MED][i]) {
      s->t.d[i] = s->ts.d[i] = exp(-medium->tau / nd->mu[LAYER_MED][i]);
    }
  }
  return doublings;
}
