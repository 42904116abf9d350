#include "subsurf/gwc.h"

#include "subsurf/sampling.h"

#include <math.h>

const double ss_gwc_anchor_cos[3] = {0.9530, 0.4050, -0.7527};

/* Ferrier2016 sec. 3.2: pdf_WC = (1 - c^2) / (2 pi (1 + c^2 - 2 c cos phi)). */
double ss_wc_pdf(double phi, double c) {
  return (1.0 - c * c) / (2.0 * SS_PI * (1.0 + c * c - 2.0 * c * cos(phi)));
}

/* Ferrier2016 sec. 4.2: 1/2 + atan(((1 + c)/(1 - c)) tan(phi/2)) / pi, with
 * atan2 so that phi = +-pi gives exactly 1 and 0. */
double ss_wc_cdf(double phi, double c) {
  double h = 0.5 * phi;
  return 0.5 + atan2((1.0 + c) * sin(h), (1.0 - c) * cos(h)) * SS_INV_PI;
}

/* Ferrier2016 sec. 4.2: 2 atan(((1 - c)/(1 + c)) tan(pi (u - 1/2))). */
double ss_wc_inv_cdf(double u, double c) {
  double h = SS_PI * (u - 0.5);
  return 2.0 * atan2((1.0 - c) * sin(h), (1.0 + c) * cos(h));
}

double ss_gwc_eval(const ss_gwc *g, double phi) {
  return g->alpha + g->beta * ss_wc_pdf(phi, g->c);
}

double ss_gwc_integral(const ss_gwc *g) { return 2.0 * SS_PI * g->alpha + g->beta; }

static double c_from_a(double a) { return a - sqrt(a * a - 1.0); }

/* With c fixed, alpha and beta through anchors i and j exactly; alpha < 0
 * is clamped to 0 with beta through anchor i. */
static void fit_linear2(double c, const double *x, const double *f, int i, int j, ss_gwc *g) {
  g->c = c;
  if (c == 0.0) {
    g->alpha = 0.0;
    g->beta = 2.0 * SS_PI * (f[0] + f[1] + f[2]) / 3.0;
    return;
  }
  double pi_ = ss_wc_pdf(acos(x[i]), c), pj = ss_wc_pdf(acos(x[j]), c);
  g->beta = (f[i] - f[j]) / (pi_ - pj);
  g->alpha = f[i] - g->beta * pi_;
  if (g->alpha < 0.0 || g->beta < 0.0) {
    g->alpha = 0.0;
    g->beta = f[i] / pi_;
  }
}

