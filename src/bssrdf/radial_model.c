/* The operations every radially symmetric profile model shares (see
 * radial_model.h): the separable Fresnel factors of S and M around the
 * model's R(r), its totals, and entry sampling from radial mixtures. */
#include "bssrdf/radial_model.h"

#include "bssrdf/handle.h"

#include <math.h>

int ss_radial_sampler_sample_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                   double u1, double u2, ss_bssrdf_entry *e) {
  ss_radial_mix_sample(&((const ss_radial_sampler *)state)->ch[channel], u1, u2, e);
  return 1;
}

double ss_radial_sampler_pdf_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                   double r, double phi) {
  return ss_radial_mix_pdf(&((const ss_radial_sampler *)state)->ch[channel], r);
}

double ss_radial_sampler_max_radius(const void *state, int channel) {
  return ss_radial_mix_max_radius(&((const ss_radial_sampler *)state)->ch[channel]);
}

void ss_radial_model_init(ss_radial_model *m, double eta, ss_radial_exit exit,
                          ss_radial_profile_fn profile) {
  m->profile = profile;
  m->eta = eta;
  m->t_out = ss_fresnel_transmission_out(eta);
  if (exit == SS_RADIAL_EXIT_FRESNEL) {
    m->s_scale = SS_INV_PI;
    m->m_scale = m->t_out;
  } else {
    m->s_scale = 1.0 / (SS_PI * m->t_out);
    m->m_scale = 1.0;
  }
  m->small = INFINITY;
  m->large = 0.0;
}

void ss_radial_model_set_diffusion_sampler(ss_radial_model *m, int c, double sigma_tr,
                                           double sigma_t_prime) {
  ss_radial_mix *mix = &m->sampler.mix[c];
  ss_radial_mix_init_diffusion(mix, sigma_tr, sigma_t_prime);
  m->small = fmin(m->small, 0.05 * (1.0 / sigma_t_prime));
  m->large = fmax(m->large, ss_radial_mix_max_radius(mix));
}

static void unit_profile(const void *ctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = ctx;
  m->profile(m, r, 1.0, out);
}

void ss_radial_model_fit_sampler(ss_radial_model *m, const ss_bssrdf_params *p) {
  if (p->single_use) {
    ss_profile_sampler_init_mixture(&m->sampler, m->sampler.mix);
  } else {
    ss_profile_sampler_init_diffusion(&m->sampler, unit_profile, m, m->sampler.mix);
  }
}

static void ring(void *ctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = ctx;
  m->profile(m, r, 2.0 * SS_PI * r, out);
}

void ss_radial_model_integrate_total(ss_radial_model *m) {
  ss_vec_integrate_halfline(ring, m, m->small, m->large, m->total);
}

void ss_radial_model_eval(const void *state, const ss_bssrdf_query *q,
                          double s[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = state;
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), m->eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), m->eta) * m->s_scale;
  m->profile(m, ss_vec3_length(ss_vec3_sub(q->x_o, q->x_i)), f, s);
}

static void scaled_totals(const ss_radial_model *m, double cos_i,
                          const double total[SS_BSSRDF_CHANNELS], double out[SS_BSSRDF_CHANNELS]) {
  double f = ss_ft_outside(cos_i, m->eta) * m->m_scale;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * total[c];
  }
}

void ss_radial_model_total_reflectance(const void *state, double cos_i,
                                       double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = state;
  scaled_totals(m, cos_i, m->total, out);
}

void ss_radial_model_total_transmittance(const void *state, double cos_i,
                                         double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = state;
  scaled_totals(m, cos_i, m->transmit, out);
}

void ss_radial_model_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = m->total[c];
  }
}

void ss_radial_model_profile(const void *state, int channel, double r,
                             ss_bssrdf_profile_value *out) {
  const ss_radial_model *m = state;
  double v[SS_BSSRDF_CHANNELS];
  m->profile(m, r, 1.0, v);
  out->ms = out->value = v[channel];
}

void ss_radial_model_exitance(const void *state, double cos_i, double x, double y,
                              double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = state;
  m->profile(m, hypot(x, y), ss_ft_outside(cos_i, m->eta) * m->m_scale, out);
}

typedef struct {
  const ss_radial_model *m;
  double x;
} line_ctx;

/* Both halves y and -y of the line at once (R is even in y). */
static void line_point(void *ctx, double y, double out[SS_BSSRDF_CHANNELS]) {
  const line_ctx *l = ctx;
  l->m->profile(l->m, hypot(l->x, y), 2.0, out);
}

void ss_radial_model_radiance_line(const void *state, double cos_i, double x, ss_vec3 w_o,
                                   double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = state;
  line_ctx l = {m, x};
  ss_vec_integrate_halfline(line_point, &l, m->small, m->large, out);
  double f = ss_ft_outside(cos_i, m->eta) * ss_ft_outside(w_o.z, m->eta) * m->s_scale;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] *= f;
  }
}

void ss_radial_model_brdf(const void *state, ss_vec3 w_i, ss_vec3 w_o,
                          double out[SS_BSSRDF_CHANNELS]) {
  const ss_radial_model *m = state;
  double f = ss_ft_outside(w_i.z, m->eta) * ss_ft_outside(w_o.z, m->eta) * m->s_scale;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * m->total[c];
  }
}
