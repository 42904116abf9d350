/* The effective BRDF of the forward scattering dipole (Frederickx2017
 * sec. 8; docs/fwddip.md).
 *
 * | option           | meaning                                               |
 * |------------------|-------------------------------------------------------|
 * | sigma_s, g, sigma_a, eta | as for fwddip                                 |
 * | s_rtol           | relative accuracy of the adaptive integral over s     |
 * | image_a          | image plane at 2 A d_e: A from the Fresnel moments, or 1 |
 * | alpha, distribution, rough_nodes | a rough dielectric boundary (fwddip_rough.c) |
 *
 * f_r(w_i, w_o) = Ft(w_i) Ft(w_o)/eta^2 int_0^inf G^pb_f(s, w_o^e, w_i^e) ds
 * (eq. 17-18 in docs/fwddip.md's conventions: both directions propagation
 * directions, w_i^e the refracted beam, w_o^e the inside direction leaving
 * toward w_o, image plane 2 A d_e outside), clamped at 0. Light leaves where
 * it entered: eval is 0 (SS_BSSRDF_BRDF) and the brdf hook is the model. */
#include "bssrdf/fwddip_model.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  const ss_fwddip_state *st;
  int c;
  ss_fwddip_nodes in, out; /* inside directions at both ends (one each when smooth) */
} plane_ctx;

static double plane_integrand(void *vctx, const ss_fwddip_coeffs *k, double s) {
  const plane_ctx *q = vctx;
  double sum = 0.0;
  for (int j = 0; j < q->out.n; ++j) {
    double inner = 0.0;
    for (int a = 0; a < q->in.n; ++a) {
      inner += q->in.w[a] * ss_fwddip_gpbf(&q->st->m[q->c], k, s, q->out.d[j], q->in.d[a],
                                           ss_vec3_make(0, 0, 1), q->st->z_v[q->c]);
    }
    sum += q->out.w[j] * inner;
  }
  return sum;
}

static double plane_transport(void *vctx, int c) {
  plane_ctx *q = vctx;
  q->c = c;
  return ss_fwddip_integrate_s(&q->st->m[c], plane_integrand, q, NULL, 0, q->st->cfg.s_rtol);
}

static void fwddip_brdf_brdf(const void *state, ss_vec3 w_i, ss_vec3 w_o,
                             double out[SS_BSSRDF_CHANNELS]) {
  const ss_fwddip_state *st = state;
  ss_vec3 n = ss_vec3_make(0, 0, 1);
  plane_ctx q = {.st = st};
  double factor;
  ss_channels_zero(out);
  if (!ss_fwddip_pairs(st, w_i, n, w_o, n, &q.in, &q.out, &factor)) {
    return;
  }
  ss_fwddip_channels(st, plane_transport, &q, factor, out);
}

/* Ft(w_i) sum_k weight_k G^pb_f(s, w_k, w_i^e) over the state's inside rule. */
static double albedo_integrand(void *vctx, const ss_fwddip_coeffs *k, double s) {
  const plane_ctx *q = vctx;
  const ss_fwddip_state *st = q->st;
  ss_vec3 n = ss_vec3_make(0, 0, 1);
  double total = 0.0;
  for (int a = 0; a < q->in.n; ++a) {
    double sum = 0.0;
    for (int j = 0; j < st->n_dir; ++j) {
      sum += st->dir_weight[j] *
             ss_fwddip_gpbf(&st->m[q->c], k, s, st->dir[j], q->in.d[a], n, st->z_v[q->c]);
    }
    total += q->in.w[a] * sum;
  }
  return total;
}

static double albedo_transport(void *vctx, int c) {
  plane_ctx *q = vctx;
  q->c = c;
  return ss_fwddip_integrate_s(&q->st->m[c], albedo_integrand, q, NULL, 0, q->st->cfg.s_rtol);
}

void ss_fwddip_total_reflectance(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const ss_fwddip_state *st = state;
  plane_ctx q = {.st = st};
  double ft;
  ss_channels_zero(out);
  if (!(cos_i > 0.0) || !ss_fwddip_beam_nodes(st, cos_i, &q.in, &ft)) {
    return;
  }
  ss_fwddip_channels(st, albedo_transport, &q, ft, out);
}

static void fwddip_brdf_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  ss_fwddip_total_reflectance(state, 1.0, out);
}

static ss_status fwddip_brdf_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  return ss_fwddip_state_create(p, "fwddip-brdf", state, err);
}

const ss_bssrdf_ops ss_bssrdf_model_fwddip_brdf = {
    .name = "fwddip-brdf",
    .summary = "effective BRDF of the forward scattering dipole, int G^pb_f ds (Frederickx & "
               "Dutré 2017 sec. 8)",
    .options = ss_fwddip_brdf_options,
    .flags = SS_BSSRDF_BRDF | SS_BSSRDF_ANGULAR,
    .create = fwddip_brdf_create,
    .destroy = free,
    .max_radius = ss_radial_sampler_max_radius,
    .total_reflectance = ss_fwddip_total_reflectance,
    .rd = fwddip_brdf_rd,
    .brdf = fwddip_brdf_brdf,
};
