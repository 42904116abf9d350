/* What the models `fwddip` and `fwddip-brdf` share (private to src/bssrdf):
 * their options, the per-channel media and image distances, the coupling
 * through the smooth dielectric boundary and the adaptive integral over the
 * path length s. */
#ifndef SUBSURF_BSSRDF_FWDDIP_MODEL_H
#define SUBSURF_BSSRDF_FWDDIP_MODEL_H

#include "bssrdf/fwddip_propagator.h"
#include "bssrdf/radial_model.h"

/* The models' declared options (fwddip_state.c) and their values. */
extern const ss_bssrdf_option ss_fwddip_options[];
extern const ss_bssrdf_option ss_fwddip_brdf_options[];

typedef struct {
  double s_rtol;  /* relative accuracy of the integral over s */
  int reciprocal; /* eq. 15 instead of eq. 14 (fwddip) */
  int image_a;    /* 0: A from the Fresnel moments (Frisvad et al. 2014); 1: A = 1 */
  double ballistic; /* probability of the renderer's ballistic entry strategy (fwddip) */
} ss_fwddip_config;

/* A fixed rule over the inside directions that leave through the surface
 * (normal +z): weight = cos_t (1 - Fr_inside(cos_t)) dw_t, so that
 * sum weight L_inside = the exitance per eta^2 (radiance/n^2 conserved). */
#define SS_FWDDIP_DIR_MU 16
#define SS_FWDDIP_DIR_PHI 24
#define SS_FWDDIP_DIRS (SS_FWDDIP_DIR_MU * SS_FWDDIP_DIR_PHI)

typedef struct {
  ss_radial_sampler sampler; /* first: the entry sampler hooks read it */
  ss_fwddip_config cfg;
  double eta;
  ss_fwddip_medium m[SS_BSSRDF_CHANNELS];
  double z_v[SS_BSSRDF_CHANNELS];  /* 2 A d_e (eq. 13) */
  int same_as[SS_BSSRDF_CHANNELS]; /* a lower channel with the same medium, or itself */
  double sigma_t_prime[SS_BSSRDF_CHANNELS];
  ss_vec3 dir[SS_FWDDIP_DIRS];
  double dir_weight[SS_FWDDIP_DIRS];
} ss_fwddip_state;

/* Reads the options, checks that sigma_s' > 0 (the propagator's scale) and
 * fills the state; `model` names the model in error messages. */
ss_status ss_fwddip_state_init(ss_fwddip_state *st, const ss_bssrdf_params *p, const char *model,
                               ss_error *err);
/* Allocates and initialises a state (the models' create). */
ss_status ss_fwddip_state_create(const ss_bssrdf_params *p, const char *model, void **state,
                                 ss_error *err);

/* Total diffuse reflectance for incidence cos_i: the albedo of the effective
 * BRDF, Ft(w_i) int cos_t Ft(w_t) int G^pb_f ds dw_t (the BSSRDF integrated
 * over the exit plane is its planar-source propagator). */
void ss_fwddip_total_reflectance(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]);

/* The boundary seen from inside: w_i, w_o point away from the surface,
 * outside (bssrdf.h); wi_e is the refracted propagation direction into the
 * medium at the entry, wo_e the propagation direction inside that leaves
 * toward w_o, and *factor = Ft(w_i) Ft(w_o)/eta^2 (radiance/n^2 is
 * conserved through a smooth boundary). Returns 0 when no light passes. */
int ss_fwddip_boundary(double eta, ss_vec3 w_i, ss_vec3 n_i, ss_vec3 w_o, ss_vec3 n_o,
                       ss_vec3 *wi_e, ss_vec3 *wo_e, double *factor);

/* The refracted beam of the half-space experiment (along (sin t, 0, -cos t)
 * outside, cos_i = cos t) and Ft at entry; 0 when nothing enters. */
int ss_fwddip_halfspace_beam(double eta, double cos_i, ss_vec3 *w_i, double *ft);

/* f(s) with the coefficients of eq. 9 already made at p s. */
typedef double (*ss_fwddip_s_fn)(void *ctx, const ss_fwddip_coeffs *k, double s);

#define SS_FWDDIP_MAX_BALLISTIC 4

/* int_0^inf f(s) ds for the medium m: Gauss-Kronrod (7, 15) panels in
 * log s over p s in [1e-6, 1e4] (two per decade, plus panels closing in
 * geometrically on each ballistic length d, where the unscattered peak of
 * eq. 10 sits), then bisection of the panel with the largest error estimate
 * until the summed estimate is below rtol |integral| (at most 1000 panels). */
double ss_fwddip_integrate_s(const ss_fwddip_medium *m, ss_fwddip_s_fn f, void *ctx,
                             const double *ballistic, int n_ballistic, double rtol);

/* A channel's transport (before the boundary factor and the clamp). */
typedef double (*ss_fwddip_channel_fn)(void *ctx, int c);

/* out[c] = scale max(0, f(ctx, c)), computed once per distinct medium. */
void ss_fwddip_channels(const ss_fwddip_state *st, ss_fwddip_channel_fn f, void *ctx, double scale,
                        double out[SS_BSSRDF_CHANNELS]);

#endif
