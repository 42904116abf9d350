/* What a model predicts for the half-space experiment of `subsurf halfspace`
 * (docs/halfspace.md): for a unit-power beam entering at the origin, L_o(x_o, w_o) =
 * S(x_i, w_i; x_o, w_o) and M(x_o) = int S cos(theta_o) dw_o. Models may
 * provide these integrals in closed form; otherwise they are computed here
 * from the lower-level hooks with fixed Gauss-Legendre panels. */
#include "bssrdf/bssrdf_util.h"
#include "bssrdf/handle.h"

#include <math.h>
#include <string.h>

#define PHI_STEPS 16           /* midpoints on [0, pi]; exitance is even in y */
#define ORIENTED_PHI_STEPS 128 /* midpoints on [0, 2 pi] for SS_BSSRDF_ORIENTED */

void ss_vec_integrate(ss_vec_fn f, void *ctx, double a, double b, int panels,
                      double out[SS_BSSRDF_CHANNELS]) {
  ss_channels_zero(out);
  double h = (b - a) / panels, v[SS_BSSRDF_CHANNELS];
  for (int p = 0; p < panels; ++p) {
    double mid = a + (p + 0.5) * h, half = 0.5 * h;
    for (int k = 0; k < SS_GL8_N; ++k) {
      f(ctx, mid + half * ss_gl8_x[k], v);
      for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
        out[c] += ss_gl8_w[k] * half * v[c];
      }
    }
  }
}

void ss_vec_integrate_halfline(ss_vec_fn f, void *ctx, double small, double large,
                               double out[SS_BSSRDF_CHANNELS]) {
  double part[SS_BSSRDF_CHANNELS];
  ss_vec_integrate(f, ctx, 0.0, small, 1, out);
  double end = 64.0 * fmax(large, small);
  for (double a = small; a < end; a *= 2.0) {
    ss_vec_integrate(f, ctx, a, 2.0 * a, 1, part);
    ss_channels_add(out, part);
  }
}

void ss_vec_integrate_log(ss_vec_fn f, void *ctx, double a, double b,
                          double out[SS_BSSRDF_CHANNELS]) {
  double part[SS_BSSRDF_CHANNELS];
  ss_channels_zero(out);
  if (!(b > a)) {
    return;
  }
  if (a <= 0.0) {
    a = b / 64.0;
    ss_vec_integrate(f, ctx, 0.0, a, 1, part);
    ss_channels_add(out, part);
  }
  int panels = (int)ceil(log2(b / a));
  if (panels < 1) {
    panels = 1;
  }
  double ratio = pow(b / a, 1.0 / panels), lo = a;
  for (int p = 0; p < panels; ++p) {
    double hi = p == panels - 1 ? b : lo * ratio;
    ss_vec_integrate(f, ctx, lo, hi, 1, part);
    ss_channels_add(out, part);
    lo = hi;
  }
}

void ss_bssrdf_observe_init(ss_bssrdf *b) {
  double small = INFINITY, large = 0.0;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double st = b->params.medium.sigma_s.c[c] + b->params.medium.sigma_a.c[c];
    double stp = (1.0 - b->params.medium.g.c[c]) * b->params.medium.sigma_s.c[c] +
                 b->params.medium.sigma_a.c[c];
    small = fmin(small, 0.05 / fmax(st, stp));
    double rmax = b->ops->max_radius ? b->ops->max_radius(b->state, c) : 0.0;
    if (!(rmax > 0.0) || !isfinite(rmax)) {
      rmax = 1e4 / stp;
    }
    large = fmax(large, rmax);
  }
  b->small_scale = small;
  b->large_scale = large;
}

ss_bssrdf_query ss_bssrdf_halfspace_query(double cos_i, double x, double y, ss_vec3 w_o) {
  double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
  ss_bssrdf_query q;
  q.x_i = ss_vec3_make(0.0, 0.0, 0.0);
  q.n_i = ss_vec3_make(0.0, 0.0, 1.0);
  q.w_i = ss_vec3_make(-sin_i, 0.0, cos_i);
  q.x_o = ss_vec3_make(x, y, 0.0);
  q.n_o = q.n_i;
  q.w_o = w_o;
  return q;
}

/* --- exitance: int S cos(theta_o) dw_o over the outside hemisphere ---- */

typedef struct {
  const ss_bssrdf *b;
  double cos_i, x, y;
  ss_vec3 w_o;
} point_ctx;

static void exitance_phi(void *vctx, double mu, double out[SS_BSSRDF_CHANNELS]) {
  point_ctx *p = vctx;
  ss_channels_zero(out);
  double v[SS_BSSRDF_CHANNELS];
  const int steps = 24;
  for (int k = 0; k < steps; ++k) {
    double phi = 2.0 * SS_PI * (k + 0.5) / steps;
    ss_bssrdf_query q =
        ss_bssrdf_halfspace_query(p->cos_i, p->x, p->y, ss_spherical_direction(mu, phi));
    ss_bssrdf_eval(p->b, &q, v);
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      out[c] += v[c] * mu * 2.0 * SS_PI / steps;
    }
  }
}

