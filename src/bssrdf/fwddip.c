/* Forward scattering dipole (Frederickx2017; docs/fwddip.md).
 *
 * | option     | meaning                                                     |
 * |------------|-------------------------------------------------------------|
 * | sigma_s, g | p = sigma_s'/2 = (1 - g) sigma_s / 2, the propagator's scale |
 * | sigma_a    | absorption e^{-sigma_a s} along the path length s           |
 * | eta        | refraction and Fresnel at both ends (smooth dielectric)     |
 * | s_rtol     | relative accuracy of the adaptive integral over s (1e-3)    |
 * | reciprocal | eq. 15 instead of eq. 14 (off)                              |
 * | image_a    | virtual source at 2 A d_e: A from the Fresnel moments, or 1 |
 * | alpha, distribution, rough_nodes | a rough dielectric boundary (0: smooth) |
 *
 * S(x_i, w_i; x_o, w_o) = Ft(w_i) Ft(w_o)/eta^2 int_0^inf G^b_f(s, x_o, w_o^e,
 * x_i, w_i^e) ds (eq. 14 and 16 for a unit-power beam), with w_i^e the
 * refracted beam and w_o^e the inside propagation direction that leaves
 * toward w_o; the integral is clamped at 0 where the image dominates. Behind
 * a rough boundary the two directions become the rules of fwddip_rough.c,
 * summed in pairs inside the s integral. The
 * path-length integral is adaptive (fwddip_integrate.c). Entry sampling:
 * the diffusion models' radial mixture for the radius and, when the exit
 * direction is known and oblique, an azimuth leaning upstream (a mixture of
 * uniform and wrapped Cauchy, docs/fwddip.md); exact for what it draws. */
#include "subsurf/fwddip.h"
#include "bssrdf/fwddip_model.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  const ss_fwddip_state *st;
  int c;
  ss_vec3 x_o, n_o, w_o, x_i, n_i, w_i;
  const ss_fwddip_dipole *dip; /* made for (x_o, x_i, n_i, w_i), NULL where G^b_f vanishes */
} point_ctx;

static double point_integrand(void *vctx, const ss_fwddip_coeffs *k, double s) {
  const point_ctx *q = vctx;
  const ss_fwddip_medium *m = &q->st->m[q->c];
  double z_v = q->st->z_v[q->c];
  if (q->st->cfg.reciprocal) {
    return ss_fwddip_gbf_reciprocal(m, k, s, q->x_o, q->n_o, q->w_o, q->x_i, q->n_i, q->w_i, z_v);
  }
  /* Eq. 14 with the dipole of eq. 12-13, which does not depend on s. */
  return q->dip ? ss_fwddip_gbf_dipole(m, k, s, q->x_o, q->w_o, q->x_i, q->w_i, q->dip) : 0.0;
}

/* int G^b_f ds for channel c with inside directions. */
static double point_transport(void *vctx, int c) {
  point_ctx q = *(const point_ctx *)vctx;
  const ss_fwddip_state *st = q.st;
  q.c = c;
  double d[2] = {ss_vec3_length(ss_vec3_sub(q.x_o, q.x_i)), 0.0};
  ss_fwddip_dipole dip;
  int n = 1;
  if (ss_fwddip_dipole_make(q.x_o, q.x_i, q.n_i, q.w_i, st->z_v[c], &dip)) {
    d[n++] = ss_vec3_length(ss_vec3_sub(q.x_o, dip.x_v));
    q.dip = &dip;
  } else if (!st->cfg.reciprocal) {
    return 0.0;
  }
  return ss_fwddip_integrate_s(&st->m[c], point_integrand, &q, d, n, st->cfg.s_rtol);
}

/* The rough boundary: the transported radiance summed over the pairs of
 * transmitted directions at the exit (out) and the entry (in). */
typedef struct {
  point_ctx q;
  ss_fwddip_nodes in, out;
  /* per entry direction in.d[a], for the channel being integrated */
  ss_fwddip_dipole dip[SS_FWDDIP_ROUGH_MAX];
  int has_dip[SS_FWDDIP_ROUGH_MAX];
} rough_point_ctx;