ss_gwc_fit_kind ss_gwc_fit3(const double cos_phi[3], const double f[3], ss_gwc *out) {
  const double *x = cos_phi;
  double a_min = (1.0 + SS_GWC_C_MAX * SS_GWC_C_MAX) / (2.0 * SS_GWC_C_MAX);
  /* Ferrier2016 sec. 3.3 (docs/tables.md): k and K, the slopes' ratios of the geometry and the
   * data. */
  double k = (x[0] - x[1]) / (x[1] - x[2]);
  /* Flat or exactly linear in cos(phi) (K = k up to rounding): a GWC with
   * c -> 0 has no unique (alpha, beta). */
  if (f[1] == f[2] || fabs((f[0] - f[1]) - k * (f[1] - f[2])) <= 1e-12 * fabs(f[0] - f[1])) {
    out->c = 0.0;
    out->alpha = 0.0;
    out->beta = 2.0 * SS_PI * f[0];
    return SS_GWC_FIT_FLAT;
  }
  double K = (f[0] - f[1]) / (f[1] - f[2]);
  if (K < k) {
    /* Data flatter than linear in cos(phi) (or peaked backwards): the
     * nearest GWC is the c -> 0 limit. */
    fit_linear2(0.0, x, f, 0, 2, out);
    return SS_GWC_FIT_CLAMPED_C;
  }
  double a = (K * x[0] - k * x[2]) / (K - k);
  if (!(a >= a_min)) {
    /* Sharper than the largest concentration allowed (a <= 1 when
     * K >= k (1 - x_3)/(1 - x_1)). */
    fit_linear2(SS_GWC_C_MAX, x, f, 0, 2, out);
    return SS_GWC_FIT_CLAMPED_C;
  }
  double b = sqrt(a * a - 1.0);
  /* Ferrier2016 sec. 3.3 with its beta corrected (docs/tables.md): beta and alpha
   * through anchors 1 and 2. */
  double beta = 2.0 * SS_PI * (f[0] - f[1]) / (b * (1.0 / (a - x[0]) - 1.0 / (a - x[1])));
  double alpha = f[0] - beta * b / (2.0 * SS_PI * (a - x[0]));
  if (!(beta > 0.0)) {
    /* Increasing toward phi = pi: no forward lobe to fit. */
    fit_linear2(0.0, x, f, 0, 2, out);
    return SS_GWC_FIT_CLAMPED_C;
  }
  if (alpha >= 0.0) {
    out->c = c_from_a(a);
    out->alpha = alpha;
    out->beta = beta;
    return SS_GWC_FIT_EXACT;
  }
  /* alpha = 0: a pure Wrapped Cauchy through anchors 1 and 3,
   * f_1 / f_3 = (a - x_3) / (a - x_1). */
  out->alpha = 0.0;
  double a2 = (f[0] * x[0] - f[2] * x[2]) / (f[0] - f[2]);
  if (!(a2 > a_min)) {
    a2 = a_min;
  }
  double b2 = sqrt(a2 * a2 - 1.0);
  out->c = c_from_a(a2);
  out->beta = 2.0 * SS_PI * f[0] * (a2 - x[0]) / b2;
  return SS_GWC_FIT_CLAMPED_ALPHA;
}

/* Weighted residual of the best (alpha >= 0, beta >= 0) for fixed c. */
static double lsq_at(size_t n, const double *phi, const double *f, const double *w, double c,
                     ss_gwc *g) {
  double s00 = 0, s01 = 0, s11 = 0, t0 = 0, t1 = 0;
  for (size_t j = 0; j < n; ++j) {
    double p = ss_wc_pdf(phi[j], c), wj = w ? w[j] : 1.0;
    s00 += wj;
    s01 += wj * p;
    s11 += wj * p * p;
    t0 += wj * f[j];
    t1 += wj * p * f[j];
  }
  double det = s00 * s11 - s01 * s01;
  double alpha = det > 0.0 ? (t0 * s11 - t1 * s01) / det : 0.0;
  double beta = det > 0.0 ? (s00 * t1 - s01 * t0) / det : t1 / s11;
  if (alpha < 0.0 || det <= 0.0) {
    alpha = 0.0;
    beta = t1 / s11;
  }
  if (beta < 0.0) {
    beta = 0.0;
    alpha = t0 / s00;
  }
  g->alpha = alpha;
  g->beta = beta;
  g->c = c;
  double res = 0.0;
  for (size_t j = 0; j < n; ++j) {
    double d = alpha + beta * ss_wc_pdf(phi[j], c) - f[j];
    res += (w ? w[j] : 1.0) * d * d;
  }
  return res;
}

