/* Importance sampling for the forward scattering dipole (subsurf/fwddip.h;
 * derivations in docs/fwddip.md). */
#include "subsurf/fwddip.h"

#include "bssrdf/fwddip_model.h"
#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"

#include <gsl/gsl_cdf.h>

#include <math.h>
#include <string.h>

/* Mixture weights: cosine lobe, then vMF lobes of growing concentration. */
#define LOBES 4
static const double lobe_weight[LOBES] = {0.4, 0.2, 0.2, 0.2};
static const double lobe_kappa[LOBES] = {0.0, 8.0, 64.0, 512.0};

/* von Mises-Fisher density on the sphere about mu:
 * kappa e^{kappa (w.mu - 1)} / (2 pi (1 - e^{-2 kappa})). */
static double vmf_pdf(double kappa, double cos_mu) {
  return kappa * exp(kappa * (cos_mu - 1.0)) / (2.0 * SS_PI * -expm1(-2.0 * kappa));
}

/* Inverse cdf of w.mu: 1 + log(u + (1 - u) e^{-2 kappa}) / kappa. */
static ss_vec3 vmf_sample(double kappa, ss_vec3 mu, double u1, double u2) {
  double c = 1.0 + log1p(-u1 * -expm1(-2.0 * kappa)) / kappa;
  c = fmax(-1.0, fmin(1.0, c));
  ss_vec3 local = ss_spherical_direction(c, 2.0 * SS_PI * u2);
  return ss_frame_to_world(ss_frame_from_normal(mu), local);
}

static ss_vec3 mirror(ss_vec3 w_i) { return ss_vec3_make(-w_i.x, -w_i.y, w_i.z); }

static int is_brdf(const ss_bssrdf *b) { return !strcmp(ss_bssrdf_name(b), "fwddip-brdf"); }

static double mixture_pdf(ss_vec3 w_i, ss_vec3 w_o) {
  double pdf = lobe_weight[0] * (w_o.z > 0.0 ? ss_pdf_cosine_hemisphere(w_o.z) : 0.0);
  double c = ss_vec3_dot(w_o, mirror(w_i));
  for (int k = 1; k < LOBES; ++k) {
    pdf += lobe_weight[k] * vmf_pdf(lobe_kappa[k], c);
  }
  return pdf;
}

int ss_fwddip_brdf_sample(const ss_bssrdf *b, ss_vec3 w_i, double u1, double u2, ss_vec3 *w_o,
                          double *pdf) {
  if (!is_brdf(b)) {
    return 0;
  }
  /* u1 picks the lobe and is rescaled to drive that lobe's polar angle. */
  int k = 0;
  double acc = lobe_weight[0];
  while (k + 1 < LOBES && u1 >= acc) {
    u1 -= acc;
    acc = lobe_weight[++k];
  }
  u1 = fmin(u1 / lobe_weight[k], 1.0 - 1e-16);
  *w_o =
      k == 0 ? ss_sample_cosine_hemisphere(u1, u2) : vmf_sample(lobe_kappa[k], mirror(w_i), u1, u2);
  *pdf = mixture_pdf(w_i, *w_o);
  return *pdf > 0.0;
}

double ss_fwddip_brdf_pdf(const ss_bssrdf *b, ss_vec3 w_i, ss_vec3 w_o) {
  return is_brdf(b) ? mixture_pdf(w_i, w_o) : 0.0;
}

/* --- eq. 16: path length and entry direction (fwddip) ---------------- */

static const ss_fwddip_state *fwddip_state(const ss_bssrdf *b, int channel) {
  return !strcmp(ss_bssrdf_name(b), "fwddip") && channel >= 0 && channel < SS_BSSRDF_CHANNELS
             ? ss_bssrdf_state(b)
             : NULL;
}

/* Eq. 11 as a density in x = ps: x^{-3/2} e^{-B/x - A x}, B = 3 (p d)^2 / 2
 * and A = sigma_a / p: the inverse Gaussian IG(mu = sqrt(B/A), lambda = 2B),
 * normalised sqrt(B/pi) x^{-3/2} e^{-B/x - A x + 2 sqrt(A B)}; A = 0 is the
 * Levy law. B is floored at the value for d = 1/(10 p) so that the density
 * stays proper at d = 0. */
typedef struct {
  double A, B;
  double s0, sigma; /* the log-normal: median and log-width */
} length_law;

static length_law length_law_make(const ss_fwddip_medium *m, double dist) {
  length_law L;
  double pd = fmax(m->p * dist, 0.1);
  L.A = m->sigma_a / m->p;
  L.B = 1.5 * pd * pd;
  /* Eq. 10: the ballistic peak sits just beyond s = d with a relative width
   * ~ sqrt(pd)/2; the log-normal is a little wider, and keeps a floor of
   * 0.05 and a ceiling of 1. */
  L.s0 = fmax(dist, 1e-3 / m->p);
  L.sigma = fmin(1.0, fmax(0.05, sqrt(m->p * L.s0)));
  return L;
}