void ss_bssrdf_exitance(const ss_bssrdf *b, double cos_i, double x, double y,
                        double out[SS_BSSRDF_CHANNELS]) {
  if (ss_bssrdf_in_tail(hypot(x, y))) {
    ss_channels_zero(out);
    return;
  }
  if (b->ops->exitance) {
    b->ops->exitance(b->state, cos_i, x, y, out);
    return;
  }
  if (b->ops->flags & (SS_BSSRDF_BRDF | SS_BSSRDF_SINGULAR)) {
    ss_channels_zero(out);
    return;
  }
  point_ctx p = {b, cos_i, x, y, ss_vec3_make(0, 0, 1)};
  ss_vec_integrate(exitance_phi, &p, 0.0, 1.0, 2, out);
}

/* --- radiance integrated over y --------------------------------------- */

static void eval_at_y(void *vctx, double y, double out[SS_BSSRDF_CHANNELS]) {
  point_ctx *p = vctx;
  ss_bssrdf_query q = ss_bssrdf_halfspace_query(p->cos_i, p->x, y, p->w_o);
  ss_bssrdf_eval(p->b, &q, out);
}

static void eval_at_minus_y(void *vctx, double y, double out[SS_BSSRDF_CHANNELS]) {
  eval_at_y(vctx, -y, out);
}

void ss_bssrdf_radiance_line(const ss_bssrdf *b, double cos_i, double x, ss_vec3 w_o,
                             double out[SS_BSSRDF_CHANNELS]) {
  if (ss_bssrdf_in_tail(x)) {
    ss_channels_zero(out);
    return;
  }
  if (b->ops->radiance_line) {
    b->ops->radiance_line(b->state, cos_i, x, w_o, out);
    return;
  }
  if (b->ops->flags & (SS_BSSRDF_BRDF | SS_BSSRDF_SINGULAR)) {
    ss_channels_zero(out);
    return;
  }
  point_ctx p = {b, cos_i, x, 0.0, w_o};
  double neg[SS_BSSRDF_CHANNELS];
  ss_vec_integrate_halfline(eval_at_y, &p, b->small_scale, b->large_scale, out);
  ss_vec_integrate_halfline(eval_at_minus_y, &p, b->small_scale, b->large_scale, neg);
  ss_channels_add(out, neg);
}

/* --- integrals over the plane ----------------------------------------- */

/* r times the azimuthal integral of the exitance at radius r. */
static void exitance_ring(void *vctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  point_ctx *p = vctx;
  double v[SS_BSSRDF_CHANNELS];
  ss_channels_zero(out);
  if (ss_bssrdf_flags(p->b) & SS_BSSRDF_ORIENTED) {
    /* An oriented medium: neither radial nor even in y; the midpoint rule is
     * spectrally accurate for the smooth periodic integrand. */
    for (int k = 0; k < ORIENTED_PHI_STEPS; ++k) {
      double phi = 2.0 * SS_PI * (k + 0.5) / ORIENTED_PHI_STEPS;
      ss_bssrdf_exitance(p->b, p->cos_i, r * cos(phi), r * sin(phi), v);
      for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
        out[c] += 2.0 * SS_PI / ORIENTED_PHI_STEPS * r * v[c];
      }
    }
    return;
  }
  if (p->cos_i >= 1.0) {
    /* Normal incidence on an isotropic half-space is radially symmetric. */
    ss_bssrdf_exitance(p->b, p->cos_i, r, 0.0, v);
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      out[c] = 2.0 * SS_PI * r * v[c];
    }
    return;
  }
  for (int k = 0; k < PHI_STEPS; ++k) {
    double phi = SS_PI * (k + 0.5) / PHI_STEPS;
    ss_bssrdf_exitance(p->b, p->cos_i, r * cos(phi), r * sin(phi), v);
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      out[c] += 2.0 * SS_PI / PHI_STEPS * r * v[c];
    }
  }
}

typedef struct {
  const ss_bssrdf *b;
  ss_vec3 w_i, w_o;
} brdf_ctx;

static void brdf_cos_mu(void *vctx, double mu, double out[SS_BSSRDF_CHANNELS]) {
  brdf_ctx *p = vctx;
  double v[SS_BSSRDF_CHANNELS];
  ss_channels_zero(out);
  const int steps = 24;
  for (int k = 0; k < steps; ++k) {
    ss_vec3 w_o = ss_spherical_direction(mu, 2.0 * SS_PI * (k + 0.5) / steps);
    ss_bssrdf_brdf(p->b, p->w_i, w_o, v);
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      out[c] += v[c] * mu * 2.0 * SS_PI / steps;
    }
  }
}

