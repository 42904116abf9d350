/* Micro-flake distributions, their projected areas and the specular
 * micro-flake phase function (Jakob2010 sec. 4). */
#include "subsurf/microflake.h"

#include "optics/microflake_sample.h"

#include "subsurf/quadrature.h"
#include "subsurf/sampling.h"
#include "subsurf/table_index.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define QUAD_PANELS 4 /* 8-point panels per segment of the theta_m integral */
#define PHI_PANELS 1  /* per side of the kink of the azimuthal integral (1e-7 relative) */

double ss_microflake_albedo(const ss_microflake *mf, double cos_wm) {
  const ss_flake_albedo *a = &mf->albedo;
  if (ss_flake_albedo_is_constant(a)) {
    return a->alpha1;
  }
  return a->alpha0 + (a->alpha1 - a->alpha0) * pow(fabs(cos_wm), a->k);
}

/* D as a function of u = m.v. */
static double flake_D_of_u(const ss_microflake *mf, double u) {
  switch (mf->type) {
  case SS_FLAKE_SURFACE:
    return mf->norm * pow(fabs(u), mf->p);
  case SS_FLAKE_FIBER: {
    double s2 = 1.0 - u * u;
    return s2 > 0.0 ? mf->norm * pow(s2, 0.5 * mf->p) : (mf->p == 0.0 ? mf->norm : 0.0);
  }
  case SS_FLAKE_UNIFORM:
  default:
    return mf->norm;
  }
}

double ss_microflake_D(const ss_microflake *mf, ss_vec3 m) {
  return flake_D_of_u(mf, ss_vec3_dot(m, mf->frame.n));
}

/* int_0^{2 pi} |a cos(phi) + b| dphi for a >= 0: 2 pi |b| when the
 * cosine term cannot change the sign, else, with phi0 = acos(-b/a) where it
 * does, 4 sqrt(a^2 - b^2) + 4 b phi0 - 2 pi b. */
static double abs_cosine_azimuth(double a, double b) {
  if (fabs(b) >= a) {
    return 2.0 * SS_PI * fabs(b);
  }
  double phi0 = acos(-b / a);
  return 4.0 * sqrt(a * a - b * b) + 4.0 * b * phi0 - 2.0 * SS_PI * b;
}

typedef struct {
  const ss_microflake *mf;
  double s, c;   /* w = (s, 0, c) in the axis frame */
  double a, b;   /* w.m = a cos(phi) + b at the current u */
  int component; /* scattered_mean_integrand: 0 the axis's, 1 across it */
} area_ctx;

static double weighted_cosine(void *vctx, double phi) {
  area_ctx *x = vctx;
  double wm = fabs(x->a * cos(phi) + x->b);
  return ss_microflake_albedo(x->mf, wm) * wm;
}

/* int_0^{2 pi} alpha(|w.m|) |w.m| dphi, split where w.m changes sign. */
static double albedo_cosine_azimuth(area_ctx *x) {
  if (fabs(x->b) >= x->a) {
    return 2.0 * ss_gl_integrate(weighted_cosine, x, 0.0, SS_PI, 2 * PHI_PANELS);
  }
  double phi0 = acos(-x->b / x->a);
  return 2.0 * (ss_gl_integrate(weighted_cosine, x, 0.0, phi0, PHI_PANELS) +
                ss_gl_integrate(weighted_cosine, x, phi0, SS_PI, PHI_PANELS));
}

static double area_integrand(void *vctx, double u, int with_albedo) {
  area_ctx *x = vctx;
  double r = sqrt(fmax(0.0, 1.0 - u * u));
  x->a = x->s * r;
  x->b = x->c * u;
  double azimuth = with_albedo ? albedo_cosine_azimuth(x) : abs_cosine_azimuth(x->a, x->b);
  return flake_D_of_u(x->mf, u) * azimuth;
}

