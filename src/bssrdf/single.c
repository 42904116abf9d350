/* Single scattering S^(1) of a collimated beam in a half-space (Jensen2001
 * sec. 2.2 and 2.4; HanrahanKrueger1993).
 *
 * | option     | meaning                                                    |
 * |------------|------------------------------------------------------------|
 * | sigma_s, g | scattering coefficient and Henyey-Greenstein mean cosine   |
 * | sigma_a    | absorption                                                 |
 * | eta        | n_inside / n_outside (Fresnel at both ends, refraction)    |
 *
 * S^(1) is a distribution (the refracted incoming and outgoing rays must
 * meet), so eval returns 0 and the model answers through its observable
 * integrals, all exact up to 1D quadrature:
 * - exitance M(x_o): the beam's single-scattered light reaching x_o,
 * - radiance integrated over y: a closed form (the exit points of one
 *   outgoing direction form a line),
 * - the BRDF f_r^(1) = alpha Ft(w_i) Ft(w_o) p / (eta^2 (cos_i' + cos_o')).
 * The 1/eta^2 is the radiance change on leaving the medium (dw_inside =
 * cos_o dw / (eta^2 cos_o')); Jensen2001 writes f_r^(1) without it because
 * its eq. 6 integrates over refracted solid angles. The entry sampler draws
 * Gamma(2, sigma_t) radii, the scale of the single-scattering footprint. */
#include "bssrdf/handle.h"
#include "bssrdf/radial_model.h"
#include "subsurf/phase.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  ss_radial_sampler sampler;
  double eta;
  double sigma_s[SS_BSSRDF_CHANNELS], sigma_t[SS_BSSRDF_CHANNELS];
  ss_phase phase[SS_BSSRDF_CHANNELS];
  double mfp_min, mfp_max; /* shortest and longest 1/sigma_t */
} single;

static ss_status single_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  single *s = calloc(1, sizeof *s);
  if (!s) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "single: out of memory");
  }
  s->eta = p->eta;
  s->mfp_min = INFINITY;
  s->mfp_max = 0.0;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s->sigma_s[c] = p->medium.sigma_s.c[c];
    s->sigma_t[c] = p->medium.sigma_s.c[c] + p->medium.sigma_a.c[c];
    ss_status st = ss_phase_init(&s->phase[c], SS_PHASE_HG, p->medium.g.c[c], err);
    if (st != SS_OK) {
      free(s);
      ss_error_prefix(err, "single: ");
      return st;
    }
    double w = 1.0;
    ss_radial_mix_init(&s->sampler.ch[c], 1, &s->sigma_t[c], &w);
    s->mfp_min = fmin(s->mfp_min, 1.0 / s->sigma_t[c]);
    s->mfp_max = fmax(s->mfp_max, 1.0 / s->sigma_t[c]);
  }
  *state = s;
  return SS_OK;
}

/* Propagation direction inside for light arriving from outside along -w. */
static int refract_in(ss_vec3 w, double eta, ss_vec3 *d) {
  return w.z > 0.0 && ss_refract(w, ss_vec3_make(0, 0, 1), eta, d);
}

/* HanrahanKrueger1993 / Jensen2001 sec. 2.4, with the exit radiance factor. */
static void single_brdf(const void *state, ss_vec3 w_i, ss_vec3 w_o,
                        double out[SS_BSSRDF_CHANNELS]) {
  const single *s = state;
  ss_vec3 d_in, d_o;
  ss_channels_zero(out);
  if (!refract_in(w_i, s->eta, &d_in) || !refract_in(w_o, s->eta, &d_o)) {
    return;
  }
  ss_vec3 d_out = ss_vec3_neg(d_o); /* travelling up toward the exit */
  double cos_t = -d_in.z, cos_o = d_out.z;
  double f = ss_ft_outside(w_i.z, s->eta) * ss_ft_outside(w_o.z, s->eta) /
             (s->eta * s->eta * (cos_t + cos_o));
  double mu = ss_vec3_dot(d_in, d_out);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * s->sigma_s[c] / s->sigma_t[c] * ss_phase_eval(&s->phase[c], mu);
  }
}

typedef struct {
  const single *s;
  ss_vec3 d_in, x_o;
} beam_ctx;

/* Power scattered once at depth t along the refracted beam that leaves the
 * medium at x_o, per unit area of x_o and per unit power entering. */
