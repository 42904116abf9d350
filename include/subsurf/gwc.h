/* The General Wrapped Cauchy azimuthal model of Ferrier2016 (sec.
 * 3.2-4.2): f(phi) = alpha + beta pdf_WC(phi; c) on [-pi, pi], its
 * closed-form fit through three anchors, its analytic CDF and its sampling by
 * inverting that CDF (gwc.c: safeguarded fourth-order steps from a
 * Cauchy-mixture quantile, shared with the two-lobe model); plus the
 * least-squares fit over many azimuths that subsurf uses to go beyond the
 * paper at the same storage. */
#ifndef SUBSURF_GWC_H
#define SUBSURF_GWC_H

#include <stddef.h>

/* Largest concentration the fits return: keeps a - cos(phi) away from 0. */
#define SS_GWC_C_MAX 0.98

typedef struct {
  double alpha; /* isotropic offset */
  double beta;  /* weight of the Wrapped Cauchy lobe */
  double c;     /* concentration, 0 <= c <= SS_GWC_C_MAX */
} ss_gwc;

/* Ferrier2016 sec. 3.3: cos(phi_j) of the three anchors. */
extern const double ss_gwc_anchor_cos[3];

/* Wrapped Cauchy density, CDF on [-pi, pi] and inverse CDF (sec. 4.2). */
double ss_wc_pdf(double phi, double c);
/* The same from cos(phi), for callers that have it. */
static inline double ss_wc_pdf_cos(double cos_phi, double c) {
  return (1.0 - c * c) / (2.0 * 3.14159265358979323846 * (1.0 + c * c - 2.0 * c * cos_phi));
}
double ss_wc_cdf(double phi, double c);
double ss_wc_inv_cdf(double u, double c);

double ss_gwc_eval(const ss_gwc *g, double phi);
/* int_{-pi}^{pi} f = 2 pi alpha + beta (Ferrier2016, eq. 1 without r). */
double ss_gwc_integral(const ss_gwc *g);

/* How a fit ended. */
typedef enum {
  SS_GWC_FIT_EXACT,         /* the three anchors are reproduced */
  SS_GWC_FIT_FLAT,          /* f_2 = f_3 or K = k: c = 0, alpha = 0, beta = 2 pi f_1 */
  SS_GWC_FIT_CLAMPED_C,     /* a <= 1 would be needed: c clamped, alpha, beta refitted */
  SS_GWC_FIT_CLAMPED_ALPHA, /* alpha < 0: alpha = 0, c and beta through anchors 1 and 3 */
} ss_gwc_fit_kind;

/* Closed form through (cos phi_j, f_j), j = 1..3 (Ferrier2016 sec. 3.3, with
 * its beta corrected, docs/tables.md). f_j >= 0. */
ss_gwc_fit_kind ss_gwc_fit3(const double cos_phi[3], const double f[3], ss_gwc *out);

/* Weighted least squares over n azimuths: minimises
 * sum_j w_j (alpha + beta pdf_WC(phi_j; c) - f_j)^2 with alpha >= 0,
 * beta >= 0, 0 <= c <= SS_GWC_C_MAX, by exact linear solves in (alpha, beta)
 * nested in a golden-section search over c started around `*g` (used as the
 * initial guess when g->beta > 0). */
void ss_gwc_fit_lsq(size_t n, const double *phi, const double *f, const double *w, ss_gwc *g);

/* Normalised density of phi on [-pi, pi] (f >= 0 required: alpha >= 0). */
double ss_gwc_pdf(const ss_gwc *g, double phi);
double ss_gwc_cdf(const ss_gwc *g, double phi);
/* Inverts the CDF at u in [0, 1) (sec. 4.2) by safeguarded fourth-order
 * steps from a Cauchy-mixture quantile (gwc.c: the GWC is two lobes, one
 * with c = 0); monotone in u; returns phi in [-pi, pi]. */
double ss_gwc_sample(const ss_gwc *g, double u);

/* Two Wrapped Cauchy lobes, normalised on [-pi, pi]:
 * g(phi) = lambda pdf_WC(phi; c1) + (1 - lambda) pdf_WC(phi; c2), c1 >= c2,
 * with 0 <= lambda <= lambda_max: lambda > 1 (a negative broad lobe) is
 * allowed while g(pi) >= 0, which makes profiles sharper than a Wrapped
 * Cauchy (von Mises-like, far from an absorbing beam). The GWC is c2 = 0.
 * Its n-th harmonic int g cos(n phi) is lambda c1^n + (1 - lambda) c2^n:
 * PBD's decay faster than geometrically near the beam, slower far away. */
typedef struct {
  double lambda, c1, c2;
} ss_wc2;

double ss_wc2_pdf(const ss_wc2 *m, double phi);
/* The same from cos(phi), with one division:
 * [lambda (1 - c1^2) D2 + (1 - lambda)(1 - c2^2) D1] / (2 pi D1 D2),
 * D_k = 1 + c_k^2 - 2 c_k cos(phi). */
static inline double ss_wc2_pdf_cos(const ss_wc2 *m, double cos_phi) {
  double c1 = m->c1, c2 = m->c2;
  double d1 = 1.0 + c1 * c1 - 2.0 * c1 * cos_phi, d2 = 1.0 + c2 * c2 - 2.0 * c2 * cos_phi;
  double num = m->lambda * (1.0 - c1 * c1) * d2 + (1.0 - m->lambda) * (1.0 - c2 * c2) * d1;
  return num / (2.0 * 3.14159265358979323846 * d1 * d2);
}
double ss_wc2_cdf(const ss_wc2 *m, double phi);
/* The analytic CDF inverted as for the GWC; c1, c2 < 1. */
double ss_wc2_sample(const ss_wc2 *m, double u);
/* Largest lambda keeping g >= 0 for lobes c1 >= c2. */
double ss_wc2_lambda_max(double c1, double c2);
/* Least squares sum_j w_j (g(phi_j) - h_j)^2 over 0 <= c2 <= c1 <= SS_GWC_C_MAX
 * and 0 <= lambda <= lambda_max, for data h normalised to integrate to 1:
 * lambda by an exact linear solve, (c1, c2) by a grid search refined by a
 * pattern search. */
void ss_wc2_fit(size_t n, const double *phi, const double *h, const double *w, ss_wc2 *m);

/* The harmonics H_n = lambda c1^n + (1 - lambda) c2^n, n = 1..3: a
 * representation without the model's degeneracies (c1 = c2 makes lambda
 * arbitrary), smooth over the table and so safe to interpolate. */
void ss_wc2_harmonics(const ss_wc2 *m, double h[3]);
/* Inverse (Prony's method for two exponentials): the lobes are the roots of
 * x^2 - p x + q with H_{n+2} = p H_{n+1} - q H_n (H_0 = 1). Harmonics no
 * two-lobe model in range reproduces (after interpolation) fall back to the
 * single Wrapped Cauchy with the same first harmonic. Returns 1 when the
 * three harmonics are reproduced. */
int ss_wc2_from_harmonics(const double h[3], ss_wc2 *m);
/* The normalised density at cos(phi) of the model ss_wc2_from_harmonics
 * recovers (the same branch decisions), with fewer divisions. */
double ss_wc2_pdf_harmonics(const double h[3], double cos_phi);

#endif
