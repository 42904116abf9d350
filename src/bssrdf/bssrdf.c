/* The BSSRDF registry and the handle that pairs a model's operations with its
 * state. Every wrapper dispatches to the model; where an optional hook is
 * missing, observe.c integrates the lower-level ones. */
#include "subsurf/bssrdf.h"

#include "bssrdf/bssrdf_util.h"
#include "bssrdf/handle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SS_BSSRDF_MODEL(id) extern const ss_bssrdf_ops ss_bssrdf_model_##id;
#include "bssrdf/models.def"
#undef SS_BSSRDF_MODEL

static const ss_bssrdf_ops *const registry[] = {
#define SS_BSSRDF_MODEL(id) &ss_bssrdf_model_##id,
#include "bssrdf/models.def"
#undef SS_BSSRDF_MODEL
};

size_t ss_bssrdf_model_count(void) { return sizeof registry / sizeof registry[0]; }

const ss_bssrdf_ops *ss_bssrdf_model_at(size_t i) {
  return i < ss_bssrdf_model_count() ? registry[i] : NULL;
}

const ss_bssrdf_ops *ss_bssrdf_model_find(const char *name) {
  if (!name) {
    return NULL;
  }
  for (size_t i = 0; i < ss_bssrdf_model_count(); ++i) {
    if (!strcmp(registry[i]->name, name)) {
      return registry[i];
    }
  }
  return NULL;
}

void ss_bssrdf_model_names(char *buf, size_t size) {
  if (size == 0) {
    return;
  }
  buf[0] = '\0';
  size_t used = 0;
  for (size_t i = 0; i < ss_bssrdf_model_count() && used + 1 < size; ++i) {
    int n = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", registry[i]->name);
    if (n < 0) {
      break;
    }
    used += (size_t)n;
  }
}

void ss_bssrdf_params_default(ss_bssrdf_params *p) {
  memset(p, 0, sizeof *p);
  ss_bssrdf_params_set_gray(p, 1.0, 0.01, 0.0);
  p->eta = 1.3;
}

void ss_bssrdf_params_set_gray(ss_bssrdf_params *p, double sigma_s, double sigma_a, double g) {
  p->medium = ss_medium_optics_gray(sigma_s, sigma_a, g, SS_PHASE_HG);
}

ss_bssrdf_coeffs ss_bssrdf_coeffs_make(double sigma_s, double sigma_a, double g) {
  ss_bssrdf_coeffs k;
  k.sigma_t = sigma_s + sigma_a;
  k.sigma_s_prime = (1.0 - g) * sigma_s;
  k.sigma_t_prime = k.sigma_s_prime + sigma_a;
  k.alpha_prime = k.sigma_s_prime / k.sigma_t_prime;
  /* Jensen et al. 2001, sec. 2.1. */
  k.D = 1.0 / (3.0 * k.sigma_t_prime);
  k.sigma_tr = sqrt(3.0 * sigma_a * k.sigma_t_prime);
  /* Grosjean's diffusion coefficient (d'Eon 2012; Habel et al. 2013). */
  k.D_g = (2.0 * sigma_a + k.sigma_s_prime) / (3.0 * k.sigma_t_prime * k.sigma_t_prime);
  k.sigma_tr_g = sqrt(sigma_a / k.D_g);
  return k;
}

ss_status ss_bssrdf_create(const char *name, const ss_bssrdf_params *p, ss_bssrdf **out,
                           ss_error *err) {
  const ss_bssrdf_ops *ops = ss_bssrdf_model_find(name);
  if (!ops) {
    char names[512];
    ss_bssrdf_model_names(names, sizeof names);
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "unknown BSSRDF model '%s' (known: %s)",
                        name ? name : "(null)", names);
  }
  return ss_bssrdf_create_ops(ops, p, out, err);
}

ss_status ss_bssrdf_check(const ss_bssrdf_ops *ops, const ss_bssrdf_params *p, ss_error *err) {
  ss_status st = ops->flags & SS_BSSRDF_FLAKES ? ss_bssrdf_params_check_medium(p, ops->name, err)
                                               : ss_bssrdf_params_check(p, ops->name, err);
  return st == SS_OK ? ss_bssrdf_params_check_options(p, ops, err) : st;
}

ss_status ss_bssrdf_create_ops(const ss_bssrdf_ops *ops, const ss_bssrdf_params *p, ss_bssrdf **out,
                               ss_error *err) {
  *out = NULL;
  ss_status st = ss_bssrdf_check(ops, p, err);
  if (st != SS_OK) {
    return st;
  }
  ss_bssrdf *b = calloc(1, sizeof *b);
  if (!b) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", ops->name);
  }
  b->ops = ops;
  b->params = *p;
  st = ops->create(&b->params, &b->state, err);
  if (st != SS_OK) {
    free(b);
    return st;
  }
  ss_bssrdf_observe_init(b);
  if (ops->point_source_exitance && !p->single_use) {
    /* a model built for one path vertex (textures) skips the quadrature
     * here, which its creation would pay per vertex; its lobe computes it */
    b->t_out = ss_fresnel_transmission_out(p->eta);
  }
  *out = b;
  return SS_OK;
}