void ss_gwc_fit_lsq(size_t n, const double *phi, const double *f, const double *w, ss_gwc *g) {
  /* Coarse scan of c, then golden-section refinement around the best
   * bracket (the residual is smooth and unimodal in practice). */
  enum { SCAN = 24 };
  double best = INFINITY, best_c = 0.0;
  for (int i = 0; i <= SCAN; ++i) {
    double c = SS_GWC_C_MAX * i / SCAN;
    ss_gwc t;
    double r = lsq_at(n, phi, f, w, c, &t);
    if (r < best) {
      best = r;
      best_c = c;
    }
  }
  double lo = fmax(0.0, best_c - SS_GWC_C_MAX / SCAN);
  double hi = fmin(SS_GWC_C_MAX, best_c + SS_GWC_C_MAX / SCAN);
  const double gr = 0.6180339887498949;
  double c1 = hi - gr * (hi - lo), c2 = lo + gr * (hi - lo);
  ss_gwc t;
  double r1 = lsq_at(n, phi, f, w, c1, &t), r2 = lsq_at(n, phi, f, w, c2, &t);
  for (int it = 0; it < 40; ++it) {
    if (r1 < r2) {
      hi = c2;
      c2 = c1;
      r2 = r1;
      c1 = hi - gr * (hi - lo);
      r1 = lsq_at(n, phi, f, w, c1, &t);
    } else {
      lo = c1;
      c1 = c2;
      r1 = r2;
      c2 = lo + gr * (hi - lo);
      r2 = lsq_at(n, phi, f, w, c2, &t);
    }
  }
  double c = 0.5 * (lo + hi);
  if (lsq_at(n, phi, f, w, c, &t) <= best) {
    *g = t;
  } else {
    lsq_at(n, phi, f, w, best_c, g);
  }
}

double ss_gwc_pdf(const ss_gwc *g, double phi) { return ss_gwc_eval(g, phi) / ss_gwc_integral(g); }

/* Ferrier2016 sec. 4.2: (alpha (phi + pi) + beta cdf_WC) / (2 pi alpha + beta). */
double ss_gwc_cdf(const ss_gwc *g, double phi) {
  return (g->alpha * (phi + SS_PI) + g->beta * ss_wc_cdf(phi, g->c)) / ss_gwc_integral(g);
}

/* Both azimuthal models are mixtures of two Wrapped Cauchy lobes (the GWC's
 * uniform part is the lobe c = 0), and with tau = tan(phi/2) a Wrapped Cauchy
 * lobe is a Cauchy distribution of scale s = (1 - c)/(1 + c): its CDF is
 * 1/2 + atan(tau/s)/pi (Ferrier2016 sec. 4.2). Inverting the CDF at u means
 * solving w1 atan(tau/s1) + w2 atan(tau/s2) = pi |u - 1/2| for tau >= 0.
 *
 * The unknown is the angle psi = atan(tau/s_a) of the lobe a with the larger
 * weight, in which the equation reads
 *   G(psi) = w_a psi + w_b atan(rho tan psi) = y,  rho = s_a/s_b,
 * linear when the lobes are alike and increasing wherever the density is
 * non-negative (G' is the density per unit psi). The start is the quantile
 * of one Cauchy whose scale runs from the mixture's at the centre
 * (1/s = sum w_k/s_k, matching the density at phi = 0) to its tail scale
 * (s = sum w_k s_k, matching the mass near phi = pi). Fourth-order steps,
 * kept inside a bisection bracket, stop once the error they leave is
 * estimated below tolerance: one CDF evaluation for 2/3 of a table's
 * samples, two for the rest. Steps update cos psi, sin psi, the other lobe's
 * angle and phi/2 by rotation, with Taylor series for the small angles, so
 * only the start calls atan (three times). Accuracy: |G - y| <= 1e-13 (CDF
 * error < 4e-14). */
typedef struct {
  double wa, wb, ca, cb; /* weights (wa >= 1/2, wa + wb = 1) and concentrations */
} lobe_pair;

/* atan z, by series near 0: z P(z^2) with terms up to z^13 for |z| <= 0.05
 * (next term z^15/15 < 1e-19 z), fewer for |z| <= 0.03 (z^11/11 < 1e-16 z)
 * and |z| <= 1e-3 (z^7/7 < 1e-19 z), in Estrin's form, whose dependency
 * chain is shorter than Horner's; atan() beyond. */