static void beam_point(void *vctx, double t, double out[SS_BSSRDF_CHANNELS]) {
  const beam_ctx *b = vctx;
  ss_vec3 v = ss_vec3_sub(b->x_o, ss_vec3_scale(b->d_in, t));
  double s2 = ss_vec3_length2(v), dist = sqrt(s2);
  ss_channels_zero(out);
  if (!(dist > 0.0)) {
    return;
  }
  double cos_o = v.z / dist;
  double ft = ss_ft_inside(cos_o, b->s->eta);
  double mu = ss_vec3_dot(b->d_in, v) / dist;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double sig_t = b->s->sigma_t[c];
    out[c] = b->s->sigma_s[c] * exp(-sig_t * (t + dist)) * ss_phase_eval(&b->s->phase[c], mu) * ft *
             cos_o / s2;
  }
}

static ss_vec3 beam_direction(const single *s, double cos_i) {
  double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
  ss_vec3 d;
  if (!refract_in(ss_vec3_make(-sin_i, 0.0, cos_i), s->eta, &d)) {
    d = ss_vec3_make(0, 0, -1);
  }
  return d;
}

typedef struct {
  beam_ctx *b;
  double t0;
} shifted_ctx;

static void beam_point_shifted(void *vctx, double u, double out[SS_BSSRDF_CHANNELS]) {
  shifted_ctx *s = vctx;
  beam_point(s->b, s->t0 + u, out);
}

/* Depth along the beam beyond which the light reaching x_o arrives inside the
 * critical cone: (t cos_t)^2 = cos_c^2 |x_o - t d_in|^2, the kink of the
 * integrand (0 when there is none). */
static double critical_depth(const single *s, const beam_ctx *b) {
  if (s->eta <= 1.0) {
    return 0.0;
  }
  double cc2 = 1.0 - 1.0 / (s->eta * s->eta), ct2 = b->d_in.z * b->d_in.z;
  double r2 = ss_vec3_length2(b->x_o), xd = ss_vec3_dot(b->x_o, b->d_in);
  double qa = ct2 - cc2, qb = 2.0 * cc2 * xd, qc = -cc2 * r2;
  if (fabs(qa) < 1e-300) {
    return qb > 0.0 ? -qc / qb : 0.0;
  }
  double disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0.0) {
    return 0.0;
  }
  double t1 = (-qb + sqrt(disc)) / (2.0 * qa), t2 = (-qb - sqrt(disc)) / (2.0 * qa);
  double t = fmax(t1, t2);
  return t > 0.0 && isfinite(t) ? t : 0.0;
}

static void exitance_entered(const single *s, double cos_i, double x, double y,
                             double out[SS_BSSRDF_CHANNELS]) {
  beam_ctx b = {s, beam_direction(s, cos_i), ss_vec3_make(x, y, 0.0)};
  double r = hypot(x, y);
  double small = 0.05 * fmax(fmin(r, s->mfp_min), 1e-9 * s->mfp_min);
  double tk = critical_depth(s, &b);
  if (!(tk > 0.0)) {
    ss_vec_integrate_halfline(beam_point, &b, small, s->mfp_max, out);
    return;
  }
  double tail[SS_BSSRDF_CHANNELS];
  ss_vec_integrate_log(beam_point, &b, 0.0, tk, out);
  shifted_ctx sh = {&b, tk};
  ss_vec_integrate_halfline(beam_point_shifted, &sh, fmin(small, 0.05 * tk), s->mfp_max, tail);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] += tail[c];
  }
}

static void single_exitance(const void *state, double cos_i, double x, double y,
                            double out[SS_BSSRDF_CHANNELS]) {
  const single *s = state;
  exitance_entered(s, cos_i, x, y, out);
  double ft = ss_ft_outside(cos_i, s->eta);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] *= ft;
  }
}

/* The exit points of direction w_o lie on x = a t (t the depth parameter
 * along the beam), so int L dy at x is the line density K(t)/|a| with
 * K(t) = Ft Ft sigma_s p e^{-sigma_t t (1 + cos_t/cos_o)} / (eta^2 cos_o);
 * int K dt over all t is the BRDF. */
typedef struct {
  int ok;
  double a, rate_scale, f, mu;
} line_geometry;

static line_geometry line_setup(const single *s, double cos_i, ss_vec3 w_o) {
  line_geometry g = {0, 0.0, 0.0, 0.0, 0.0};
  ss_vec3 d_in = beam_direction(s, cos_i), d_o;
  if (!refract_in(w_o, s->eta, &d_o)) {
    return g;
  }
  ss_vec3 d_out = ss_vec3_neg(d_o);
  double cos_t = -d_in.z, cos_o = d_out.z;
  g.ok = 1;
  g.a = d_in.x + cos_t * d_out.x / cos_o;
  g.rate_scale = 1.0 + cos_t / cos_o;
  g.f = ss_ft_outside(cos_i, s->eta) * ss_ft_outside(w_o.z, s->eta) / (s->eta * s->eta * cos_o);
  g.mu = ss_vec3_dot(d_in, d_out);
  return g;
}

