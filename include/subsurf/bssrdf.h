/* One interface for every BSSRDF model: a small
 * table of operations (ss_bssrdf_ops, in the style of the kernel's
 * file_operations) plus the model's own state behind an opaque handle.
 * The renderer and the CLI see only this header; a new model is one file in
 * src/bssrdf/ defining `const ss_bssrdf_ops ss_bssrdf_model_<id>` plus one
 * line SS_BSSRDF_MODEL(<id>) in src/bssrdf/models.def.
 *
 * Conventions (the same as the half-space reference, halfspace.h):
 * - eta = n_inside / n_outside; normals point outward.
 * - Directions w_i and w_o both point AWAY from the surface, on the outside:
 *   w_i toward where the light comes from, w_o toward the viewer. A beam
 *   travelling along (sin t, 0, -cos t) has w_i = (-sin t, 0, cos t).
 * - S is per unit area at x_i and x_o and per unit solid angle at w_i and
 *   w_o, with the model's own Fresnel transmission factors included:
 *   for a unit-power beam entering at x_i, the exitant radiance is
 *   L_o(x_o, w_o) = S(x_i, w_i; x_o, w_o) and the exitance is
 *   M(x_o) = int S cos(theta_o) dw_o, the quantities the half-space
 *   reference measures (halfspace.h).
 * - Three colour channels (RGB); every per-channel output is double[3].
 * - Operations on a valid handle never fail and never allocate; only
 *   ss_bssrdf_create reports errors. */
#ifndef SUBSURF_BSSRDF_H
#define SUBSURF_BSSRDF_H

#include "subsurf/medium_optics.h"
#include "subsurf/option.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <stddef.h>

#define SS_BSSRDF_CHANNELS 3

/* Model options: each model declares the options it reads in
 * ss_bssrdf_ops.options (the shared contract of option.h, which integrators
 * use too), and everything outside the model (the CLI, scene files) sets
 * them by name, as text, with ss_bssrdf_params_set_option. The model's
 * create() reads them with the typed getters below, passing its own
 * declaration; an option never set reads as its declared default. */
#define SS_BSSRDF_MAX_OPTIONS 8

/* A material's coefficients and the model options set on it.
 * ss_bssrdf_params_default gives every field a meaningful value and sets no
 * option. */
typedef struct {
  /* sigma_s, sigma_a, g per channel; the models use g (single scattering
   * with a Henyey-Greenstein phase function of that g, whatever the family). */
  ss_medium_optics medium;
  double eta; /* the boundary: n_inside / n_outside, one for all channels */

  int n_options; /* set with ss_bssrdf_params_set_option */
  ss_option_value options[SS_BSSRDF_MAX_OPTIONS];

  /* Tables shared with other materials (table_cache.h), which the tabulated
   * models take theirs from; NULL: the model builds its own. */
  struct ss_table_cache *tables;
  /* Built for one path vertex (spatially varying coefficients): the model
   * skips the per-instance fits and tables that pay off only over many
   * samples (its entry sampler is then the exponential mixture alone). */
  int single_use;
  /* The material's own model when this one is built for one path vertex
   * (owned by the caller, outliving this model): a model may borrow its
   * tables when they fit (aniso-dipole: the same flakes and albedos at
   * another density and axis, a gridded medium). NULL: none. */
  const struct ss_bssrdf *base;
} ss_bssrdf_params;

/* Defaults: sigma_s 1, sigma_a 0.01, g 0 (Henyey-Greenstein), eta 1.3, no
 * option set. */
void ss_bssrdf_params_default(ss_bssrdf_params *p);

/* Sets all three channels of the medium from scalar coefficients
 * (Henyey-Greenstein phase). */
void ss_bssrdf_params_set_gray(ss_bssrdf_params *p, double sigma_s, double sigma_a, double g);

/* An evaluation query: entry point, normal, direction; exit point, normal,
 * direction (see the conventions above); and the object's local thickness
 * at x_o along -n_o when the renderer measured it (models whose
 * ss_bssrdf_uses_thickness is 1 ask for it), else 0. */
typedef struct {
  ss_vec3 x_i, n_i, w_i;
  ss_vec3 x_o, n_o, w_o;
  double thickness;
} ss_bssrdf_query;

