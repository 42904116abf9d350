/* Classical dipole diffusion BSSRDF (Jensen, Marschner, Levoy & Hanrahan
 * 2001, seed 001, sec. 2.1-2.4).
 *
 * | option       | meaning                                                  |
 * |--------------|----------------------------------------------------------|
 * | sigma_s, g   | reduced scattering sigma_s' = (1 - g) sigma_s            |
 * | sigma_a      | absorption                                               |
 * | eta          | n_inside / n_outside: Fresnel factors and A              |
 * | min_distance | evaluate R_d at max(r, 1/sigma_t') (sec. 4)              |
 *
 * S_d = (1/pi) Ft(eta, w_i) R_d(|x_o - x_i|) Ft(eta, w_o); the entry point is
 * sampled from a mixture of area exponentials with rates sigma_tr (the
 * profile's tail) and sigma_t' (its core). */
#include "bssrdf/bssrdf_util.h"
#include "bssrdf/handle.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  double eta, t_out;
  int min_distance;
  double alpha_prime[SS_BSSRDF_CHANNELS], sigma_tr[SS_BSSRDF_CHANNELS];
  double z_r[SS_BSSRDF_CHANNELS], z_v[SS_BSSRDF_CHANNELS], r_min[SS_BSSRDF_CHANNELS];
  double total[SS_BSSRDF_CHANNELS]; /* 2 pi int R_d r dr as evaluated */
  double rd[SS_BSSRDF_CHANNELS];    /* the paper's closed form */
  double small, large;
  ss_radial_mix mix[SS_BSSRDF_CHANNELS];
} dipole;

/* Jensen et al. 2001, eq. 4 (R_d for a dipole at z_r and -z_v). */
static double dipole_rd(const dipole *d, int c, double r) {
  if (r < d->r_min[c]) {
    r = d->r_min[c];
  }
  double r2 = r * r;
  return d->alpha_prime[c] / (4.0 * SS_PI) *
         (ss_dipole_source(d->z_r[c], r2, d->sigma_tr[c]) +
          ss_dipole_source(d->z_v[c], r2, d->sigma_tr[c]));
}

static void ring_rd(void *ctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = ctx;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = 2.0 * SS_PI * r * dipole_rd(d, c, r);
  }
}

static ss_status dipole_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  dipole *d = calloc(1, sizeof *d);
  if (!d) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "dipole: out of memory");
  }
  d->eta = p->eta;
  d->t_out = ss_fresnel_transmission_out(p->eta);
  d->min_distance = p->min_distance;
  /* Jensen et al. 2001, sec. 2.1: A = (1 + Fdr)/(1 - Fdr). */
  double A = ss_fresnel_A(p->eta);
  d->small = INFINITY;
  d->large = 0.0;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k = ss_bssrdf_coeffs_make(p->sigma_s[c], p->sigma_a[c], p->g[c]);
    d->alpha_prime[c] = k.alpha_prime;
    d->sigma_tr[c] = k.sigma_tr;
    d->z_r[c] = 1.0 / k.sigma_t_prime;
    d->z_v[c] = d->z_r[c] * (1.0 + 4.0 * A / 3.0);
    d->r_min[c] = p->min_distance ? 1.0 / k.sigma_t_prime : 0.0;
    /* Jensen et al. 2001, sec. 2.4: total diffuse reflectance. */
    double s = sqrt(3.0 * (1.0 - k.alpha_prime));
    d->rd[c] = 0.5 * k.alpha_prime * (1.0 + exp(-4.0 / 3.0 * A * s)) * exp(-s);
    double rates[2] = {fmax(k.sigma_tr, 1e-3 * k.sigma_t_prime), k.sigma_t_prime};
    double weights[2] = {0.75, 0.25};
    ss_radial_mix_init(&d->mix[c], 2, rates, weights);
    d->small = fmin(d->small, 0.05 * d->z_r[c]);
    d->large = fmax(d->large, ss_radial_mix_max_radius(&d->mix[c]));
  }
  if (p->min_distance) {
    ss_vec_integrate_halfline(ring_rd, d, d->small, d->large, d->total);
  } else {
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      d->total[c] = d->rd[c];
    }
  }
  *state = d;
  return SS_OK;
}

static void dipole_destroy(void *state) { free(state); }

static void dipole_eval(const void *state, const ss_bssrdf_query *q,
                        double s[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), d->eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), d->eta) * SS_INV_PI;
  double r = ss_vec3_length(ss_vec3_sub(q->x_o, q->x_i));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s[c] = f * dipole_rd(d, c, r);
  }
}

static int dipole_sample(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                         double u1, double u2, ss_bssrdf_entry *e) {
  const dipole *d = state;
  ss_radial_mix_sample(&d->mix[channel], u1, u2, e);
  return 1;
}

static double dipole_pdf(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                         double r, double phi) {
  const dipole *d = state;
  return ss_radial_mix_pdf(&d->mix[channel], r);
}

static double dipole_max_radius(const void *state, int channel) {
  const dipole *d = state;
  return ss_radial_mix_max_radius(&d->mix[channel]);
}

/* int M dA = Ft(cos_i) (2 pi int R_d r dr) (1/pi) int Ft cos dw_o. */
static void dipole_total(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  double f = ss_ft_outside(cos_i, d->eta) * d->t_out;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * d->total[c];
  }
}

static void dipole_rd_closed(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = d->rd[c];
  }
}

static void dipole_profile(const void *state, int channel, double r, ss_bssrdf_profile_value *out) {
  const dipole *d = state;
  out->ms = out->value = dipole_rd(d, channel, r);
}

static void dipole_exitance(const void *state, double cos_i, double x, double y,
                            double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  double f = ss_ft_outside(cos_i, d->eta) * d->t_out, r = hypot(x, y);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * dipole_rd(d, c, r);
  }
}

typedef struct {
  const dipole *d;
  double x;
} line_ctx;

static void line_rd(void *ctx, double y, double out[SS_BSSRDF_CHANNELS]) {
  const line_ctx *l = ctx;
  double r = hypot(l->x, y);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = 2.0 * dipole_rd(l->d, c, r);
  }
}

static void dipole_radiance_line(const void *state, double cos_i, double x, ss_vec3 w_o,
                                 double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  line_ctx l = {d, x};
  ss_vec_integrate_halfline(line_rd, &l, d->small, d->large, out);
  double f = ss_ft_outside(cos_i, d->eta) * ss_ft_outside(w_o.z, d->eta) * SS_INV_PI;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] *= f;
  }
}

static void dipole_brdf(const void *state, ss_vec3 w_i, ss_vec3 w_o,
                        double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  double f = ss_ft_outside(w_i.z, d->eta) * ss_ft_outside(w_o.z, d->eta) * SS_INV_PI;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * d->total[c];
  }
}

const ss_bssrdf_ops ss_bssrdf_model_dipole = {
    .name = "dipole",
    .summary = "classical dipole with Fresnel factors (Jensen et al. 2001)",
    .flags = SS_BSSRDF_RADIAL,
    .create = dipole_create,
    .destroy = dipole_destroy,
    .eval = dipole_eval,
    .sample_entry = dipole_sample,
    .pdf_entry = dipole_pdf,
    .max_radius = dipole_max_radius,
    .total_reflectance = dipole_total,
    .rd = dipole_rd_closed,
    .profile = dipole_profile,
    .exitance = dipole_exitance,
    .radiance_line = dipole_radiance_line,
    .brdf = dipole_brdf,
};