static double rough_point_integrand(void *vctx, const ss_fwddip_coeffs *k, double s) {
  const rough_point_ctx *r = vctx;
  point_ctx q = r->q;
  double sum = 0.0;
  for (int j = 0; j < r->out.n; ++j) {
    double inner = 0.0;
    q.w_o = r->out.d[j];
    for (int a = 0; a < r->in.n; ++a) {
      q.w_i = r->in.d[a];
      q.dip = r->has_dip[a] ? &r->dip[a] : NULL;
      inner += r->in.w[a] * point_integrand(&q, k, s);
    }
    sum += r->out.w[j] * inner;
  }
  return sum;
}

static double rough_point_transport(void *vctx, int c) {
  rough_point_ctx *r = vctx;
  const ss_fwddip_state *st = r->q.st;
  r->q.c = c;
  double d[2] = {ss_vec3_length(ss_vec3_sub(r->q.x_o, r->q.x_i)), 0.0};
  ss_fwddip_dipole dip;
  int n = 1;
  /* The image source does not depend on the source direction (-n_i enters). */
  if (ss_fwddip_dipole_make(r->q.x_o, r->q.x_i, r->q.n_i, ss_vec3_neg(r->q.n_i), st->z_v[c],
                            &dip)) {
    d[n++] = ss_vec3_length(ss_vec3_sub(r->q.x_o, dip.x_v));
  }
  for (int a = 0; a < r->in.n; ++a) {
    r->has_dip[a] =
        ss_fwddip_dipole_make(r->q.x_o, r->q.x_i, r->q.n_i, r->in.d[a], st->z_v[c], &r->dip[a]);
  }
  return ss_fwddip_integrate_s(&st->m[c], rough_point_integrand, r, d, n, st->cfg.s_rtol);
}

static void fwddip_eval(const void *state, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]) {
  const ss_fwddip_state *st = state;
  ss_channels_zero(s);
  point_ctx base = {.st = st, .x_o = q->x_o, .n_o = q->n_o, .x_i = q->x_i, .n_i = q->n_i};
  if (st->rough.on) {
    rough_point_ctx r = {.q = base};
    double one;
    if (ss_fwddip_pairs(st, q->w_i, q->n_i, q->w_o, q->n_o, &r.in, &r.out, &one)) {
      ss_fwddip_channels(st, rough_point_transport, &r, one, s);
    }
    return;
  }
  double factor;
  if (!ss_fwddip_boundary(st->eta, q->w_i, q->n_i, q->w_o, q->n_o, &base.w_i, &base.w_o, &factor)) {
    return;
  }
  ss_fwddip_channels(st, point_transport, &base, factor, s);
}

/* --- entry sampling ------------------------------------------------- */

/* The upstream azimuth (toward where light leaving along ctx->w came from,
 * -w projected on the tangent plane) and the wrapped Cauchy's rho = 0.95
 * sin(theta_w); rho = 0 (uniform azimuth) when w is unknown or normal. */
static double upstream(const ss_bssrdf_sample_ctx *ctx, double *rho) {
  double ws = ss_vec3_dot(ctx->w, ctx->frame.s), wt = ss_vec3_dot(ctx->w, ctx->frame.t);
  double sin_w = fmin(1.0, hypot(ws, wt));
  *rho = ss_vec3_dot(ctx->w, ctx->frame.n) > 0.0 ? 0.95 * sin_w : 0.0;
  return *rho > 0.0 ? atan2(-wt, -ws) : 0.0;
}

/* Azimuth density on [0, 2 pi): 1/2 uniform + 1/2 wrapped Cauchy about phi0. */
static double azimuth_pdf(double phi, double phi0, double rho) {
  double cauchy =
      (1.0 - rho * rho) / (2.0 * SS_PI * (1.0 + rho * rho - 2.0 * rho * cos(phi - phi0)));
  return 0.5 / (2.0 * SS_PI) + 0.5 * cauchy;
}