/* Over theta_m, u = cos(theta_m): the sqrt(1 - u^2) of the azimuthal
 * integral becomes sin(theta_m), smooth where D peaks at the poles. */
static double area_t_integrand(void *vctx, double theta) {
  return area_integrand(vctx, cos(theta), 0) * sin(theta);
}
static double area_s_integrand(void *vctx, double theta) {
  return area_integrand(vctx, cos(theta), 1) * sin(theta);
}

static int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Integrates over theta_m in [0, pi] in segments that end where the
 * integrand has a kink (|cos theta_m| = s, where w.m starts to change sign
 * over the azimuth; the equator for a non-integer p) and around the peaks
 * of D (width about 1/sqrt(p) at the poles or at the equator). */
static double integrate_over_flakes_ctx(area_ctx *x, ss_scalar_fn f) {
  double width = fmin(0.25 * SS_PI, 3.0 / sqrt(x->mf->p + 1.0)), kink = acos(fmin(x->s, 1.0));
  double edges[10] = {0.0,   kink,          0.5 * SS_PI,         SS_PI - kink,        SS_PI,
                      width, SS_PI - width, 0.5 * SS_PI - width, 0.5 * SS_PI + width, SS_PI};
  qsort(edges, 10, sizeof edges[0], compare_doubles);
  double total = 0.0;
  for (int i = 0; i + 1 < 10; ++i) {
    if (edges[i + 1] - edges[i] > 1e-12) {
      total += ss_gl_integrate(f, x, edges[i], edges[i + 1], QUAD_PANELS);
    }
  }
  return total;
}

static double integrate_over_flakes(const ss_microflake *mf, double c, ss_scalar_fn f) {
  area_ctx x = {.mf = mf, .c = c, .s = sqrt(fmax(0.0, 1.0 - c * c))};
  return integrate_over_flakes_ctx(&x, f);
}

double ss_microflake_sigma_t_quadrature(const ss_microflake *mf, double c) {
  return integrate_over_flakes(mf, fabs(c), area_t_integrand);
}

double ss_microflake_sigma_s_quadrature(const ss_microflake *mf, double c) {
  if (ss_flake_albedo_is_constant(&mf->albedo)) {
    return mf->albedo.alpha1 * ss_microflake_sigma_t_quadrature(mf, c);
  }
  return integrate_over_flakes(mf, fabs(c), area_s_integrand);
}

/* int_0^{2 pi} (w.m) |w.m| (1, cos phi) dphi with w.m = f(phi) = a cos(phi)
 * + b, a >= 0, in closed form: with one sign throughout, sgn(b) times
 * int f^2 = pi (a^2 + 2 b^2) and int f^2 cos = 2 pi a b; else, f > 0 for
 * |phi| < phi0 = acos(-b/a), 2 (2 F(phi0) - F(pi)) with F(phi) = int_0^phi
 * of f^2 or f^2 cos. */
static void signed_square_azimuth(double a, double b, double out[2]) {
  if (fabs(b) >= a) {
    double sign = b < 0.0 ? -1.0 : 1.0;
    out[0] = sign * SS_PI * (a * a + 2.0 * b * b);
    out[1] = sign * 2.0 * SS_PI * a * b;
    return;
  }
  double p = acos(-b / a), sp = sin(p), s2p = sin(2.0 * p);
  double f2 = a * a * (0.5 * p + 0.25 * s2p) + 2.0 * a * b * sp + b * b * p;
  double f2c = a * a * (sp - sp * sp * sp / 3.0) + a * b * (p + 0.5 * s2p) + b * b * sp;
  out[0] = 2.0 * (2.0 * f2 - SS_PI * (0.5 * a * a + b * b));
  out[1] = 2.0 * (2.0 * f2c - SS_PI * a * b);
}

static double signed_albedo_square(void *vctx, double phi) {
  area_ctx *x = vctx;
  double wm = x->a * cos(phi) + x->b;
  return ss_microflake_albedo(x->mf, wm) * wm * fabs(wm) * (x->component ? cos(phi) : 1.0);
}