/* The known end of a path when sampling the other end. The sampled point is
 * x + r (cos(phi) frame.s + sin(phi) frame.t) on the tangent plane of x;
 * frame.n is the outward normal at x. `w` is the direction at the known point
 * (pointing away from the surface, outside), or the zero vector when unknown;
 * models that are not radially symmetric may use it. */
typedef struct {
  ss_vec3 x;
  ss_frame frame;
  ss_vec3 w;
} ss_bssrdf_sample_ctx;

/* A sampled entry point, relative to the known exit point. */
typedef struct {
  double r;   /* radius on the tangent plane */
  double phi; /* azimuth in ctx.frame, [0, 2 pi) */
  double pdf; /* density per unit area of the tangent plane, for this channel */
} ss_bssrdf_entry;

/* The radial profile at normal incidence as the model's paper defines it
 * (per unit area per unit power), e.g. Jensen's R_d(r) for the dipole. */
typedef struct {
  double value; /* the profile the paper uses: ms + ss where it has both */
  double ms;    /* multiple-scattering (diffusion) part */
  double ss;    /* single-scattering part (0 where the model has none) */
  double t;     /* diffuse transmittance profile through a slab (0 for a half-space) */
} ss_bssrdf_profile_value;

enum {
  /* Sampling ignores phi (uniform azimuth, pdf independent of phi). */
  SS_BSSRDF_RADIAL = 1u << 0,
  /* S is a distribution concentrated at x_i = x_o (a BRDF such as
   * dipole-brdf): eval returns 0; use ss_bssrdf_brdf. */
  SS_BSSRDF_BRDF = 1u << 1,
  /* S has no pointwise value (single scattering of a collimated beam is a
   * line in (x_o, w_o)): eval returns 0; the exitance, radiance_line and
   * brdf hooks give its observable integrals. */
  SS_BSSRDF_SINGULAR = 1u << 2,
  /* Total reflectance depends on the incidence angle beyond the Fresnel
   * transmission factor at entry. */
  SS_BSSRDF_ANGULAR = 1u << 3,
  /* The model describes a slab and reports transmittance. */
  SS_BSSRDF_SLAB = 1u << 4,
  /* create() tabulates (milliseconds or more): too slow to build a model
   * per shading point for spatially varying coefficients. */
  SS_BSSRDF_TABULATED = 1u << 5,
  /* The model takes micro-flake media (params.medium.flakes); the others
   * refuse them. */
  SS_BSSRDF_FLAKES = 1u << 6,
  /* The exitance depends on the azimuth even at normal incidence and need
   * not be even in y (an oriented medium): quadratures cover the full circle. */
  SS_BSSRDF_ORIENTED = 1u << 7,
};

/* The operations of one model. `state` is what `create` returned. Optional
 * hooks may be NULL: ss_bssrdf_* then falls back to quadrature of lower-level
 * hooks (see each wrapper below). */