static double atan_small(double z) {
  double w = z * z, w2 = w * w;
  if (w <= 1e-6) {
    return z * ((1.0 - w * (1.0 / 3.0)) + w2 * (1.0 / 5.0));
  }
  double lo = (1.0 - w * (1.0 / 3.0)) + w2 * (1.0 / 5.0 - w * (1.0 / 7.0));
  if (w <= 9e-4) {
    return z * (lo + w2 * w2 * (1.0 / 9.0));
  }
  if (w > 2.5e-3) {
    return atan(z);
  }
  double hi = (1.0 / 9.0 - w * (1.0 / 11.0)) + w2 * (1.0 / 13.0);
  return z * (lo + w2 * w2 * hi);
}

/* sin d and cos d for |d| <= 0.1 (next terms < 1e-18), fewer terms for
 * |d| <= 1e-3 (next terms < 1e-20); Estrin's form. */
static void sincos_small(double d, double *sd, double *cd) {
  double w = d * d, w2 = w * w;
  if (w <= 1e-6) {
    *sd = d * ((1.0 - w * (1.0 / 6.0)) + w2 * (1.0 / 120.0));
    *cd = (1.0 - 0.5 * w) + w2 * (1.0 / 24.0);
    return;
  }
  *sd = d * (((1.0 - w * (1.0 / 6.0)) + w2 * (1.0 / 120.0 - w * (1.0 / 5040.0))) +
             w2 * w2 * (1.0 / 362880.0));
  *cd = ((1.0 - 0.5 * w) + w2 * (1.0 / 24.0 - w * (1.0 / 720.0))) +
        w2 * w2 * (1.0 / 40320.0 - w * (1.0 / 3628800.0));
}

/* tau = tan(phi/2) >= 0 with sum_k w_k atan(tau/s_k) = y, y in [0, pi/2],
 * x = pi/2 - y computed without cancellation by the caller; returns
 * phi/2 = atan(tau), tracked alongside psi like psi_b. */