/* With both directions known (the next-event branch), eq. 10's Gaussian
 * |R/s - (w + w')/2|^2 is smallest at s* = |R|^2 / (R . w_bar) and has a
 * relative width sqrt(p s*) s* / (3 |R|) there; the log-normal takes twice
 * that (floor 0.02, ceiling 1). Without a forward alignment (R . w_bar <=
 * |R| |w_bar| / 10) it is the undirected law. */
static length_law length_law_directed(const ss_fwddip_medium *m, ss_vec3 R, ss_vec3 wo_e,
                                      ss_vec3 wi_e) {
  double dist = ss_vec3_length(R);
  length_law L = length_law_make(m, dist);
  ss_vec3 w_bar = ss_vec3_scale(ss_vec3_add(wo_e, wi_e), 0.5);
  double rw = ss_vec3_dot(R, w_bar);
  if (dist * m->p > 1e-3 && rw > 0.1 * dist * ss_vec3_length(w_bar)) {
    L.s0 = dist * dist / rw;
    L.sigma = fmin(1.0, fmax(0.02, 2.0 * sqrt(m->p * L.s0) * L.s0 / (3.0 * dist)));
  }
  return L;
}

static double inverse_gaussian_pdf(const length_law *L, double x) {
  if (!(x > 0.0)) {
    return 0.0;
  }
  return sqrt(L->B / SS_PI) * pow(x, -1.5) * exp(-L->B / x - L->A * x + 2.0 * sqrt(L->A * L->B));
}

/* Michael, Schucany & Haas 1976 from a normal quantile and one uniform. */
static double inverse_gaussian_sample(const length_law *L, double u_normal, double u_accept) {
  double nu = gsl_cdf_ugaussian_Pinv(u_normal), y = nu * nu;
  if (L->A <= 0.0) {
    return 2.0 * L->B / fmax(y, 1e-300); /* Levy: x = c/nu^2, c = 2B */
  }
  double mu = sqrt(L->B / L->A), lambda = 2.0 * L->B;
  double x = mu + mu * mu * y / (2.0 * lambda) -
             mu / (2.0 * lambda) * sqrt(4.0 * mu * lambda * y + mu * mu * y * y);
  return u_accept <= mu / (mu + x) ? x : mu * mu / x;
}

static double lognormal_pdf(const length_law *L, double s) {
  if (!(s > 0.0)) {
    return 0.0;
  }
  double t = log(s / L->s0) / L->sigma;
  return exp(-0.5 * t * t) / (s * L->sigma * sqrt(2.0 * SS_PI));
}

static double length_pdf(const ss_fwddip_medium *m, const length_law *L, double s) {
  return 0.5 * m->p * inverse_gaussian_pdf(L, m->p * s) + 0.5 * lognormal_pdf(L, s);
}

static int sample_law(const ss_fwddip_medium *m, const length_law *L, double u1, double u2,
                      double *s, double *pdf) {
  double v = u1 < 0.5 ? 2.0 * u1 : 2.0 * u1 - 1.0;
  v = fmin(fmax(v, 1e-300), 1.0 - 1e-16);
  *s = u1 < 0.5 ? inverse_gaussian_sample(L, v, u2) / m->p
                : L->s0 * exp(L->sigma * gsl_cdf_ugaussian_Pinv(v));
  *pdf = length_pdf(m, L, *s);
  return isfinite(*s) && *pdf > 0.0;
}

int ss_fwddip_sample_length(const ss_bssrdf *b, int channel, double dist, double u1, double u2,
                            double *s, double *pdf) {
  const ss_fwddip_state *st = fwddip_state(b, channel);
  if (!st) {
    return 0;
  }
  length_law L = length_law_make(&st->m[channel], dist);
  return sample_law(&st->m[channel], &L, u1, u2, s, pdf);
}

double ss_fwddip_pdf_length(const ss_bssrdf *b, int channel, double dist, double s) {
  const ss_fwddip_state *st = fwddip_state(b, channel);
  if (!st) {
    return 0.0;
  }
  length_law L = length_law_make(&st->m[channel], dist);
  return length_pdf(&st->m[channel], &L, s);
}

int ss_fwddip_sample_length_directed(const ss_bssrdf *b, int channel, ss_vec3 x_o, ss_vec3 wo_e,
                                     ss_vec3 x_i, ss_vec3 wi_e, double u1, double u2, double *s,
                                     double *pdf) {
  const ss_fwddip_state *st = fwddip_state(b, channel);
  if (!st) {
    return 0;
  }
  length_law L = length_law_directed(&st->m[channel], ss_vec3_sub(x_o, x_i), wo_e, wi_e);
  return sample_law(&st->m[channel], &L, u1, u2, s, pdf);
}

double ss_fwddip_pdf_length_directed(const ss_bssrdf *b, int channel, ss_vec3 x_o, ss_vec3 wo_e,
                                     ss_vec3 x_i, ss_vec3 wi_e, double s) {
  const ss_fwddip_state *st = fwddip_state(b, channel);
  if (!st) {
    return 0.0;
  }
  length_law L = length_law_directed(&st->m[channel], ss_vec3_sub(x_o, x_i), wo_e, wi_e);
  return length_pdf(&st->m[channel], &L, s);
}

