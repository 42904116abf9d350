/* Normalised diffusion (ChristensenBurley2015).
 *
 * | option     | meaning                                                      |
 * |------------|--------------------------------------------------------------|
 * | sigma_s, g | with sigma_a: the albedo A and the length l (below)          |
 * | sigma_a    | absorption                                                   |
 * | eta        | Fresnel factors; A is the exact albedo behind this boundary  |
 * | fit        | option: which of the paper's fits gives s (searchlight, ...) |
 *
 * R(r) = A_e (e^{-r/d} + e^{-r/(3d)}) / (8 pi d r) (eq. 2), d = l / s(A), which
 * integrates to A_e over the plane. How the medium maps to (A, l):
 * - A is the exact albedo of the medium (albedo_inversion.h: the half-space
 *   Monte Carlo table's diffuse reflectance at normal incidence per unit
 *   incident power), so that a material given as albedo + mfp renders that
 *   albedo head-on; the profile carries A_e = A / (1 - F(0)), per unit power
 *   entering, and the exit lobe is normalised: total reflectance at
 *   incidence cos_i is Ft(cos_i) A_e (A at normal incidence).
 * - l is the reduced mean free path 1/sigma_t' (1/sigma_t for isotropic
 *   scattering, the paper's set-up) for the searchlight and diffuse fits,
 *   and the diffuse mean free path 1/sigma_tr (classical, sqrt(3 sigma_a
 *   sigma_t'), at least 1e-3 sigma_t') for the dmfp fit.
 * The scaling s(A) (A the surface albedo) is the paper's fit for
 *   searchlight  s = 1.85 - A + 7 |A - 0.8|^3   (eq. 6, normal incidence, mfp)
 *   diffuse      s = 1.9 - A + 3.5 (A - 0.8)^2  (eq. 5, diffuse transmission)
 *   dmfp         s = 3.5 + 100 (A - 0.33)^4     (eq. 8, diffuse mean free path)
 *
 * Sampling is exact: the radial cdf 1 - e^{-r/d}/4 - 3 e^{-r/(3d)}/4 is a
 * cubic in x = e^{-r/(3d)}, x^3 + 3 x = 4 (1 - u), whose one real root is
 * x = 2 sinh(asinh(2 (1 - u)) / 3) (Cardano's formula with p = 3). The
 * sampling density per unit area is R(r) / A_e. */
#include "bssrdf/radial_model.h"

#include "subsurf/albedo_inversion.h"
#include "subsurf/albedo_table.h"

#include <math.h>
#include <stdlib.h>

/* R is clamped at r_min = 1e-6 d (it diverges as 1/r): the clamped core
 * carries 5e-7 of the total. */
#define BURLEY_CORE 1e-6

typedef struct {
  ss_radial_model base; /* its sampler is unused: the hooks below sample */
  double a_e[SS_BSSRDF_CHANNELS], d[SS_BSSRDF_CHANNELS];
} burley;

enum { FIT_SEARCHLIGHT, FIT_DIFFUSE, FIT_DMFP };

static const ss_option burley_options[] = {
    {.name = "fit",
     .type = SS_OPTION_CHOICE,
     .def = "searchlight",
     .choices = "searchlight|diffuse|dmfp",
     .help = "Christensen & Burley's fit for s(A): searchlight (mfp, normal incidence), diffuse "
             "(mfp, diffuse transmission), dmfp (diffuse mean free path)"},
    {0},
};

/* The profile per unit area, without A_e (also the sampling density). */
static double shape(double d, double r) {
  double rc = fmax(r, BURLEY_CORE * d);
  /* Christensen & Burley 2015, eq. 2 with A = 1. */
  return (exp(-rc / d) + exp(-rc / (3.0 * d))) / (8.0 * SS_PI * d * rc);
}

static void burley_profile(const void *state, double r, double scale,
                           double out[SS_BSSRDF_CHANNELS]) {
  const burley *b = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = scale * b->a_e[c] * shape(b->d[c], r);
  }
}

/* Christensen & Burley 2015, eq. 5, 6 and 8. */
static double scaling(int fit, double A) {
  switch (fit) {
  case FIT_DIFFUSE:
    return 1.9 - A + 3.5 * (A - 0.8) * (A - 0.8);
  case FIT_DMFP:
    return 3.5 + 100.0 * pow(A - 0.33, 4.0);
  default:
    return 1.85 - A + 7.0 * pow(fabs(A - 0.8), 3.0);
  }
}

static ss_status burley_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  int fit = ss_bssrdf_params_choice(p, &burley_options[0]);
  burley *b = calloc(1, sizeof *b);
  if (!b) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "burley: out of memory");
  }
  ss_radial_model_init(&b->base, p->eta, SS_RADIAL_EXIT_NORMALISED, burley_profile);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double s_s = p->medium.sigma_s.c[c], s_a = p->medium.sigma_a.c[c], g = p->medium.g.c[c];
    ss_bssrdf_coeffs k = ss_bssrdf_coeffs_make(s_s, s_a, g);
    double A;
    ss_status st = ss_albedo_exact(s_s / k.sigma_t, g, p->eta, &A, err);
    if (st != SS_OK) {
      free(b);
      ss_error_prefix(err, "burley: ");
      return st;
    }
    double l =
        fit == FIT_DMFP ? 1.0 / fmax(k.sigma_tr, 1e-3 * k.sigma_t_prime) : 1.0 / k.sigma_t_prime;
    b->a_e[c] = A / ss_albedo_max(p->eta);
    b->d[c] = l / scaling(fit, A);
    b->base.total[c] = b->a_e[c];
    b->base.small = fmin(b->base.small, 0.01 * b->d[c]);
    b->base.large = fmax(b->base.large, 30.0 * b->d[c]);
  }
  *state = b;
  return SS_OK;
}

/* The radius at which the cdf reaches u: r = -3 d ln x, x the real root of
 * x^3 + 3 x - 4 (1 - u) = 0. */
static double radius_at(double d, double u) {
  double x = 2.0 * sinh(asinh(2.0 * (1.0 - u)) / 3.0);
  return x < 1.0 ? -3.0 * d * log(x) : 0.0;
}

static int burley_sample_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                               double u1, double u2, ss_bssrdf_entry *e) {
  const burley *b = state;
  e->r = radius_at(b->d[channel], fmin(u1, 1.0 - 0x1p-53));
  e->phi = 2.0 * SS_PI * u2;
  e->pdf = shape(b->d[channel], e->r);
  return 1;
}

static double burley_pdf_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                               double r, double phi) {
  const burley *b = state;
  return r < 0.0 ? 0.0 : shape(b->d[channel], r);
}

/* The radius holding 1 - 1e-4 of the samples. */
static double burley_max_radius(const void *state, int channel) {
  const burley *b = state;
  return radius_at(b->d[channel], 1.0 - 1e-4);
}

const ss_bssrdf_ops ss_bssrdf_model_burley = {
    .name = "burley",
    .summary = "normalised diffusion, exact albedo, closed-form sampling (Christensen & Burley "
               "2015)",
    .flags = SS_BSSRDF_RADIAL,
    .options = burley_options,
    .create = burley_create,
    .destroy = free,
    .eval = ss_radial_model_eval,
    .sample_entry = burley_sample_entry,
    .pdf_entry = burley_pdf_entry,
    .max_radius = burley_max_radius,
    .total_reflectance = ss_radial_model_total_reflectance,
    .rd = ss_radial_model_rd,
    .profile = ss_radial_model_profile,
    .exitance = ss_radial_model_exitance,
    .radiance_line = ss_radial_model_radiance_line,
    .brdf = ss_radial_model_brdf,
};