static int fwddip_sample_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                               double u1, double u2, ss_bssrdf_entry *e) {
  const ss_fwddip_state *st = state;
  ss_radial_mix_sample(&st->sampler.ch[channel], u1, 0.0, e);
  double rho, phi0 = upstream(ctx, &rho);
  if (u2 < 0.5 || rho == 0.0) {
    e->phi = 2.0 * SS_PI * (u2 < 0.5 ? 2.0 * u2 : 2.0 * u2 - 1.0);
  } else {
    /* Inverse cdf of the wrapped Cauchy. */
    double v = 2.0 * u2 - 1.0;
    e->phi = phi0 + 2.0 * atan((1.0 - rho) / (1.0 + rho) * tan(SS_PI * (v - 0.5)));
  }
  e->phi = fmod(e->phi + 4.0 * SS_PI, 2.0 * SS_PI);
  e->pdf = ss_radial_mix_pdf(&st->sampler.ch[channel], e->r) * 2.0 * SS_PI *
           azimuth_pdf(e->phi, phi0, rho);
  return 1;
}

static double fwddip_pdf_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                               double r, double phi) {
  const ss_fwddip_state *st = state;
  double rho, phi0 = upstream(ctx, &rho);
  return ss_radial_mix_pdf(&st->sampler.ch[channel], r) * 2.0 * SS_PI * azimuth_pdf(phi, phi0, rho);
}

/* --- the inside transport for renderers (subsurf/fwddip.h) ------------ */

extern const ss_bssrdf_ops ss_bssrdf_model_fwddip;

static const ss_fwddip_state *fwddip_of(const ss_bssrdf *b) {
  return ss_bssrdf_get_ops(b) == &ss_bssrdf_model_fwddip ? ss_bssrdf_state(b) : NULL;
}

double ss_fwddip_propagator(const ss_bssrdf *b, int channel, double s, ss_vec3 x_o, ss_vec3 n_o,
                            ss_vec3 wo_e, ss_vec3 x_i, ss_vec3 n_i, ss_vec3 wi_e) {
  const ss_fwddip_state *st = fwddip_of(b);
  if (!st || channel < 0 || channel >= SS_BSSRDF_CHANNELS || !(s > 0.0)) {
    return 0.0;
  }
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(st->m[channel].p * s, &k);
  ss_fwddip_dipole dip;
  int has_dip = ss_fwddip_dipole_make(x_o, x_i, n_i, wi_e, st->z_v[channel], &dip);
  point_ctx q = {st, channel, x_o, n_o, wo_e, x_i, n_i, wi_e, has_dip ? &dip : NULL};
  return point_integrand(&q, &k, s);
}

void ss_fwddip_transport(const ss_bssrdf *b, ss_vec3 x_o, ss_vec3 n_o, ss_vec3 wo_e, ss_vec3 x_i,
                         ss_vec3 n_i, ss_vec3 wi_e, double out[SS_BSSRDF_CHANNELS]) {
  const ss_fwddip_state *st = fwddip_of(b);
  ss_channels_zero(out);
  if (st) {
    point_ctx q = {st, 0, x_o, n_o, wo_e, x_i, n_i, wi_e, NULL};
    ss_fwddip_channels(st, point_transport, &q, 1.0, out);
  }
}

static ss_status fwddip_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  return ss_fwddip_state_create(p, "fwddip", state, err);
}

/* --- the half-space observables -------------------------------------- */

/* M(x, y) = Ft(w_i) sum_k weight_k int G^b_f(s, x_o, w_k, 0, w_i^e) ds over
 * the inside directions w_k of the state's rule (cos_o dw_o = eta^2 cos_t
 * dw_t cancels the 1/eta^2 of the radiance). */
typedef struct {
  const ss_fwddip_state *st;
  int c;
  ss_vec3 x_o;
  ss_fwddip_nodes in;            /* the beam's transmitted directions */
  double xd[SS_FWDDIP_DIRS_MAX]; /* x_o . dir[j] (rough boundary) */
} exitance_ctx;