typedef struct ss_bssrdf_ops {
  const char *name;    /* registry name, e.g. "dipole" */
  const char *summary; /* one line for --help listings, citing the paper */
  unsigned flags;      /* SS_BSSRDF_* */
  /* The options create() reads, ended by {NULL}; NULL when none. */
  const ss_option *options;

  ss_status (*create)(const ss_bssrdf_params *p, void **state, ss_error *err);
  void (*destroy)(void *state);

  /* S(x_i, n_i, w_i; x_o, n_o, w_o) per channel. */
  void (*eval)(const void *state, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]);

  /* Samples the entry point for one channel given the exit point; returns 0
   * when no sample is produced (then e is unspecified). u1 drives the radius
   * (and may also pick a mixture component), u2 the azimuth. */
  int (*sample_entry)(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel, double u1,
                      double u2, ss_bssrdf_entry *e);
  /* The density sample_entry draws (r, phi) with, per unit area. */
  double (*pdf_entry)(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel, double r,
                      double phi);
  /* Radius beyond which sample_entry never (or with probability < 1e-4)
   * places a point: the probe-sphere radius for the renderer. */
  double (*max_radius)(const void *state, int channel);

  /* Total diffuse reflectance per unit incident power for incidence cos_i:
   * int M(x_o) dA, including the Fresnel factors (the halfspace's
   * "reflectance"). Optional: default integrates `exitance`. */
  void (*total_reflectance)(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]);
  /* The intrinsic total diffuse reflectance at normal incidence exactly as the
   * paper defines it (the dipole's closed-form Rd; PBD's rho_eff). */
  void (*rd)(const void *state, double out[SS_BSSRDF_CHANNELS]);
  /* The radial profile at normal incidence as the paper defines it. */
  void (*profile)(const void *state, int channel, double r, ss_bssrdf_profile_value *out);

  /* Exitance M(x, y) at the surface point (x, y, 0) of the half-space for a
   * unit-power beam entering at the origin along (sin t, 0, -cos t),
   * cos_i = cos t. Optional: default integrates eval over w_o. */
  void (*exitance)(const void *state, double cos_i, double x, double y,
                   double out[SS_BSSRDF_CHANNELS]);
  /* Radiance toward w_o integrated over y along the line (x, ., 0), same
   * beam: int S(0, w_i; (x, y, 0), w_o) dy. Optional: default integrates eval. */
  void (*radiance_line)(const void *state, double cos_i, double x, ss_vec3 w_o,
                        double out[SS_BSSRDF_CHANNELS]);
  /* BRDF f_r(w_i, w_o) = int S dA_o (per unit area of the entry point),
   * normal +z. Optional: default integrates eval over the plane. */
  void (*brdf)(const void *state, ss_vec3 w_i, ss_vec3 w_o, double out[SS_BSSRDF_CHANNELS]);
  /* The x-bin average of radiance_line over [x_lo, x_hi], for models whose
   * line density is too sharp (or a delta) for quadrature. Optional. */
  void (*radiance_bin)(const void *state, double cos_i, ss_vec3 w_o, double x_lo, double x_hi,
                       double out[SS_BSSRDF_CHANNELS]);
  /* Slabs (SS_BSSRDF_SLAB): total diffuse transmittance through the bottom
   * face per unit incident power, Fresnel factors included. Optional. */
  void (*total_transmittance)(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]);
  /* n_inside / n_outside of the entry face when the model carries its own
   * (layers: the top layer's). Optional: default params.eta. */
  double (*entry_eta)(const void *state);
  /* 1 when eval reads query.thickness (multipole with local_thickness).
   * Optional: default 0. */
  int (*uses_thickness)(const void *state);
  /* The model's point source: the exitance M(r; z) at the surface point at
   * lateral distance r from an isotropic point source at depth z >= 0 below
   * the surface of the half-space, per unit power scattered there, with the
   * model's own boundary condition (its virtual source mirrored about the
   * extrapolated boundary) and its own exit convention, so that the model's
   * multiple-scattering profile is this source integrated over the depths
   * where light entering at normal incidence first scatters:
   *     exitance(1, r) = Ft(1) int Q(z) M(r; z) dz
   * (the dipoles: Q = alpha' delta(z - z_r); pbd: Q = rho' sigma_t'
   * e^{-sigma_t' z}, Habel et al. 2013). Light leaves with the model's exit
   * lobe, radiance M Ft(w) / (pi (1 - 2 C1(1/eta))). The `hybrid`
   * integrator's hand-over at a scattering event (Li et al. 2005).
   * Optional: NULL when the model has no point source. */
  void (*point_source_exitance)(const void *state, double z, double r,
                                double out[SS_BSSRDF_CHANNELS]);
} ss_bssrdf_ops;

typedef struct ss_bssrdf ss_bssrdf;

/* Registry. */
size_t ss_bssrdf_model_count(void);
const ss_bssrdf_ops *ss_bssrdf_model_at(size_t i);
/* NULL when unknown (exact, case-sensitive name). */
const ss_bssrdf_ops *ss_bssrdf_model_find(const char *name);
/* Writes "a, b, c" (the registered names) into buf for error messages. */
void ss_bssrdf_model_names(char *buf, size_t size);

/* Setting and reading options (see ss_option above).
 *
 * The scene loader and the CLI call, per key given for a material:
 *     ss_bssrdf_params_set_option(&p, ops, key, text, &err);
 * which fails (SS_ERR_INVALID_ARGUMENT) for a name `ops` does not declare
 * ("pbd: unknown option 'thicknes' (options: beam_samples)") or a value of
 * the wrong type or out of range ("pbd: option beam_samples: expected a whole
 * number in [6, 384], got '3'"); the message names the model and the option,
 * and the caller adds its own file/key or --option. Setting a name again
 * replaces the value. JSON numbers and booleans may go through
 * ss_bssrdf_params_set_option_number instead of being printed as text. */
