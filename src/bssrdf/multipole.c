/* Multipole model of a thin slab (Donner & Jensen 2005, seed 001, sec. 3).
 *
 * | option     | meaning                                                    |
 * |------------|------------------------------------------------------------|
 * | sigma_s, g | reduced scattering sigma_s' = (1 - g) sigma_s              |
 * | sigma_a    | absorption                                                 |
 * | eta        | n_slab / n_outside, the same on both faces                 |
 * | thickness  | slab thickness d >= 1/sigma_t' (INFINITY: the dipole)      |
 *
 * Thinner slabs are rejected: the real source at depth 1/sigma_t' would lie
 * below the slab and T(r) turns negative (the model's own limit).
 * R(r) and T(r) are sums over 2n + 1 dipole pairs mirrored in both
 * extrapolated boundaries, with n chosen so that omitted pairs weigh less
 * than 1e-8 (multipole_profile.c). S = (1/pi) Ft(w_i) R(r) Ft(w_o) as for
 * the dipole; n = 0 (a half-space) is exactly the dipole. */
#include "bssrdf/bssrdf_util.h"
#include "bssrdf/handle.h"
#include "bssrdf/multipole.h"

#include <math.h>
#include <stdlib.h>

#define MULTIPOLE_MAX_PAIRS 10000

typedef struct {
  double eta, t_out;
  ss_multipole m[SS_BSSRDF_CHANNELS];
  double r_total[SS_BSSRDF_CHANNELS], t_total[SS_BSSRDF_CHANNELS];
  double small, large;
  ss_radial_mix mix[SS_BSSRDF_CHANNELS];
} multipole;

static ss_status multipole_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  if (!(p->thickness > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "multipole: thickness must be > 0 (INFINITY for a half-space), got %g",
                        p->thickness);
  }
  multipole *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "multipole: out of memory");
  }
  m->eta = p->eta;
  m->t_out = ss_fresnel_transmission_out(p->eta);
  double A = ss_fresnel_A(p->eta);
  m->small = INFINITY;
  m->large = 0.0;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k = ss_bssrdf_coeffs_make(p->sigma_s[c], p->sigma_a[c], p->g[c]);
    if (p->thickness < 1.0 / k.sigma_t_prime) {
      free(m);
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "multipole: thickness %g is below the source depth 1/sigma_t' = %g of "
                          "channel %c (Donner & Jensen place the source inside the slab)",
                          p->thickness, 1.0 / k.sigma_t_prime, "RGB"[c]);
    }
    ss_multipole_setup(&m->m[c], k, p->thickness, A, A, MULTIPOLE_MAX_PAIRS);
    m->r_total[c] = ss_multipole_reflectance_disk(&m->m[c], INFINITY);
    m->t_total[c] = ss_multipole_transmittance_disk(&m->m[c], INFINITY);
    double rates[2] = {fmax(k.sigma_tr, 1e-3 * k.sigma_t_prime), k.sigma_t_prime};
    double weights[2] = {0.75, 0.25};
    ss_radial_mix_init(&m->mix[c], 2, rates, weights);
    m->small = fmin(m->small, 0.05 / k.sigma_t_prime);
    m->large = fmax(m->large, ss_radial_mix_max_radius(&m->mix[c]));
  }
  *state = m;
  return SS_OK;
}

static void multipole_destroy(void *state) { free(state); }

static void multipole_eval(const void *state, const ss_bssrdf_query *q,
                           double s[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), m->eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), m->eta) * SS_INV_PI;
  double r = ss_vec3_length(ss_vec3_sub(q->x_o, q->x_i));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s[c] = f * fmax(0.0, ss_multipole_reflectance(&m->m[c], r));
  }
}

static int multipole_sample(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                            double u1, double u2, ss_bssrdf_entry *e) {
  const multipole *m = state;
  ss_radial_mix_sample(&m->mix[channel], u1, u2, e);
  return 1;
}

static double multipole_pdf(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                            double r, double phi) {
  const multipole *m = state;
  return ss_radial_mix_pdf(&m->mix[channel], r);
}

static double multipole_max_radius(const void *state, int channel) {
  const multipole *m = state;
  return ss_radial_mix_max_radius(&m->mix[channel]);
}

static void multipole_total(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  double f = ss_ft_outside(cos_i, m->eta) * m->t_out;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * m->r_total[c];
  }
}

static void multipole_transmit(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  double f = ss_ft_outside(cos_i, m->eta) * m->t_out;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * m->t_total[c];
  }
}

static void multipole_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = m->r_total[c];
  }
}

static void multipole_profile(const void *state, int channel, double r,
                              ss_bssrdf_profile_value *out) {
  const multipole *m = state;
  out->ms = out->value = ss_multipole_reflectance(&m->m[channel], r);
  out->t = ss_multipole_transmittance(&m->m[channel], r);
}

static void multipole_exitance(const void *state, double cos_i, double x, double y,
                               double out[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  double f = ss_ft_outside(cos_i, m->eta) * m->t_out, r = hypot(x, y);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * fmax(0.0, ss_multipole_reflectance(&m->m[c], r));
  }
}

static void multipole_brdf(const void *state, ss_vec3 w_i, ss_vec3 w_o,
                           double out[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  double f = ss_ft_outside(w_i.z, m->eta) * ss_ft_outside(w_o.z, m->eta) * SS_INV_PI;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * m->r_total[c];
  }
}

const ss_bssrdf_ops ss_bssrdf_model_multipole = {
    .name = "multipole",
    .summary = "thin slab R(r), T(r) from mirrored dipole pairs (Donner & Jensen 2005)",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_SLAB,
    .create = multipole_create,
    .destroy = multipole_destroy,
    .eval = multipole_eval,
    .sample_entry = multipole_sample,
    .pdf_entry = multipole_pdf,
    .max_radius = multipole_max_radius,
    .total_reflectance = multipole_total,
    .rd = multipole_rd,
    .profile = multipole_profile,
    .exitance = multipole_exitance,
    .brdf = multipole_brdf,
    .total_transmittance = multipole_transmit,
};