static double exitance_integrand(void *vctx, const ss_fwddip_coeffs *k, double s) {
  const exitance_ctx *e = vctx;
  const ss_fwddip_state *st = e->st;
  ss_vec3 n = ss_vec3_make(0, 0, 1), o = ss_vec3_make(0, 0, 0);
  double total = 0.0;
  for (int a = 0; a < e->in.n; ++a) {
    double sum = 0.0;
    for (int j = 0; j < st->n_dir; ++j) {
      sum += st->dir_weight[j] *
             ss_fwddip_gbf(&st->m[e->c], k, s, e->x_o, st->dir[j], o, n, e->in.d[a], st->z_v[e->c]);
    }
    total += e->in.w[a] * sum;
  }
  return total;
}

/* The same sum behind a rough boundary, with eq. 9's exponent expanded on
 * the plane (n* = n, image at z_v n, w_v = w - 2 (w.n) n) so that the pairs
 * of entry and exit directions cost two dot products and two exponentials:
 * real  = -D d.w + E p x_o.(d + w) - F p^2 |x_o|^2,
 * image = -D d.w_v + E p (x_o - z_v n).(d + w_v) - F p^2 (|x_o|^2 + z_v^2). */
static double rough_exitance_integrand(void *vctx, const ss_fwddip_coeffs *k, double s) {
  const exitance_ctx *e = vctx;
  const ss_fwddip_state *st = e->st;
  const ss_fwddip_medium *m = &st->m[e->c];
  double p = m->p, zv = st->z_v[e->c], r2 = ss_vec3_length2(e->x_o), ep = k->E * p;
  double base = m->log_p3 + k->log_norm - m->sigma_a * s, total = 0.0;
  for (int a = 0; a < e->in.n; ++a) {
    ss_vec3 w = e->in.d[a];
    double xw = ss_vec3_dot(e->x_o, w), sum = 0.0;
    double c_real = base + ep * xw - k->F * p * p * r2;
    double c_image = base + ep * (xw + zv * w.z) - k->F * p * p * (r2 + zv * zv);
    for (int j = 0; j < st->n_dir; ++j) {
      ss_vec3 d = st->dir[j];
      double dw = ss_vec3_dot(d, w);
      double real = c_real - k->D * dw + ep * e->xd[j];
      double image = c_image - k->D * (dw - 2.0 * d.z * w.z) + ep * (e->xd[j] - zv * d.z);
      sum += st->dir_weight[j] * (ss_fwddip_exp(real) - ss_fwddip_exp(image));
    }
    total += e->in.w[a] * sum;
  }
  return total;
}

static double exitance_transport(void *vctx, int c) {
  exitance_ctx *e = vctx;
  e->c = c;
  ss_fwddip_s_fn f = e->st->rough.on ? rough_exitance_integrand : exitance_integrand;
  return ss_fwddip_integrate_s(&e->st->m[c], f, e, NULL, 0, e->st->cfg.s_rtol);
}

static void fwddip_exitance(const void *state, double cos_i, double x, double y,
                            double out[SS_BSSRDF_CHANNELS]) {
  const ss_fwddip_state *st = state;
  ss_channels_zero(out);
  exitance_ctx e = {.st = st, .x_o = ss_vec3_make(x, y, 0.0)};
  for (int j = 0; st->rough.on && j < st->n_dir; ++j) {
    e.xd[j] = ss_vec3_dot(e.x_o, st->dir[j]);
  }
  double ft;
  if (ss_fwddip_beam_nodes(st, cos_i, &e.in, &ft)) {
    ss_fwddip_channels(st, exitance_transport, &e, ft, out);
  }
}

/* log int_a^b exp(alpha x - beta x^2) dx (beta > 0), -inf when it underflows. */
static double log_gauss_interval(double alpha, double beta, double a, double b) {
  double sb = sqrt(beta), c = alpha / (2.0 * beta);
  double ta = sb * (a - c), tb = sb * (b - c), d;
  if (ta > 0.0) {
    d = erfc(ta) - erfc(tb);
  } else if (tb < 0.0) {
    d = erfc(-tb) - erfc(-ta);
  } else {
    d = erf(tb) - erf(ta);
  }
  if (!(d > 0.0)) {
    return -INFINITY;
  }
  return 0.5 * log(SS_PI / beta) - log(2.0) + alpha * alpha / (4.0 * beta) + log(d);
}

typedef struct {
  const ss_fwddip_state *st;
  int c;
  ss_fwddip_nodes in, out; /* the pairs of inside directions (one each when smooth) */
  double x_lo, x_hi;
} bin_ctx;