void ss_bssrdf_destroy(ss_bssrdf *b) {
  if (!b) {
    return;
  }
  if (b->ops->destroy) {
    b->ops->destroy(b->state);
  }
  free(b);
}

const char *ss_bssrdf_name(const ss_bssrdf *b) { return b->ops->name; }
unsigned ss_bssrdf_flags(const ss_bssrdf *b) { return b->ops->flags; }
const ss_bssrdf_ops *ss_bssrdf_get_ops(const ss_bssrdf *b) { return b->ops; }
const ss_bssrdf_params *ss_bssrdf_get_params(const ss_bssrdf *b) { return &b->params; }
const void *ss_bssrdf_state(const ss_bssrdf *b) { return b->state; }

static int query_in_tail(const ss_bssrdf_query *q) {
  ss_vec3 d = ss_vec3_sub(q->x_o, q->x_i);
  return ss_bssrdf_in_tail(d.x) || ss_bssrdf_in_tail(d.y) || ss_bssrdf_in_tail(d.z) ||
         ss_bssrdf_in_tail(ss_vec3_length(d));
}

void ss_bssrdf_eval(const ss_bssrdf *b, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]) {
  if (b->ops->eval && !query_in_tail(q)) {
    b->ops->eval(b->state, q, s);
  } else {
    s[0] = s[1] = s[2] = 0.0;
  }
}

int ss_bssrdf_sample_entry(const ss_bssrdf *b, const ss_bssrdf_sample_ctx *ctx, int channel,
                           double u1, double u2, ss_bssrdf_entry *e) {
  if (!b->ops->sample_entry || channel < 0 || channel >= SS_BSSRDF_CHANNELS) {
    return 0;
  }
  return b->ops->sample_entry(b->state, ctx, channel, u1, u2, e);
}

double ss_bssrdf_pdf_entry(const ss_bssrdf *b, const ss_bssrdf_sample_ctx *ctx, int channel,
                           double r, double phi) {
  if (!b->ops->pdf_entry || channel < 0 || channel >= SS_BSSRDF_CHANNELS || ss_bssrdf_in_tail(r)) {
    return 0.0;
  }
  return b->ops->pdf_entry(b->state, ctx, channel, r, phi);
}

double ss_bssrdf_pdf_entry_channels(const ss_bssrdf *b, const ss_bssrdf_sample_ctx *ctx, double r,
                                    double phi) {
  double sum = 0.0;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    sum += ss_bssrdf_pdf_entry(b, ctx, c, r, phi);
  }
  return sum / SS_BSSRDF_CHANNELS;
}

double ss_bssrdf_max_radius(const ss_bssrdf *b, int channel) {
  if (!b->ops->max_radius || channel < 0 || channel >= SS_BSSRDF_CHANNELS) {
    return 0.0;
  }
  return b->ops->max_radius(b->state, channel);
}

void ss_bssrdf_rd(const ss_bssrdf *b, double out[SS_BSSRDF_CHANNELS]) {
  if (b->ops->rd) {
    b->ops->rd(b->state, out);
  } else {
    ss_bssrdf_total_reflectance(b, 1.0, out);
  }
}

void ss_bssrdf_total_transmittance(const ss_bssrdf *b, double cos_i,
                                   double out[SS_BSSRDF_CHANNELS]) {
  if (b->ops->total_transmittance) {
    b->ops->total_transmittance(b->state, cos_i, out);
  } else {
    out[0] = out[1] = out[2] = 0.0;
  }
}

double ss_bssrdf_entry_eta(const ss_bssrdf *b) {
  return b->ops->entry_eta ? b->ops->entry_eta(b->state) : b->params.eta;
}

int ss_bssrdf_uses_thickness(const ss_bssrdf *b) {
  return b->ops->uses_thickness ? b->ops->uses_thickness(b->state) : 0;
}

int ss_bssrdf_has_point_source(const ss_bssrdf *b) { return b->ops->point_source_exitance != NULL; }

void ss_bssrdf_point_source_exitance(const ss_bssrdf *b, double z, double r,
                                     double out[SS_BSSRDF_CHANNELS]) {
  if (!b->ops->point_source_exitance || ss_bssrdf_in_tail(hypot(z, r))) {
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      out[c] = 0.0;
    }
    return;
  }
  b->ops->point_source_exitance(b->state, z > 0.0 ? z : 0.0, fabs(r), out);
}

void ss_bssrdf_point_source_radiance(const ss_bssrdf *b, double z, double r, double cos_o,
                                     double out[SS_BSSRDF_CHANNELS]) {
  ss_bssrdf_point_source_exitance(b, z, r, out);
  double t_out = b->t_out > 0.0 ? b->t_out : ss_fresnel_transmission_out(b->params.eta);
  double lobe = ss_ft_outside(cos_o, b->params.eta) / (SS_PI * t_out);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] *= lobe;
  }
}

void ss_bssrdf_profile(const ss_bssrdf *b, int channel, double r, ss_bssrdf_profile_value *out) {
  memset(out, 0, sizeof *out);
  if (b->ops->profile && channel >= 0 && channel < SS_BSSRDF_CHANNELS && !ss_bssrdf_in_tail(r)) {
    b->ops->profile(b->state, channel, r, out);
  }
}