/* int_0^{2 pi} alpha(|w.m|) (w.m) |w.m| (1 or cos phi) dphi, split where w.m
 * changes sign (the azimuth's even part: the sin phi terms vanish). */
static double signed_albedo_square_azimuth(area_ctx *x) {
  if (fabs(x->b) >= x->a) {
    return 2.0 * ss_gl_integrate(signed_albedo_square, x, 0.0, SS_PI, 4 * PHI_PANELS);
  }
  double phi0 = acos(-x->b / x->a);
  return 2.0 * (ss_gl_integrate(signed_albedo_square, x, 0.0, phi0, 2 * PHI_PANELS) +
                ss_gl_integrate(signed_albedo_square, x, phi0, SS_PI, 2 * PHI_PANELS));
}

/* The component (axis or across) of int alpha (w.m) |w.m| m D(m) dm over
 * the azimuth at theta_m: m = (r cos phi, r sin phi, u), times sin theta_m. */
static double scattered_mean_integrand(void *vctx, double theta) {
  area_ctx *x = vctx;
  double u = cos(theta), r = sin(theta), az;
  x->a = x->s * r;
  x->b = x->c * u;
  if (ss_flake_albedo_is_constant(&x->mf->albedo)) {
    double both[2];
    signed_square_azimuth(x->a, x->b, both);
    az = x->mf->albedo.alpha1 * both[x->component];
  } else {
    az = signed_albedo_square_azimuth(x);
  }
  return flake_D_of_u(x->mf, u) * az * (x->component ? r : u) * r;
}

ss_vec3 ss_microflake_scattered_mean(const ss_microflake *mf, ss_vec3 w) {
  ss_vec3 wl = ss_frame_to_local(mf->frame, w);
  double s = sqrt(wl.x * wl.x + wl.y * wl.y),
         scattered = ss_microflake_sigma_s_quadrature(mf, wl.z);
  if (!(scattered > 0.0)) {
    return ss_vec3_make(0.0, 0.0, 0.0);
  }
  /* Jakob2010 eq. 13's phase function: a flake m visible from w (weight
   * alpha(|w.m|) |w.m| D(m)) reflects w into w - 2 (w.m) m, so
   * g = w - 2 int alpha (w.m) |w.m| m D dm / int alpha |w.m| D dm */
  double J[2];
  for (int k = 0; k < 2; ++k) {
    area_ctx x = {.mf = mf, .s = s, .c = wl.z, .component = k};
    J[k] = integrate_over_flakes_ctx(&x, scattered_mean_integrand);
  }
  ss_vec3 across = s > 0.0 ? ss_vec3_make(wl.x / s, wl.y / s, 0.0) : ss_vec3_make(1.0, 0.0, 0.0);
  /* int alpha (w.m) |w.m| m D dm, from its components along z and across */
  ss_vec3 m_integral = ss_vec3_add(ss_vec3_scale(across, J[1]), ss_vec3_make(0.0, 0.0, J[0]));
  ss_vec3 g = ss_vec3_sub(wl, ss_vec3_scale(m_integral, 2.0 / scattered));
  return ss_frame_to_world(mf->frame, g);
}

void ss_microflake_tabulate_scattered_mean(ss_microflake *mf) {
  for (int i = 0; i <= SS_MICROFLAKE_MEAN; ++i) {
    double theta = 0.5 * SS_PI * i / SS_MICROFLAKE_MEAN, s = sin(theta);
    /* w = (s, 0, c) in the axis frame: g = (s mean_across, 0, mean_along) */
    ss_vec3 w = ss_frame_to_world(mf->frame, ss_vec3_make(s, 0.0, cos(theta)));
    ss_vec3 g = ss_frame_to_local(mf->frame, ss_microflake_scattered_mean(mf, w));
    mf->mean_along[i] = g.z;
    mf->mean_across[i] = s > 0.0 ? g.x / s : 0.0;
  }
  /* On the axis the across ratio is its limit: it is even in theta, so
   * (4 f(h) - f(2h)) / 3 to second order. */
  mf->mean_across[0] = (4.0 * mf->mean_across[1] - mf->mean_across[2]) / 3.0;
  mf->mean_tabulated = 1;
}

