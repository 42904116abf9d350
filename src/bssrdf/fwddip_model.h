/* What the models `fwddip` and `fwddip-brdf` share (private to src/bssrdf):
 * their options, the per-channel media and image distances, the coupling
 * through the smooth dielectric boundary and the adaptive integral over the
 * path length s. */
#ifndef SUBSURF_BSSRDF_FWDDIP_MODEL_H
#define SUBSURF_BSSRDF_FWDDIP_MODEL_H

#include "bssrdf/fwddip_propagator.h"
#include "bssrdf/radial_model.h"
#include "subsurf/microfacet.h"

/* The models' declared options (fwddip_state.c) and their values. */
extern const ss_option ss_fwddip_options[];
extern const ss_option ss_fwddip_brdf_options[];

typedef struct {
  double s_rtol;    /* relative accuracy of the integral over s */
  int reciprocal;   /* eq. 15 instead of eq. 14 (fwddip) */
  int image_a;      /* 0: A from the Fresnel moments (Frisvad et al. 2014); 1: A = 1 */
  double ballistic; /* probability of the renderer's ballistic entry strategy (fwddip) */
  double alpha;     /* rough dielectric boundary: microfacet roughness (0: smooth) */
  int distribution; /* 0: Beckmann, 1: GGX */
  int rough_nodes;  /* the boundary rule: N x 2N visible-normal nodes at each end */
} ss_fwddip_config;

/* A fixed rule over the inside directions that leave through the surface
 * (normal +z): weight = cos_t (1 - Fr_inside(cos_t)) dw_t, so that
 * sum weight L_inside = the exitance per eta^2 (radiance/n^2 conserved). */
#define SS_FWDDIP_DIR_MU 16
#define SS_FWDDIP_DIR_PHI 24
#define SS_FWDDIP_DIRS (SS_FWDDIP_DIR_MU * SS_FWDDIP_DIR_PHI)
/* With a rough boundary light also leaves beyond the critical angle: a third
 * 8-point panel in cos_t below it. */
#define SS_FWDDIP_DIRS_MAX (SS_FWDDIP_DIRS + SS_GL8_N * SS_FWDDIP_DIR_PHI)

/* The rough boundary's fixed rule over visible microfacet normals (fwddip_rough.c). */
#define SS_FWDDIP_ROUGH_MAX_NODES 8
#define SS_FWDDIP_ROUGH_MAX (2 * SS_FWDDIP_ROUGH_MAX_NODES * SS_FWDDIP_ROUGH_MAX_NODES)

typedef struct {
  int on;           /* alpha >= 1e-3 and eta != 1 (else the smooth boundary, as in src/optics) */
  ss_microfacet mf; /* the distribution of the rough dielectric (bsdf_dielectric.c) */
  int n;
  double u1[SS_FWDDIP_ROUGH_MAX], u2[SS_FWDDIP_ROUGH_MAX]; /* the visible-normal sampler's */
  double w[SS_FWDDIP_ROUGH_MAX];                           /* quadrature weights */
} ss_fwddip_rough;

/* Directions transmitted through the boundary, in world space, with weights. */
typedef struct {
  int n;
  ss_vec3 d[SS_FWDDIP_ROUGH_MAX];
  double w[SS_FWDDIP_ROUGH_MAX];
} ss_fwddip_nodes;

typedef struct {
  ss_radial_sampler sampler; /* first: the entry sampler hooks read it */
  ss_fwddip_config cfg;
  double eta;
  ss_fwddip_medium m[SS_BSSRDF_CHANNELS];
  double z_v[SS_BSSRDF_CHANNELS];  /* 2 A d_e (eq. 13) */
  int same_as[SS_BSSRDF_CHANNELS]; /* a lower channel with the same medium, or itself */
  double sigma_t_prime[SS_BSSRDF_CHANNELS];
  int n_dir;
  ss_vec3 dir[SS_FWDDIP_DIRS_MAX];
  double dir_weight[SS_FWDDIP_DIRS_MAX];
  ss_fwddip_rough rough;
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

/* The rough boundary (fwddip_rough.c): builds the slope rule from the
 * options; `model` names the model in error messages. */
ss_status ss_fwddip_rough_init(ss_fwddip_rough *r, const ss_fwddip_config *cfg, double eta,
                               const char *model, ss_error *err);
/* The inside propagation directions into which light arriving along -w
 * (w outside, pointing away from the surface with normal n) is transmitted,
 * weighted so that sum_k w_k g(d_k) = int f(d, w) |cos_d| g(d) dd, f the
 * rough dielectric BTDF of src/optics (Walter et al. 2007, eq. 21, radiance
 * transport): the transmitted share of the power. Scaled by `scale`. */
void ss_fwddip_rough_enter(const ss_fwddip_rough *r, double eta, ss_vec3 w, ss_vec3 n, double scale,
                           ss_fwddip_nodes *out);
/* The inside propagation directions (toward the surface) that leave toward
 * w_o, weighted so that sum_k w_k L(d_k) is the outside radiance for inside
 * radiance L: int f(w_o, -d) |cos_d| L(d) dd, which is the entry rule from
 * w_o reversed, over eta^2 (generalised reciprocity). */
void ss_fwddip_rough_leave(const ss_fwddip_rough *r, double eta, ss_vec3 w_o, ss_vec3 n,
                           ss_fwddip_nodes *out);
/* The power share transmitted out of the medium by light inside hitting the
 * surface at cos_t (the rough counterpart of 1 - Fr). */
double ss_fwddip_rough_leaving_share(const ss_fwddip_rough *r, double eta, double cos_t);

/* The boundary at both ends as pairs of inside directions: `in` the
 * propagation directions into the medium at the entry, `out` those toward
 * the surface at the exit, with weights, and a common factor. Smooth: one
 * direction each (ss_fwddip_boundary) of weight 1, the factor Ft Ft/eta^2;
 * rough: the rules of ss_fwddip_rough_enter/leave, factor 1. Returns 0 when
 * no light passes. */
int ss_fwddip_pairs(const ss_fwddip_state *st, ss_vec3 w_i, ss_vec3 n_i, ss_vec3 w_o, ss_vec3 n_o,
                    ss_fwddip_nodes *in, ss_fwddip_nodes *out, double *factor);
/* The half-space beam at cos_i (toward +x) as transmitted directions, and
 * their common factor (smooth: the refracted beam of weight 1 and Ft). */
int ss_fwddip_beam_nodes(const ss_fwddip_state *st, double cos_i, ss_fwddip_nodes *in,
                         double *factor);

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
