/* Shared operations of the radially symmetric profile models (private to
 * src/bssrdf), so that such a model is its profile, its totals and a choice
 * of Fresnel normalisation:
 *
 *   S(x_i, w_i; x_o, w_o) = Ft(w_i) R(|x_o - x_i|) Ft(w_o) s_scale,
 *   M(x_o) = Ft(w_i) R(r) m_scale (the exitance, int S cos dw_o).
 *
 * A model's state begins with an ss_radial_model (or, for a model with its
 * own eval, an ss_radial_sampler); its ops table then lists the hooks below
 * it needs, and its create fills R's totals and one entry sampler per
 * channel (a mixture, then ss_radial_model_fit_sampler for the fitted one). The hooks have the
 * signatures of ss_bssrdf_ops. */
#ifndef SUBSURF_BSSRDF_RADIAL_MODEL_H
#define SUBSURF_BSSRDF_RADIAL_MODEL_H

#include "bssrdf/bssrdf_util.h"
#include "bssrdf/profile_sampler.h"

/* One radial mixture per channel: the entry sampler of a model whose state
 * begins with this struct (uniform azimuth, SS_BSSRDF_RADIAL). */
typedef struct {
  ss_radial_mix ch[SS_BSSRDF_CHANNELS];
} ss_radial_sampler;

int ss_radial_sampler_sample_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                   double u1, double u2, ss_bssrdf_entry *e);
double ss_radial_sampler_pdf_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                   double r, double phi);
double ss_radial_sampler_max_radius(const void *state, int channel);

/* scale R(r) for every channel, R as S and M use it (per unit power
 * entering). The caller's factor (Fresnel, ring length) is folded in so that
 * a query is one call and one pass over the channels. `state` is the model's
 * state, which begins with its ss_radial_model. */
typedef void (*ss_radial_profile_fn)(const void *state, double r, double scale,
                                     double out[SS_BSSRDF_CHANNELS]);

/* How the light reaching the surface leaves through it. */
typedef enum {
  /* R is the diffuse flux reaching the surface and leaves with the Fresnel
   * lobe Ft(w_o)/pi (Jensen et al. 2001, eq. 5): s_scale = 1/pi and
   * m_scale = 1 - 2 C1(1/eta), the fraction of that lobe leaving. */
  SS_RADIAL_EXIT_FRESNEL,
  /* R is the exitance itself and the lobe is normalised (d'Eon 2012;
   * pbrt-v3's SeparableBSSRDF): s_scale = 1/(pi (1 - 2 C1(1/eta))),
   * m_scale = 1. */
  SS_RADIAL_EXIT_NORMALISED,
} ss_radial_exit;

typedef struct {
  /* first: the ss_profile_sampler hooks read it (unused by models with
   * their own sampling hooks) */
  ss_profile_sampler sampler;
  ss_radial_profile_fn profile;
  double eta;
  double t_out;                        /* 1 - 2 C1(1/eta) */
  double s_scale;                      /* S = Ft(w_i) Ft(w_o) s_scale R */
  double m_scale;                      /* M = Ft(w_i) m_scale R */
  double total[SS_BSSRDF_CHANNELS];    /* 2 pi int R r dr (the model fills it) */
  double transmit[SS_BSSRDF_CHANNELS]; /* slabs: the same for T(r), else 0 */
  double small, large;                 /* quadrature scales: below R's core, beyond its tail */
} ss_radial_model;

/* Sets the boundary, the normalisation and the profile; the scales start
 * empty for ss_radial_model_set_diffusion_sampler to widen. */
void ss_radial_model_init(ss_radial_model *m, double eta, ss_radial_exit exit,
                          ss_radial_profile_fn profile);
/* The diffusion models' entry sampler for channel c, 3/4 at the tail rate
 * sigma_tr and 1/4 at the core rate sigma_t' (ss_radial_mix_init_diffusion),
 * and the quadrature scales: 0.05/sigma_t' and the sampler's max radius. */
void ss_radial_model_set_diffusion_sampler(ss_radial_model *m, int c, double sigma_tr,
                                           double sigma_t_prime);
/* Fits the entry sampler to R(r) once the channels' mixtures are set
 * (ss_profile_sampler_init_diffusion, the mixtures as defensive share; the
 * mixtures alone for a single-use model). */
void ss_radial_model_fit_sampler(ss_radial_model *m, const ss_bssrdf_params *p);
/* Sets total to 2 pi int R(r) r dr by quadrature on the model's scales (for
 * a profile without a closed-form integral). */
void ss_radial_model_integrate_total(ss_radial_model *m);

void ss_radial_model_eval(const void *state, const ss_bssrdf_query *q,
                          double s[SS_BSSRDF_CHANNELS]);
/* M integrated over the plane: Ft(cos_i) m_scale total (and transmit). */
void ss_radial_model_total_reflectance(const void *state, double cos_i,
                                       double out[SS_BSSRDF_CHANNELS]);
void ss_radial_model_total_transmittance(const void *state, double cos_i,
                                         double out[SS_BSSRDF_CHANNELS]);
/* The model's total as the intrinsic Rd. */
void ss_radial_model_rd(const void *state, double out[SS_BSSRDF_CHANNELS]);
/* The profile hook: value = ms = R(r). */
void ss_radial_model_profile(const void *state, int channel, double r,
                             ss_bssrdf_profile_value *out);
void ss_radial_model_exitance(const void *state, double cos_i, double x, double y,
                              double out[SS_BSSRDF_CHANNELS]);
/* int S dy along the line (x, ., 0): 2 int_0^inf R(hypot(x, y)) dy by
 * quadrature on the model's scales, times the Fresnel factors. */
void ss_radial_model_radiance_line(const void *state, double cos_i, double x, ss_vec3 w_o,
                                   double out[SS_BSSRDF_CHANNELS]);
/* int S dA_o = Ft(w_i) Ft(w_o) s_scale total. */
void ss_radial_model_brdf(const void *state, ss_vec3 w_i, ss_vec3 w_o,
                          double out[SS_BSSRDF_CHANNELS]);

#endif