ss_status ss_bssrdf_params_set_option(ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                      const char *name, const char *value, ss_error *err);
/* For double, int and bool options (bool: 0 or 1). */
ss_status ss_bssrdf_params_set_option_number(ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                             const char *name, double value, ss_error *err);
/* Drops every option set (e.g. before passing a model's params to another
 * model it is built from). */
void ss_bssrdf_params_clear_options(ss_bssrdf_params *p);
/* SS_OK when every option set on `p` is declared by `ops` (ss_bssrdf_create
 * checks this, so that an option meant for another model is not ignored). */
ss_status ss_bssrdf_params_check_options(const ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                         ss_error *err);

/* The declaration of option `name` of a model, NULL when it has none. */
const ss_option *ss_bssrdf_option_find(const ss_bssrdf_ops *ops, const char *name);
size_t ss_bssrdf_option_count(const ss_bssrdf_ops *ops);
/* "a whole number in [6, 384], default 100" for --help and error messages. */
void ss_bssrdf_option_describe(const ss_option *o, char *buf, size_t size);
/* "a, b, c" (the model's option names) for error messages; "none" when none. */
void ss_bssrdf_option_names(const ss_bssrdf_ops *ops, char *buf, size_t size);

/* Typed getters for a model's create(): the value set under opt->name, or
 * opt->def. `opt` is the model's own declaration. */
double ss_bssrdf_params_double(const ss_bssrdf_params *p, const ss_option *opt);
int ss_bssrdf_params_int(const ss_bssrdf_params *p, const ss_option *opt);
int ss_bssrdf_params_bool(const ss_bssrdf_params *p, const ss_option *opt);
int ss_bssrdf_params_choice(const ss_bssrdf_params *p, const ss_option *opt);
/* "" when the option is empty (e.g. no table file). */
const char *ss_bssrdf_params_string(const ss_bssrdf_params *p, const ss_option *opt);

/* Validates the parameters (finite, sigma >= 0, sigma_t > 0, |g| < 1,
 * eta > 0, only options the model declares) and creates the model; the
 * message names the model and option. */
ss_status ss_bssrdf_create(const char *name, const ss_bssrdf_params *p, ss_bssrdf **out,
                           ss_error *err);
/* The checks of ss_bssrdf_create_ops without creating the model (for a
 * caller that creates it later, when it is needed). */
ss_status ss_bssrdf_check(const ss_bssrdf_ops *ops, const ss_bssrdf_params *p, ss_error *err);
ss_status ss_bssrdf_create_ops(const ss_bssrdf_ops *ops, const ss_bssrdf_params *p, ss_bssrdf **out,
                               ss_error *err);
void ss_bssrdf_destroy(ss_bssrdf *b);

const char *ss_bssrdf_name(const ss_bssrdf *b);
unsigned ss_bssrdf_flags(const ss_bssrdf *b);
const ss_bssrdf_ops *ss_bssrdf_get_ops(const ss_bssrdf *b);
const ss_bssrdf_params *ss_bssrdf_get_params(const ss_bssrdf *b);
const void *ss_bssrdf_state(const ss_bssrdf *b);

/* eval, pdf_entry, profile, exitance, radiance_line and point_source_exitance
 * answer 0 for a radius (or distance between x_i and x_o, or depth) that is NaN
 * or not below SS_BSSRDF_TAIL_RADIUS: every
 * model's profile falls at least as fast as 1/r^3 (the dipole's without
 * absorption), below the smallest double long before r^2 overflows, so
 * models see only radii they may square. */
#define SS_BSSRDF_TAIL_RADIUS 1e150
void ss_bssrdf_eval(const ss_bssrdf *b, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]);
int ss_bssrdf_sample_entry(const ss_bssrdf *b, const ss_bssrdf_sample_ctx *ctx, int channel,
                           double u1, double u2, ss_bssrdf_entry *e);
double ss_bssrdf_pdf_entry(const ss_bssrdf *b, const ss_bssrdf_sample_ctx *ctx, int channel,
                           double r, double phi);