static void single_radiance_line(const void *state, double cos_i, double x, ss_vec3 w_o,
                                 double out[SS_BSSRDF_CHANNELS]) {
  const single *s = state;
  ss_channels_zero(out);
  line_geometry g = line_setup(s, cos_i, w_o);
  if (!g.ok || !(fabs(g.a) > 0.0) || x / g.a < 0.0) {
    return;
  }
  double t = x / g.a;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = g.f / fabs(g.a) * s->sigma_s[c] * ss_phase_eval(&s->phase[c], g.mu) *
             exp(-s->sigma_t[c] * t * g.rate_scale);
  }
}

/* Exact bin average: the x range maps to a depth range [t_lo, t_hi] (the whole
 * beam when a = 0, where every exit point is the entry point). */
static void single_radiance_bin(const void *state, double cos_i, ss_vec3 w_o, double x_lo,
                                double x_hi, double out[SS_BSSRDF_CHANNELS]) {
  const single *s = state;
  ss_channels_zero(out);
  line_geometry g = line_setup(s, cos_i, w_o);
  if (!g.ok) {
    return;
  }
  double t_lo, t_hi;
  if (fabs(g.a) < 1e-12) {
    if (!(x_lo <= 0.0 && 0.0 < x_hi)) {
      return;
    }
    t_lo = 0.0;
    t_hi = INFINITY;
  } else {
    t_lo = fmax(0.0, fmin(x_lo / g.a, x_hi / g.a));
    t_hi = fmax(x_lo / g.a, x_hi / g.a);
    if (t_hi <= t_lo) {
      return;
    }
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double k = s->sigma_t[c] * g.rate_scale;
    double mass = (exp(-k * t_lo) - (isfinite(t_hi) ? exp(-k * t_hi) : 0.0)) / k;
    out[c] = g.f * s->sigma_s[c] * ss_phase_eval(&s->phase[c], g.mu) * mass / (x_hi - x_lo);
  }
}

typedef struct {
  const single *s;
  ss_vec3 w_i;
} total_ctx;

static void brdf_cos(void *vctx, double mu, double out[SS_BSSRDF_CHANNELS]) {
  const total_ctx *t = vctx;
  double v[SS_BSSRDF_CHANNELS];
  ss_channels_zero(out);
  const int steps = 32;
  for (int k = 0; k < steps; ++k) {
    double phi = SS_PI * (k + 0.5) / steps;
    single_brdf(t->s, t->w_i, ss_spherical_direction(mu, phi), v);
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      out[c] += 2.0 * SS_PI / steps * mu * v[c];
    }
  }
}

static void single_total(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
  total_ctx t = {state, ss_vec3_make(-sin_i, 0.0, cos_i)};
  ss_vec_integrate(brdf_cos, &t, 0.0, 1.0, 4, out);
}

static void single_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const single *s = state;
  single_total(state, 1.0, out);
  double ft = ss_ft_outside(1.0, s->eta);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] /= ft;
  }
}

/* Per unit power entering at normal incidence, exit Fresnel included (the
 * E_ss convention of pbrt-v3's BeamDiffusionSS). */
static void single_profile(const void *state, int channel, double r, ss_bssrdf_profile_value *out) {
  double v[SS_BSSRDF_CHANNELS];
  exitance_entered(state, 1.0, r, 0.0, v);
  out->ss = out->value = v[channel];
}

const ss_bssrdf_ops ss_bssrdf_model_single = {
    .name = "single",
    .summary = "single scattering S^(1) and f_r^(1) (Jensen et al. 2001 sec. 2.2-2.4)",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_SINGULAR | SS_BSSRDF_ANGULAR,
    .create = single_create,
    .destroy = free,
    .eval = NULL,
    .sample_entry = ss_radial_sampler_sample_entry,
    .pdf_entry = ss_radial_sampler_pdf_entry,
    .max_radius = ss_radial_sampler_max_radius,
    .total_reflectance = single_total,
    .rd = single_rd,
    .profile = single_profile,
    .exitance = single_exitance,
    .radiance_line = single_radiance_line,
    .brdf = single_brdf,
    .radiance_bin = single_radiance_bin,
};
