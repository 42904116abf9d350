/* Importance sampling for the forward scattering dipole (subsurf/fwddip.h;
 * derivations in docs/fwddip.md). */
#include "subsurf/fwddip.h"

#include "subsurf/sampling.h"

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