/* One-sample MIS density over channels picked uniformly: mean of pdf_entry. */
double ss_bssrdf_pdf_entry_channels(const ss_bssrdf *b, const ss_bssrdf_sample_ctx *ctx, double r,
                                    double phi);
double ss_bssrdf_max_radius(const ss_bssrdf *b, int channel);
void ss_bssrdf_total_reflectance(const ss_bssrdf *b, double cos_i, double out[SS_BSSRDF_CHANNELS]);
void ss_bssrdf_rd(const ss_bssrdf *b, double out[SS_BSSRDF_CHANNELS]);
/* 0 for models without the hook (half-spaces). */
void ss_bssrdf_total_transmittance(const ss_bssrdf *b, double cos_i,
                                   double out[SS_BSSRDF_CHANNELS]);
/* The relative index of the face light enters (and the specular reflection
 * there is Fresnel's at it). */
double ss_bssrdf_entry_eta(const ss_bssrdf *b);
/* 1 when eval wants query.thickness measured by the renderer. */
int ss_bssrdf_uses_thickness(const ss_bssrdf *b);
/* 1 when the model has a point source (ss_bssrdf_ops.point_source_exitance). */
int ss_bssrdf_has_point_source(const ss_bssrdf *b);
/* M(r; z) of the model's point source at depth z (negative z: 0) per
 * channel; 0 for models without one. */
void ss_bssrdf_point_source_exitance(const ss_bssrdf *b, double z, double r,
                                     double out[SS_BSSRDF_CHANNELS]);
/* The radiance that leaves there toward a direction at cos_o (> 0) from
 * the outward normal, with the model's exit lobe:
 *     L_o = M(r; z) Ft(cos_o) / (pi (1 - 2 C1(1/eta))),
 * whose integral over the hemisphere (times cos_o) is M; 0 for models
 * without a point source. */
void ss_bssrdf_point_source_radiance(const ss_bssrdf *b, double z, double r, double cos_o,
                                     double out[SS_BSSRDF_CHANNELS]);
void ss_bssrdf_profile(const ss_bssrdf *b, int channel, double r, ss_bssrdf_profile_value *out);
void ss_bssrdf_exitance(const ss_bssrdf *b, double cos_i, double x, double y,
                        double out[SS_BSSRDF_CHANNELS]);
void ss_bssrdf_radiance_line(const ss_bssrdf *b, double cos_i, double x, ss_vec3 w_o,
                             double out[SS_BSSRDF_CHANNELS]);
void ss_bssrdf_brdf(const ss_bssrdf *b, ss_vec3 w_i, ss_vec3 w_o, double out[SS_BSSRDF_CHANNELS]);

/* The half-space geometry of the reference: entry at the origin, normals +z,
 * beam along (sin t, 0, -cos t) with cos_i = cos t, exit at (x, y, 0). */
ss_bssrdf_query ss_bssrdf_halfspace_query(double cos_i, double x, double y, ss_vec3 w_o);

/* Annulus average of the exitance over r_lo <= r < r_hi (the halfspace's
 * "radial" bins) and the x-bin average of radiance_line over [x_lo, x_hi]. */
void ss_bssrdf_radial_average(const ss_bssrdf *b, double cos_i, double r_lo, double r_hi,
                              double out[SS_BSSRDF_CHANNELS]);
void ss_bssrdf_direction_average(const ss_bssrdf *b, double cos_i, ss_vec3 w_o, double x_lo,
                                 double x_hi, double out[SS_BSSRDF_CHANNELS]);

/* Reduced and derived coefficients shared by the diffusion models. */
typedef struct {
  double sigma_t;       /* sigma_s + sigma_a */
  double sigma_s_prime; /* (1 - g) sigma_s */
  double sigma_t_prime; /* sigma_s' + sigma_a */
  double alpha_prime;   /* sigma_s' / sigma_t' */
  double D;             /* classical 1/(3 sigma_t') */
  double sigma_tr;      /* classical sqrt(3 sigma_a sigma_t') */
  double D_g;           /* Grosjean (2 sigma_a + sigma_s')/(3 sigma_t'^2) */
  double sigma_tr_g;    /* sqrt(sigma_a / D_g) */
} ss_bssrdf_coeffs;

ss_bssrdf_coeffs ss_bssrdf_coeffs_make(double sigma_s, double sigma_a, double g);

#endif