/* The axis h = E p (x_o - x_i) - D w_o^e of eq. 9's exponential in w'. */
static ss_vec3 direction_axis(const ss_fwddip_medium *m, double s, ss_vec3 x_o, ss_vec3 wo_e,
                              ss_vec3 x_i) {
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(m->p * s, &k);
  return ss_vec3_sub(ss_vec3_scale(ss_vec3_sub(x_o, x_i), k.E * m->p), ss_vec3_scale(wo_e, k.D));
}

int ss_fwddip_sample_direction(const ss_bssrdf *b, int channel, double s, ss_vec3 x_o, ss_vec3 wo_e,
                               ss_vec3 x_i, double u1, double u2, ss_vec3 *wi_e, double *pdf) {
  const ss_fwddip_state *st = fwddip_state(b, channel);
  if (!st) {
    return 0;
  }
  ss_vec3 h = direction_axis(&st->m[channel], s, x_o, wo_e, x_i);
  double kappa = ss_vec3_length(h);
  if (!(kappa > 1e-12)) {
    *wi_e = ss_sample_uniform_sphere(u1, u2);
    *pdf = ss_pdf_uniform_sphere();
    return 1;
  }
  *wi_e = vmf_sample(kappa, ss_vec3_scale(h, 1.0 / kappa), u1, u2);
  *pdf = vmf_pdf(kappa, ss_vec3_dot(*wi_e, h) / kappa);
  return *pdf > 0.0;
}

double ss_fwddip_pdf_direction(const ss_bssrdf *b, int channel, double s, ss_vec3 x_o, ss_vec3 wo_e,
                               ss_vec3 x_i, ss_vec3 wi_e) {
  const ss_fwddip_state *st = fwddip_state(b, channel);
  if (!st) {
    return 0.0;
  }
  ss_vec3 h = direction_axis(&st->m[channel], s, x_o, wo_e, x_i);
  double kappa = ss_vec3_length(h);
  return kappa > 1e-12 ? vmf_pdf(kappa, ss_vec3_dot(wi_e, h) / kappa) : ss_pdf_uniform_sphere();
}

/* --- eq. 16: the ballistic entry strategy (fwddip) -------------------- */

/* Light that leaves x_o toward w_o travelled, unscattered, along w_o^e =
 * -refract(w_o); eq. 10's peak sits on the line back along it. The renderer
 * traces from x_o along a direction drawn about refract(w_o) (into the
 * medium) from a mixture of von Mises-Fisher lobes of concentration
 * 1, 8, 64, 512 (weights 1/4): the angular spread of eq. 10, ~sqrt(ps), is
 * unknown before the distance is, and the broad lobe keeps the density
 * positive on the whole sphere. */
#define BALLISTIC_LOBES 4
static const double ballistic_kappa[BALLISTIC_LOBES] = {1.0, 8.0, 64.0, 512.0};

static int ballistic_axis(const ss_bssrdf *b, ss_vec3 n_o, ss_vec3 w_o, ss_vec3 *mu) {
  return fwddip_state(b, 0) && ss_vec3_dot(w_o, n_o) > 0.0 &&
         ss_refract(w_o, n_o, ss_bssrdf_get_params(b)->eta, mu);
}

static double ballistic_pdf(ss_vec3 mu, ss_vec3 d) {
  double c = ss_vec3_dot(mu, d), pdf = 0.0;
  for (int k = 0; k < BALLISTIC_LOBES; ++k) {
    pdf += vmf_pdf(ballistic_kappa[k], c) / BALLISTIC_LOBES;
  }
  return pdf;
}

double ss_fwddip_ballistic_fraction(const ss_bssrdf *b) {
  const ss_fwddip_state *st = fwddip_state(b, 0);
  return st ? st->cfg.ballistic : 0.0;
}

int ss_fwddip_sample_ballistic(const ss_bssrdf *b, ss_vec3 n_o, ss_vec3 w_o, double u1, double u2,
                               double u3, ss_vec3 *d, double *pdf) {
  ss_vec3 mu;
  if (!ballistic_axis(b, n_o, w_o, &mu)) {
    return 0;
  }
  int k = (int)(u1 * BALLISTIC_LOBES);
  k = k < BALLISTIC_LOBES ? k : BALLISTIC_LOBES - 1;
  *d = vmf_sample(ballistic_kappa[k], mu, u2, u3);
  *pdf = ballistic_pdf(mu, *d);
  return *pdf > 0.0;
}

double ss_fwddip_pdf_ballistic(const ss_bssrdf *b, ss_vec3 n_o, ss_vec3 w_o, ss_vec3 d) {
  ss_vec3 mu;
  return ballistic_axis(b, n_o, w_o, &mu) ? ballistic_pdf(mu, d) : 0.0;
}