static double lobes_invert(const lobe_pair *m, double y, double x) {
  /* u = 0 is phi = -pi for every model (G(pi/2) = pi/2). */
  if (x == 0.0) {
    return 0.5 * SS_PI;
  }
  double wa = m->wa, wb = m->wb;
  double pa = 1.0 - m->ca, qa = 1.0 + m->ca, pb = 1.0 - m->cb, qb = 1.0 + m->cb; /* s = p/q */
  /* The start: tau = s(y) tan y, s(y) = s_centre cos^2 y + s_tail sin^2 y,
   * with cos y = sin x, sin y = cos x from short series: the start need
   * not be exact, only the state (psi, cos psi, sin psi, psi_b, phi/2)
   * derived from it consistent. x >= 1e-200 keeps cos y a normal number.
   * The divisions are independent: s_a, rho = s_a/s_b, s_centre/s_a =
   * 1/(w_a + w_b rho), s_tail/s_a = w_a + w_b/rho and 1/cos y. */
  x = fmax(x, 1e-200);
  double x2 = x * x;
  double cy = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0))));
  double sy = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0))));
  double sa = pa / qa, rho = pa * qb / (qa * pb), inv_cy = 1.0 / cy;
  double r_centre = qa * pb / (wa * qa * pb + wb * pa * qb);
  double r_tail = wa + wb * qa * pb / (pa * qb);
  double ta = (r_centre * cy * cy + r_tail * sy * sy) * sy * inv_cy; /* tan psi = tau / s_a */
  double c = 1.0 / ta, s = 1.0;
  if (ta < 1e8) {
    c = 1.0 / sqrt(1.0 + ta * ta);
    s = ta * c;
  }
  double psi = atan(ta), psib = atan(rho * ta), half = atan(sa * ta);
  double rho2 = rho * rho, sa2 = sa * sa;
  double lo = 0.0, hi = 0.5 * SS_PI;
  for (int it = 0; it < 60; ++it) {
    double g = wa * psi + wb * psib - y;
    if (fabs(g) <= 1e-13) {
      break;
    }
    if (g < 0.0) {
      lo = psi;
    } else {
      hi = psi;
    }
    /* G' = P/D, G'' = Q/D^2, G''' = R/D^3 from theta = atan(rho tan psi):
     * theta' = rho/D, D = c^2 + rho^2 s^2, D' = 2 c s (rho^2 - 1),
     * D'' = 2 (rho^2 - 1)(c^2 - s^2). The step inverts the cubic Taylor
     * polynomial of G: -h (1 + A h + (2 A^2 - B) h^2), h = g/G',
     * A = G''/(2 G'), B = G'''/(6 G'), leaving an error ~ 10 K^3 h^4 with
     * K = 1 + |A| + sqrt|B| (the n-th derivative of an analytic function
     * grows like n! K^n): below 1e-14 in G the iteration stops there. */
    double cs = c * s, d = c * c + rho2 * s * s;
    double d1 = 2.0 * cs * (rho2 - 1.0), d2 = 2.0 * (rho2 - 1.0) * (c * c - s * s);
    double p = wa * d + wb * rho, q = -wb * rho * d1, r = wb * rho * (2.0 * d1 * d1 - d2 * d);
    double inv_d = 1.0 / d, inv_p = 1.0 / p;
    double h = g * d * inv_p, a = 0.5 * q * inv_d * inv_p;
    double b = r * inv_d * inv_d * inv_p * (1.0 / 6.0);
    double step = -h * (1.0 + h * (a + h * (2.0 * a * a - b)));
    double next = psi + step;
    int bisect = !(next >= lo && next <= hi);
    if (bisect) {
      next = 0.5 * (lo + hi);
      step = next - psi;
    }
    if (fabs(step) <= 0.1) {
      /* Rotate (c, s) by the step; psi_b and phi/2 move by
       * atan(k sin(step) / (c c' + k^2 s s')), k = rho and s_a. */
      double sd, cd;
      sincos_small(step, &sd, &cd);
      double c2 = c * cd - s * sd, s2 = s * cd + c * sd;
      double cc = c * c2, ss = s * s2;
      double zb = rho * sd / (cc + rho2 * ss), z0 = sa * sd / (cc + sa2 * ss);
      psib += atan_small(zb);
      half += atan_small(z0);
      c = c2;
      s = s2;
    } else {
      c = cos(next);
      s = sin(next);
      psib = atan(rho * s / c);
      half = atan(sa * s / c);
    }
    psi = next;
    double k = 1.0 + fabs(a) + sqrt(fabs(b)), h2 = h * h;
    if (!bisect && 10.0 * k * k * k * h2 * h2 * p * inv_d <= 1e-14) {
      break;
    }
  }
  return half;
}

/* The inverse CDF of lambda WC(c1) + (1 - lambda) WC(c2) at u in [0, 1). */
static double two_lobe_invert(double lambda, double c1, double c2, double u) {
  lobe_pair m = lambda >= 0.5 ? (lobe_pair){lambda, 1.0 - lambda, c1, c2}
                              : (lobe_pair){1.0 - lambda, lambda, c2, c1};
  double y = SS_PI * (u - 0.5);
  double half = lobes_invert(&m, fabs(y), SS_PI * fmin(u, 1.0 - u));
  return y < 0.0 ? -2.0 * half : 2.0 * half;
}

double ss_gwc_sample(const ss_gwc *g, double u) {
  /* alpha is the lobe c = 0 with weight 2 pi alpha. */
  return two_lobe_invert(g->beta / ss_gwc_integral(g), g->c, 0.0, u);
}

double ss_wc2_pdf(const ss_wc2 *m, double phi) {
  return m->lambda * ss_wc_pdf(phi, m->c1) + (1.0 - m->lambda) * ss_wc_pdf(phi, m->c2);
}

double ss_wc2_cdf(const ss_wc2 *m, double phi) {
  return m->lambda * ss_wc_cdf(phi, m->c1) + (1.0 - m->lambda) * ss_wc_cdf(phi, m->c2);
}