ss_vec3 ss_microflake_scattered_mean_lookup(const ss_microflake *mf, ss_vec3 w) {
  if (!mf->mean_tabulated) {
    return ss_microflake_scattered_mean(mf, w);
  }
  ss_vec3 v = mf->frame.n;
  double c = ss_vec3_dot(w, v);
  double ti = acos(fmin(fabs(c), 1.0)) * (2.0 * SS_MICROFLAKE_MEAN / SS_PI);
  int i = ss_table_cell_clamped(ti, SS_MICROFLAKE_MEAN);
  double t = ti - i;
  double along = mf->mean_along[i] + t * (mf->mean_along[i + 1] - mf->mean_along[i]);
  double across = mf->mean_across[i] + t * (mf->mean_across[i + 1] - mf->mean_across[i]);
  return ss_vec3_add(ss_vec3_scale(v, c < 0.0 ? -along : along),
                     ss_vec3_scale(ss_vec3_sub(w, ss_vec3_scale(v, c)), across));
}

double ss_microflake_sigma_t(const ss_microflake *mf, ss_vec3 w) {
  return ss_microflake_table_at(mf->sigma_t, ss_vec3_dot(w, mf->frame.n));
}

double ss_microflake_sigma_s(const ss_microflake *mf, ss_vec3 w) {
  return ss_microflake_table_at(mf->sigma_s, ss_vec3_dot(w, mf->frame.n));
}

double ss_microflake_sigma_max(const ss_microflake *mf) {
  double smax = 0.0;
  for (int i = 0; i < SS_MICROFLAKE_TABLE; ++i) {
    smax = fmax(smax, mf->sigma_t[i]);
  }
  return smax;
}

double ss_microflake_collision_albedo(const ss_microflake *mf, ss_vec3 w) {
  return ss_microflake_collision_albedo_at(mf, ss_vec3_dot(w, mf->frame.n));
}

/* The two factors of the visible-normal envelope as functions of |u|. */
static double along_of_u(const ss_microflake *mf, double u) { return u * flake_D_of_u(mf, u); }
static double across_of_u(const ss_microflake *mf, double u) {
  return sqrt(fmax(0.0, 1.0 - u * u)) * flake_D_of_u(mf, u);
}

static double beta_fn(double a, double b) { return exp(lgamma(a) + lgamma(b) - lgamma(a + b)); }

/* Walker's alias method (Vose's construction, Vose 1991): column j of n
 * equally likely columns keeps cell j with probability keep[j] and gives
 * its alias otherwise, so that cell k comes out with probability
 * bound[k] / sum(bound). */
static void build_alias(ss_flake_envelope *e, double total) {
  const int n = SS_MICROFLAKE_ENVELOPE;
  double q[SS_MICROFLAKE_ENVELOPE];
  int small[SS_MICROFLAKE_ENVELOPE], large[SS_MICROFLAKE_ENVELOPE], ns = 0, nl = 0;
  for (int k = 0; k < n; ++k) {
    q[k] = e->bound[k] * n / total;
    e->keep[k] = 1.0;
    e->alias[k] = k;
    if (q[k] < 1.0) {
      small[ns++] = k;
    } else {
      large[nl++] = k;
    }
  }
  while (ns > 0 && nl > 0) {
    int lo = small[--ns], hi = large[--nl];
    e->keep[lo] = q[lo];
    e->alias[lo] = hi;
    q[hi] = (q[hi] + q[lo]) - 1.0;
    if (q[hi] < 1.0) {
      small[ns++] = hi;
    } else {
      large[nl++] = hi;
    }
  }
  /* Columns left on either list keep their own cell (rounding leftovers). */
  for (int k = 0; k < n; ++k) {
    e->inv_keep[k] = e->keep[k] > 0.0 ? 1.0 / e->keep[k] : 0.0;
    e->inv_rest[k] = e->keep[k] < 1.0 ? 1.0 / (1.0 - e->keep[k]) : 0.0;
  }
}