void ss_bssrdf_total_reflectance(const ss_bssrdf *b, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  if (b->ops->total_reflectance) {
    b->ops->total_reflectance(b->state, cos_i, out);
    return;
  }
  if (b->ops->flags & SS_BSSRDF_BRDF) {
    double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
    brdf_ctx p = {b, ss_vec3_make(-sin_i, 0.0, cos_i), ss_vec3_make(0, 0, 1)};
    ss_vec_integrate(brdf_cos_mu, &p, 0.0, 1.0, 2, out);
    return;
  }
  point_ctx p = {b, cos_i, 0.0, 0.0, ss_vec3_make(0, 0, 1)};
  ss_vec_integrate_halfline(exitance_ring, &p, b->small_scale, b->large_scale, out);
}

/* r times the azimuthal integral of S over exit points on the ring r. */
static void eval_ring(void *vctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  brdf_ctx *p = vctx;
  double v[SS_BSSRDF_CHANNELS];
  ss_channels_zero(out);
  const int steps = 2 * PHI_STEPS;
  for (int k = 0; k < steps; ++k) {
    double phi = 2.0 * SS_PI * (k + 0.5) / steps;
    ss_bssrdf_query q;
    q.x_i = ss_vec3_make(0, 0, 0);
    q.n_i = q.n_o = ss_vec3_make(0, 0, 1);
    q.w_i = p->w_i;
    q.x_o = ss_vec3_make(r * cos(phi), r * sin(phi), 0.0);
    q.w_o = p->w_o;
    ss_bssrdf_eval(p->b, &q, v);
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      out[c] += 2.0 * SS_PI / steps * r * v[c];
    }
  }
}

void ss_bssrdf_brdf(const ss_bssrdf *b, ss_vec3 w_i, ss_vec3 w_o, double out[SS_BSSRDF_CHANNELS]) {
  if (b->ops->brdf) {
    b->ops->brdf(b->state, w_i, w_o, out);
    return;
  }
  if (b->ops->flags & (SS_BSSRDF_BRDF | SS_BSSRDF_SINGULAR)) {
    ss_channels_zero(out);
    return;
  }
  brdf_ctx p = {b, w_i, w_o};
  ss_vec_integrate_halfline(eval_ring, &p, b->small_scale, b->large_scale, out);
}

/* --- the binned observables of `subsurf halfspace` -------------------- */

void ss_bssrdf_radial_average(const ss_bssrdf *b, double cos_i, double r_lo, double r_hi,
                              double out[SS_BSSRDF_CHANNELS]) {
  double area = SS_PI * (r_hi * r_hi - r_lo * r_lo);
  if (b->ops->flags & SS_BSSRDF_BRDF) {
    /* A BRDF sends all its exitance out at the entry point. */
    if (r_lo <= 0.0) {
      ss_bssrdf_total_reflectance(b, cos_i, out);
      for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
        out[c] /= area;
      }
    } else {
      ss_channels_zero(out);
    }
    return;
  }
  point_ctx p = {b, cos_i, 0.0, 0.0, ss_vec3_make(0, 0, 1)};
  ss_vec_integrate_log(exitance_ring, &p, r_lo, r_hi, out);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] /= area;
  }
}

static void radiance_line_at(void *vctx, double x, double out[SS_BSSRDF_CHANNELS]) {
  point_ctx *p = vctx;
  ss_bssrdf_radiance_line(p->b, p->cos_i, x, p->w_o, out);
}

static void radiance_line_at_minus(void *vctx, double x, double out[SS_BSSRDF_CHANNELS]) {
  radiance_line_at(vctx, -x, out);
}

void ss_bssrdf_direction_average(const ss_bssrdf *b, double cos_i, ss_vec3 w_o, double x_lo,
                                 double x_hi, double out[SS_BSSRDF_CHANNELS]) {
  double width = x_hi - x_lo;
  if (b->ops->radiance_bin) {
    b->ops->radiance_bin(b->state, cos_i, w_o, x_lo, x_hi, out);
    return;
  }
  if (b->ops->flags & SS_BSSRDF_BRDF) {
    ss_channels_zero(out);
    if (x_lo <= 0.0 && 0.0 < x_hi) {
      double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
      ss_bssrdf_brdf(b, ss_vec3_make(-sin_i, 0.0, cos_i), w_o, out);
      for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
        out[c] /= width;
      }
    }
    return;
  }
  point_ctx p = {b, cos_i, 0.0, 0.0, w_o};
  if (x_lo < 0.0 && x_hi > 0.0) {
    /* Profiles peak at the entry point: integrate each side of it. */
    double left[SS_BSSRDF_CHANNELS];
    ss_vec_integrate_log(radiance_line_at, &p, 0.0, x_hi, out);
    ss_vec_integrate_log(radiance_line_at_minus, &p, 0.0, -x_lo, left);
    ss_channels_add(out, left);
  } else {
    ss_vec_integrate(radiance_line_at, &p, x_lo, x_hi, 2, out);
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] /= width;
  }
}