double ss_wc2_sample(const ss_wc2 *m, double u) {
  return two_lobe_invert(m->lambda, m->c1, m->c2, u);
}

double ss_wc2_lambda_max(double c1, double c2) {
  /* g(pi) = lambda P1(pi) + (1 - lambda) P2(pi) >= 0, P(pi; c) = (1-c)/(2 pi (1+c)). */
  double p1 = (1.0 - c1) / (1.0 + c1), p2 = (1.0 - c2) / (1.0 + c2);
  return p2 > p1 ? p2 / (p2 - p1) : 1.0;
}

#define WC2_MAX_POINTS 64
#define WC2_GRID 14

/* Best lambda for fixed lobes (values p1, p2 at the azimuths) and its
 * weighted squared residual. */
static double wc2_residual(size_t n, const double *p1, const double *p2, const double *h,
                           const double *w, double lambda_max, double *lambda) {
  double sdd = 0.0, sdy = 0.0;
  for (size_t j = 0; j < n; ++j) {
    double d = p1[j] - p2[j];
    sdd += w[j] * d * d;
    sdy += w[j] * d * (h[j] - p2[j]);
  }
  double l = sdd > 0.0 ? fmin(lambda_max, fmax(0.0, sdy / sdd)) : 1.0;
  double res = 0.0;
  for (size_t j = 0; j < n; ++j) {
    double e = l * p1[j] + (1.0 - l) * p2[j] - h[j];
    res += w[j] * e * e;
  }
  *lambda = l;
  return res;
}

static void wc_values(size_t n, const double *cos_phi, double c, double *p) {
  double k = (1.0 - c * c) / (2.0 * SS_PI);
  for (size_t j = 0; j < n; ++j) {
    p[j] = k / (1.0 + c * c - 2.0 * c * cos_phi[j]);
  }
}

static double wc2_try(size_t n, const double *cos_phi, const double *h, const double *w, double c1,
                      double c2, double *lambda) {
  double p1[WC2_MAX_POINTS], p2[WC2_MAX_POINTS];
  wc_values(n, cos_phi, c1, p1);
  wc_values(n, cos_phi, c2, p2);
  return wc2_residual(n, p1, p2, h, w, ss_wc2_lambda_max(c1, c2), lambda);
}

void ss_wc2_fit(size_t n, const double *phi, const double *h, const double *w, ss_wc2 *m) {
  double cos_phi[WC2_MAX_POINTS], grid[WC2_GRID + 1][WC2_MAX_POINTS];
  if (n > WC2_MAX_POINTS) {
    n = WC2_MAX_POINTS;
  }
  for (size_t j = 0; j < n; ++j) {
    cos_phi[j] = cos(phi[j]);
  }
  for (int i = 0; i <= WC2_GRID; ++i) {
    wc_values(n, cos_phi, SS_GWC_C_MAX * i / WC2_GRID, grid[i]);
  }
  /* Grid over 0 <= c2 <= c1 <= C_MAX, then a pattern search. */
  double best = INFINITY, b1 = 0.0, b2 = 0.0, bl = 1.0, l;
  for (int i = 0; i <= WC2_GRID; ++i) {
    for (int k = 0; k <= i; ++k) {
      double c1 = SS_GWC_C_MAX * i / WC2_GRID, c2 = SS_GWC_C_MAX * k / WC2_GRID;
      double r = wc2_residual(n, grid[i], grid[k], h, w, ss_wc2_lambda_max(c1, c2), &l);
      if (r < best) {
        best = r;
        b1 = c1;
        b2 = c2;
        bl = l;
      }
    }
  }
  double step = 0.5 * SS_GWC_C_MAX / WC2_GRID;
  while (step > 1e-4) {
    int moved = 0;
    for (int d = 0; d < 4; ++d) {
      double c1 = b1 + (d == 0 ? step : d == 1 ? -step : 0.0);
      double c2 = b2 + (d == 2 ? step : d == 3 ? -step : 0.0);
      if (c2 < 0.0 || c1 > SS_GWC_C_MAX || c2 > c1) {
        continue;
      }
      double r = wc2_try(n, cos_phi, h, w, c1, c2, &l);
      if (r < best) {
        best = r;
        b1 = c1;
        b2 = c2;
        bl = l;
        moved = 1;
      }
    }
    if (!moved) {
      step *= 0.5;
    }
  }
  m->lambda = bl;
  m->c1 = b1;
  m->c2 = b2;
}