/* Bounds each cell by its end values and, in the cell holding it, the value
 * at the function's only interior maximum `peak` (< 0: none). The functions
 * here, |u| D and r D, are |u|^a (1 - u^2)^b up to a factor, with a, b >= 0
 * for both types of flakes, so they are log-concave: over a cell, log f
 * lies above its chord, so f(t) >= G exp((t - 1/2) L) >= G (1 + (t - 1/2) L)
 * at the position t in [0, 1] across the cell, with G = sqrt(f0 f1) and
 * L = log(f1 / f0) (exp(x) >= 1 + x). That line is the squeeze, below f by
 * at most G L^2 / 8 (0.1 % of f for surface-like flakes of p = 20 near the
 * axis), lowered by 1e-9 of itself against rounding (f's relative rounding
 * error is under 1e-12 for p <= 1000). In the half-space walk with those
 * flakes, f is evaluated on 4.4 % of the draws (those the bound rejects,
 * 4.0 %, and a few more), against 8.2 % with the smaller end value as the
 * squeeze. */
static void build_envelope(const ss_microflake *mf, ss_flake_envelope *e,
                           double (*f)(const ss_microflake *, double), double peak,
                           double integral) {
  const int n = SS_MICROFLAKE_ENVELOPE;
  const double lowered = 1.0 - 1e-9;
  double total = 0.0;
  for (int k = 0; k < n; ++k) {
    double u0 = (double)k / n, u1 = (double)(k + 1) / n;
    double f0 = f(mf, u0), f1 = f(mf, u1), hi = fmax(f0, f1);
    if (peak > u0 && peak < u1) {
      hi = fmax(hi, f(mf, peak));
    }
    e->bound[k] = hi;
    /* Where f vanishes at an end (or is subnormal there, where its
     * rounding is no longer relative), no line but 0 is safely below it. */
    e->squeeze[k] = 0.0;
    e->squeeze_slope[k] = 0.0;
    if (f0 >= DBL_MIN && f1 >= DBL_MIN) {
      double g = lowered * sqrt(f0) * sqrt(f1), l = log(f1 / f0);
      e->squeeze[k] = g * (1.0 - 0.5 * l);
      e->squeeze_slope[k] = g * l;
    }
    total += hi;
  }
  build_alias(e, total);
  e->integral = integral;
}

/* The envelopes and their exact integrals over [0, 1] (norm times):
 * int |u| D = 1/(p + 2) for both types; int r D = B((p + 1)/2, 3/2)/2
 * (surface-like, with its maximum at u^2 = p/(p + 1)) or B(1/2, (p + 3)/2)/2
 * (fibre-like, whose |u| D peaks at u^2 = 1/(p + 1)). Uniform flakes are
 * surface-like with p = 0. */
static void build_envelopes(ss_microflake *mf) {
  double p = mf->p, along_peak = -1.0, across_peak = -1.0, across_integral;
  if (mf->type == SS_FLAKE_FIBER) {
    along_peak = p > 0.0 ? 1.0 / sqrt(p + 1.0) : -1.0;
    across_integral = 0.5 * beta_fn(0.5, 0.5 * (p + 3.0));
  } else {
    across_peak = p > 0.0 ? sqrt(p / (p + 1.0)) : -1.0;
    across_integral = 0.5 * beta_fn(0.5 * (p + 1.0), 1.5);
  }
  build_envelope(mf, &mf->along, along_of_u, along_peak, mf->norm / (p + 2.0));
  build_envelope(mf, &mf->across, across_of_u, across_peak, mf->norm * across_integral);
}