/* G_f of a source at (0, 0, z0) integrated over the strip x_lo <= x <= x_hi
 * of the surface (all y), in logarithms: eq. 9 is Gaussian in x and y. */
static double log_strip(const ss_fwddip_medium *m, const ss_fwddip_coeffs *k, const bin_ctx *b,
                        double z0, ss_vec3 w, ss_vec3 wp) {
  ss_vec3 u = ss_vec3_add(w, wp);
  double p = m->p, beta = k->F * p * p, pz = -p * z0;
  double lx = log_gauss_interval(k->E * p * u.x, beta, b->x_lo, b->x_hi);
  double ly = 0.5 * log(SS_PI / beta) + k->E * k->E * u.y * u.y / (4.0 * k->F);
  return -k->D * ss_vec3_dot(w, wp) + k->E * pz * u.z - k->F * pz * pz + lx + ly;
}

static double bin_integrand(void *vctx, const ss_fwddip_coeffs *k, double s) {
  const bin_ctx *b = vctx;
  const ss_fwddip_medium *m = &b->st->m[b->c];
  double base = m->log_p3 + k->log_norm - m->sigma_a * s, sum = 0.0;
  for (int j = 0; j < b->out.n; ++j) {
    double inner = 0.0;
    for (int a = 0; a < b->in.n; ++a) {
      ss_vec3 w_i = b->in.d[a], w_v = ss_vec3_make(w_i.x, w_i.y, -w_i.z);
      /* Frederickx2017 eq. 14 on the plane: n* = n, image at z_v above the entry. */
      inner += b->in.w[a] * (exp(base + log_strip(m, k, b, 0.0, b->out.d[j], w_i)) -
                             exp(base + log_strip(m, k, b, b->st->z_v[b->c], b->out.d[j], w_v)));
    }
    sum += b->out.w[j] * inner;
  }
  return sum;
}

static double bin_transport(void *vctx, int c) {
  bin_ctx *b = vctx;
  double d[3] = {fabs(b->x_lo), fabs(b->x_hi), fabs(0.5 * (b->x_lo + b->x_hi))};
  b->c = c;
  return ss_fwddip_integrate_s(&b->st->m[c], bin_integrand, b, d, 3, b->st->cfg.s_rtol);
}

static void fwddip_radiance_bin(const void *state, double cos_i, ss_vec3 w_o, double x_lo,
                                double x_hi, double out[SS_BSSRDF_CHANNELS]) {
  const ss_fwddip_state *st = state;
  ss_channels_zero(out);
  double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i)), factor;
  ss_vec3 n = ss_vec3_make(0, 0, 1);
  bin_ctx b = {.st = st, .x_lo = x_lo, .x_hi = x_hi};
  if (!ss_fwddip_pairs(st, ss_vec3_make(-sin_i, 0.0, cos_i), n, w_o, n, &b.in, &b.out, &factor)) {
    return;
  }
  ss_fwddip_channels(st, bin_transport, &b, factor / (x_hi - x_lo), out);
}

static void fwddip_profile(const void *state, int channel, double r, ss_bssrdf_profile_value *out) {
  double v[SS_BSSRDF_CHANNELS];
  fwddip_exitance(state, 1.0, r, 0.0, v);
  out->ms = out->value = v[channel];
}

const ss_bssrdf_ops ss_bssrdf_model_fwddip = {
    .name = "fwddip",
    .summary = "forward scattering dipole: propagator of a worm-like chain (Frederickx & Dutré "
               "2017)",
    .options = ss_fwddip_options,
    .flags = SS_BSSRDF_ANGULAR,
    .create = fwddip_create,
    .destroy = free,
    .eval = fwddip_eval,
    .sample_entry = fwddip_sample_entry,
    .pdf_entry = fwddip_pdf_entry,
    .max_radius = ss_radial_sampler_max_radius,
    .total_reflectance = ss_fwddip_total_reflectance,
    .profile = fwddip_profile,
    .exitance = fwddip_exitance,
    .radiance_bin = fwddip_radiance_bin,
};