void ss_wc2_harmonics(const ss_wc2 *m, double h[3]) {
  double a = m->c1, b = m->c2;
  for (int n = 0; n < 3; ++n) {
    h[n] = m->lambda * a + (1.0 - m->lambda) * b;
    a *= m->c1;
    b *= m->c2;
  }
}

/* Prony's method with the divisions taken apart: with
 * A = H3 - H1 H2, B = H1 H3 - H2^2, det = H2 - H1^2, the lobes are the roots
 * (A +- sqrt(N)) / (2 det) of x^2 - (A/det) x + B/det, N = A^2 - 4 det B,
 * and c1 - c2 = sqrt(N) / |det|. Fills c1, c2, that difference and
 * num = H1 - c2 = lambda (c1 - c2); returns 0 when the harmonics are not
 * those of two distinct lobes in range with 0 <= lambda <= lambda_max =
 * (1 - c2)(1 + c1) / (2 (c1 - c2)) (ss_wc2_lambda_max, compared without
 * dividing). */
static int prony(const double h[3], double *c1, double *c2, double *diff, double *num) {
  double m1 = h[0], m2 = h[1], m3 = h[2];
  double det = m2 - m1 * m1;
  if (!(fabs(det) > 1e-10)) {
    return 0;
  }
  double a = m3 - m1 * m2, b = m1 * m3 - m2 * m2;
  double n = a * a - 4.0 * det * b;
  if (!(n > 0.0)) {
    return 0;
  }
  /* The division and the square root are independent. */
  double inv = 0.5 / det, root = sqrt(n);
  double signed_root = det > 0.0 ? root : -root;
  *c1 = (a + signed_root) * inv;
  *c2 = (a - signed_root) * inv;
  *diff = 2.0 * root * fabs(inv);
  *num = m1 - *c2;
  return *c2 >= 0.0 && *c1 <= SS_GWC_C_MAX && *num >= 0.0 &&
         2.0 * *num <= (1.0 - *c2) * (1.0 + *c1);
}

int ss_wc2_from_harmonics(const double h[3], ss_wc2 *m) {
  double c1, c2, diff, num;
  if (prony(h, &c1, &c2, &diff, &num)) {
    m->lambda = num / diff;
    m->c1 = c1;
    m->c2 = c2;
    return 1;
  }
  m->lambda = 1.0;
  m->c1 = m->c2 = fmin(SS_GWC_C_MAX, fmax(0.0, h[0]));
  return 0;
}

/* ss_wc2_pdf_cos with lambda = num / diff folded into its one division. */
double ss_wc2_pdf_harmonics(const double h[3], double cos_phi) {
  double c1, c2, diff, num;
  if (!prony(h, &c1, &c2, &diff, &num)) {
    double c = fmin(SS_GWC_C_MAX, fmax(0.0, h[0]));
    return ss_wc_pdf_cos(cos_phi, c);
  }
  double d1 = 1.0 + c1 * c1 - 2.0 * c1 * cos_phi, d2 = 1.0 + c2 * c2 - 2.0 * c2 * cos_phi;
  double top = num * (1.0 - c1 * c1) * d2 + (diff - num) * (1.0 - c2 * c2) * d1;
  return top / (2.0 * SS_PI * diff * d1 * d2);
}