double ss_flake_envelope_value(const ss_microflake *mf, const ss_flake_envelope *e, double u) {
  return e == &mf->across ? across_of_u(mf, u) : along_of_u(mf, u);
}

ss_vec3 ss_microflake_sample_visible_normal(const ss_microflake *mf, ss_vec3 w, ss_rng *rng) {
  double wm;
  ss_vec3 m = ss_microflake_sample_flake(mf, ss_frame_to_local(mf->frame, w), rng, &wm);
  m = ss_rng_uniform(rng) < 0.5 ? m : ss_vec3_neg(m);
  return ss_frame_to_world(mf->frame, m);
}

ss_vec3 ss_microflake_sample_phase(const ss_microflake *mf, ss_vec3 w_in, ss_rng *rng) {
  ss_vec3 o = ss_microflake_sample_phase_local(mf, ss_frame_to_local(mf->frame, w_in), rng);
  return ss_frame_to_world(mf->frame, o);
}

/* Jakob2010 eq. 13: f_p = alpha(|w'.h|) [D(h) + D(-h)] /
 * (4 sigma_s(w')) per unit density, h the half vector of the reflection. */
double ss_microflake_phase_eval(const ss_microflake *mf, ss_vec3 w_in, ss_vec3 w_out) {
  ss_vec3 h = ss_vec3_sub(w_out, w_in);
  double len = ss_vec3_length(h);
  if (len < 1e-12) {
    return 0.0;
  }
  h = ss_vec3_scale(h, 1.0 / len);
  double d = ss_microflake_D(mf, h) + ss_microflake_D(mf, ss_vec3_neg(h));
  double sigma_s = ss_microflake_sigma_s(mf, w_in);
  return ss_microflake_albedo(mf, ss_vec3_dot(w_in, h)) * d / (4.0 * sigma_s);
}

/* 1 / int D over the sphere: surface 4 pi / (p + 1); fibre
 * 2 pi B(1/2, p/2 + 1) = 2 pi sqrt(pi) Gamma(p/2 + 1) / Gamma(p/2 + 3/2). */
static double flake_norm(ss_flake_type type, double p) {
  switch (type) {
  case SS_FLAKE_SURFACE:
    return (p + 1.0) / (4.0 * SS_PI);
  case SS_FLAKE_FIBER:
    return 1.0 / (2.0 * SS_PI * sqrt(SS_PI) * exp(lgamma(0.5 * p + 1.0) - lgamma(0.5 * p + 1.5)));
  case SS_FLAKE_UNIFORM:
  default:
    return 1.0 / (4.0 * SS_PI);
  }
}

/* The distribution's own parameters, shared by init and the medium check. */
static ss_status validate_distribution(ss_flake_type type, double p, ss_vec3 axis, ss_error *err) {
  if (type != SS_FLAKE_UNIFORM && type != SS_FLAKE_SURFACE && type != SS_FLAKE_FIBER) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "flakes: the distribution must be uniform, surface or fiber");
  }
  if (type != SS_FLAKE_UNIFORM && !(p >= 0.0 && p <= 1000.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "flake-p: the flake exponent must be in [0, 1000] (got %g)", p);
  }
  double len = ss_vec3_length(axis);
  if (!isfinite(len) || !(len > 1e-12)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "medium-axis: the flake axis must be a finite non-zero vector (got "
                        "%g,%g,%g)",
                        axis.x, axis.y, axis.z);
  }
  return SS_OK;
}

