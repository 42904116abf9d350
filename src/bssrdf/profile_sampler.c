/* The entry sampler fitted to a model's radial profile (profile_sampler.h). */
#include "bssrdf/profile_sampler.h"

#include "subsurf/table_index.h"

#include <math.h>

enum { N = SS_PROFILE_SAMPLER_NODES };

/* The table's share is 1 - 1e-5 within this radius (the probe sphere). */
static double table_radius(const ss_profile_sampler *s, int c) {
  int k = 1;
  while (k < N - 1 && s->cdf[c][k] < 1.0 - 1e-5) {
    ++k;
  }
  return s->r[k];
}

void ss_profile_sampler_init(ss_profile_sampler *s, ss_profile_shape_fn shape, const void *ctx,
                             double r_lo, double r_hi, const ss_radial_mix mix[SS_BSSRDF_CHANNELS],
                             double defensive) {
  double log_q = log(r_hi / r_lo) / (N - 2);
  s->r1 = r_lo;
  s->inv_log_q = 1.0 / log_q;
  s->r[0] = 0.0;
  for (int k = 1; k < N; ++k) {
    s->r[k] = r_lo * exp((k - 1) * log_q);
  }
  double total[SS_BSSRDF_CHANNELS] = {0};
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s->mix[c] = mix[c];
    s->f[c][0] = s->cdf[c][0] = 0.0;
  }
  double r_prev = 0.0;
  for (int k = 1; k < N; ++k) {
    double r = s->r[k], v[SS_BSSRDF_CHANNELS];
    shape(ctx, r, v);
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      double f = 2.0 * SS_PI * r * v[c];
      s->f[c][k] = isfinite(f) && f > 0.0 ? f : 0.0;
      /* the trapezoid is the exact mass of the linear density between nodes */
      total[c] += 0.5 * (s->f[c][k - 1] + s->f[c][k]) * (r - r_prev);
      s->cdf[c][k] = total[c];
    }
    r_prev = r;
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    int usable = isfinite(total[c]) && total[c] > 0.0 && mix[c].n > 0;
    s->table_weight[c] = usable ? 1.0 - defensive : 0.0;
    double inv = usable ? 1.0 / total[c] : 0.0;
    for (int k = 0; k < N; ++k) {
      s->f[c][k] *= inv;
      s->cdf[c][k] *= inv;
    }
    double r_mix = ss_radial_mix_max_radius(&mix[c]);
    s->max_radius[c] = usable ? fmax(table_radius(s, c), fmin(r_mix, s->r[N - 1])) : r_mix;
  }
}

void ss_profile_sampler_init_mixture(ss_profile_sampler *s,
                                     const ss_radial_mix mix[SS_BSSRDF_CHANNELS]) {
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s->mix[c] = mix[c];
    s->table_weight[c] = 0.0;
    s->max_radius[c] = ss_radial_mix_max_radius(&mix[c]);
  }
}

void ss_profile_sampler_init_diffusion(ss_profile_sampler *s, ss_profile_shape_fn shape,
                                       const void *ctx,
                                       const ss_radial_mix mix[SS_BSSRDF_CHANNELS]) {
  double core = 0.0, tail = 0.0;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    /* the mixture's last rate is the core rate sigma_t' of the diffusion mixture */
    if (mix[c].n > 0) {
      core = fmax(core, mix[c].sigma[mix[c].n - 1]);
      tail = fmax(tail, ss_radial_mix_max_radius(&mix[c]));
    }
  }
  if (!(core > 0.0) || !(tail > 0.0)) {
    core = 1.0;
    tail = 1.0;
  }
  ss_profile_sampler_init(s, shape, ctx, 0.005 / core, 2.0 * tail, mix, 0.02);
}

/* The largest node index k with r_k <= r (0 below r1), at most N - 2. */
static int bin_of(const ss_profile_sampler *s, double r) {
  if (r < s->r1) {
    return 0;
  }
  double x = 1.0 + floor(log(r / s->r1) * s->inv_log_q);
  int k = ss_table_cell_clamped(x, N - 1);
  /* the stored nodes decide where rounding left r */
  if (k > 1 && r < s->r[k]) {
    --k;
  } else if (k < N - 2 && r >= s->r[k + 1]) {
    ++k;
  }
  return k;
}

/* The table's density per unit area at r (the linear ring density / 2 pi r). */
static double table_pdf(const ss_profile_sampler *s, int c, double r) {
  if (!(r >= 0.0) || r > s->r[N - 1]) {
    return 0.0;
  }
  int k = bin_of(s, r);
  if (k == 0) {
    return s->f[c][1] / (2.0 * SS_PI * s->r1); /* f rises linearly from 0 */
  }
  double a = s->r[k], b = s->r[k + 1], t = (r - a) / (b - a);
  t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  return ((1.0 - t) * s->f[c][k] + t * s->f[c][k + 1]) / (2.0 * SS_PI * r);
}

void ss_profile_sampler_sample(const ss_profile_sampler *s, int c, double u1, double u2,
                               ss_bssrdf_entry *e) {
  double w = s->table_weight[c];
  e->phi = 2.0 * SS_PI * u2;
  if (!(u1 < w)) {
    ss_radial_mix_sample(&s->mix[c], w > 0.0 ? (u1 - w) / (1.0 - w) : u1, u2, e);
    e->pdf = ss_profile_sampler_pdf(s, c, e->r);
    return;
  }
  double u = u1 / w;
  /* the bin: cdf[k] <= u < cdf[k + 1] */
  int lo = 0, hi = N - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (s->cdf[c][mid] <= u) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  double a = s->r[lo], h = s->r[lo + 1] - a;
  double fa = s->f[c][lo], fb = s->f[c][lo + 1];
  /* mass of the bin up to a + t h is h (fa t + (fb - fa) t^2 / 2); its root
   * in t in the cancellation-free form 2 m / (fa + sqrt(fa^2 + 2 (fb - fa) m)) */
  double m = fmax(0.0, u - s->cdf[c][lo]) / h;
  double den = fa + sqrt(fmax(0.0, fa * fa + 2.0 * (fb - fa) * m));
  double t = den > 0.0 ? 2.0 * m / den : 0.5;
  e->r = a + h * fmin(1.0, fmax(0.0, t));
  e->pdf = ss_profile_sampler_pdf(s, c, e->r);
}

double ss_profile_sampler_pdf(const ss_profile_sampler *s, int c, double r) {
  double w = s->table_weight[c];
  double p = (1.0 - w) * ss_radial_mix_pdf(&s->mix[c], r);
  return w > 0.0 ? p + w * table_pdf(s, c, r) : p;
}

int ss_profile_sampler_sample_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                    double u1, double u2, ss_bssrdf_entry *e) {
  ss_profile_sampler_sample(state, channel, u1, u2, e);
  return 1;
}

double ss_profile_sampler_pdf_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                    double r, double phi) {
  return ss_profile_sampler_pdf(state, channel, r);
}

double ss_profile_sampler_max_radius(const void *state, int channel) {
  return ((const ss_profile_sampler *)state)->max_radius[channel];
}