ss_status ss_microflake_init(ss_microflake *mf, ss_flake_type type, double p, ss_vec3 axis,
                             ss_flake_albedo albedo, ss_error *err) {
  memset(mf, 0, sizeof *mf);
  ss_status st = validate_distribution(type, p, axis, err);
  if (st != SS_OK) {
    return st;
  }
  if (type == SS_FLAKE_UNIFORM) {
    p = 0.0;
  }
  if (!(albedo.alpha0 >= 0.0 && albedo.alpha0 <= 1.0 && albedo.alpha1 >= 0.0 &&
        albedo.alpha1 <= 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "the flake albedo must be in [0, 1] (got %g and %g)", albedo.alpha0,
                        albedo.alpha1);
  }
  if (!(albedo.k >= 0.0 && albedo.k <= 100.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "the flake albedo exponent must be in [0, 100] (got %g)", albedo.k);
  }
  double len = ss_vec3_length(axis);
  mf->type = type;
  mf->p = p;
  mf->frame = ss_frame_from_normal(ss_vec3_scale(axis, 1.0 / len));
  mf->norm = flake_norm(type, p);
  mf->albedo = albedo;
  /* The fine table's entries at x = i FINE_X / FINE, then the coarse one's
   * at x = i / COARSE (microflake.h), x = 1 - |w.v|. */
  for (int i = 0; i < SS_MICROFLAKE_TABLE; ++i) {
    int fine = i <= SS_MICROFLAKE_FINE, j = fine ? i : i - (SS_MICROFLAKE_FINE + 1);
    double x =
        fine ? j * (SS_MICROFLAKE_FINE_X / SS_MICROFLAKE_FINE) : (double)j / SS_MICROFLAKE_COARSE;
    mf->sigma_t[i] = ss_microflake_sigma_t_quadrature(mf, 1.0 - x);
    /* A constant albedo scales sigma (what the quadrature would return). */
    mf->sigma_s[i] = ss_flake_albedo_is_constant(&albedo)
                         ? albedo.alpha1 * mf->sigma_t[i]
                         : ss_microflake_sigma_s_quadrature(mf, 1.0 - x);
  }
  build_envelopes(mf);
  return SS_OK;
}

ss_status ss_medium_flakes_check(const ss_medium_flakes *flakes, ss_error *err) {
  if (flakes->type == SS_FLAKE_NONE) {
    return SS_OK;
  }
  ss_status st = validate_distribution(flakes->type, flakes->p, flakes->axis, err);
  if (st != SS_OK) {
    return st;
  }
  if (!(flakes->albedo_falloff >= 0.0 && flakes->albedo_falloff <= 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "flake-albedo-falloff: must be in [0, 1] (got %g)", flakes->albedo_falloff);
  }
  if (!(flakes->albedo_exponent >= 0.0 && flakes->albedo_exponent <= 100.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "flake-albedo-exponent: must be in [0, 100] (got %g)",
                        flakes->albedo_exponent);
  }
  return SS_OK;
}

ss_status ss_microflake_init_medium(ss_microflake *mf, const ss_medium_flakes *flakes,
                                    double albedo, ss_error *err) {
  ss_status st = ss_medium_flakes_check(flakes, err);
  if (st != SS_OK) {
    return st;
  }
  if (flakes->type == SS_FLAKE_NONE) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "the medium has no flakes");
  }
  ss_flake_albedo a = {albedo * (1.0 - flakes->albedo_falloff), albedo, flakes->albedo_exponent};
  return ss_microflake_init(mf, flakes->type, flakes->p, flakes->axis, a, err);
}

int ss_flake_type_from_name(const char *name, ss_flake_type *type) {
  static const struct {
    const char *name;
    ss_flake_type type;
  } names[] = {{"none", SS_FLAKE_NONE},
               {"uniform", SS_FLAKE_UNIFORM},
               {"surface", SS_FLAKE_SURFACE},
               {"fiber", SS_FLAKE_FIBER}};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
    if (strcmp(name, names[i].name) == 0) {
      *type = names[i].type;
      return 1;
    }
  }
  return 0;
}

const char *ss_flake_type_name(ss_flake_type type) {
  switch (type) {
  case SS_FLAKE_SURFACE:
    return "surface";
  case SS_FLAKE_FIBER:
    return "fiber";
  case SS_FLAKE_UNIFORM:
    return "uniform";
  case SS_FLAKE_NONE:
  default:
    return "none";
  }
}
