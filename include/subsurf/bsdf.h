/* Boundary BSDFs in the local frame (normal = +z = the OUTSIDE of the
 * surface), as small vtables: eval / sample / pdf, like the phase
 * functions and the BSSRDF models (bssrdf.h).
 *
 * Directions: wo and wi both point AWAY from the surface. wo is the
 * direction the path arrived from (towards the camera in path tracing), wi
 * the sampled or light direction. A direction with z > 0 is outside, z < 0
 * inside. eta = n_inside / n_outside (fresnel.h).
 *
 * Values are RGB triples stored in ss_vec3 (x, y, z = r, g, b). eval and pdf
 * of delta lobes are 0; only sample produces them.
 *
 * Radiance scaling convention: in SS_TRANSPORT_RADIANCE mode (the default,
 * what volpath and path tracers from the camera need) the transmission
 * value INCLUDES the factor 1/eta_rel^2 with eta_rel = n(wi side) / n(wo
 * side), i.e. Walter et al. 2007 eq. 21 as written (radiance entering a
 * denser medium is compressed). Generalised reciprocity then holds:
 * f(wo, wi) / n(wo side)^2 == f(wi, wo) / n(wi side)^2. In
 * SS_TRANSPORT_IMPORTANCE mode (light tracing) the factor is left out, which
 * makes it the adjoint: f_importance(wo, wi) == f_radiance(wi, wo).
 * Reflection is the same in both modes and symmetric. */
#ifndef SUBSURF_BSDF_H
#define SUBSURF_BSDF_H

#include "subsurf/microfacet.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

typedef enum {
  SS_TRANSPORT_RADIANCE = 0,
  SS_TRANSPORT_IMPORTANCE,
} ss_transport_mode;

/* Lobe flags: of a BSDF (what it can do) and of a sample (what it did). */
enum {
  SS_BSDF_REFLECTION = 1u << 0,
  SS_BSDF_TRANSMISSION = 1u << 1,
  /* specular: a Dirac lobe, not evaluable. Of a BSDF: EVERY lobe is one
   * (a mix of a mirror and a diffuse reflector lacks it, its samples carry
   * it when they took the mirror). */
  SS_BSDF_DELTA = 1u << 2,
};

typedef struct {
  ss_vec3 wi;    /* sampled direction, unit, local frame */
  ss_vec3 f;     /* BSDF value; for a delta lobe the value that makes
                    f |wi.z| / pdf the lobe's weight */
  double pdf;    /* solid-angle density, or the probability of a delta lobe */
  unsigned lobe; /* SS_BSDF_REFLECTION or SS_BSDF_TRANSMISSION, | SS_BSDF_DELTA */
  double eta;    /* n(wi side) / n(wo side) for a transmission, 1 otherwise */
} ss_bsdf_sample;

typedef struct ss_bsdf ss_bsdf;

typedef struct {
  const char *name;
  ss_vec3 (*eval)(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi);
  double (*pdf)(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi);
  /* uc picks the lobe, (u1, u2) the direction; returns 0 when no sample
   * (s untouched or pdf 0). */
  int (*sample)(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2, ss_bsdf_sample *s);
} ss_bsdf_ops;

/* Energy compensation of a rough dielectric (Kulla & Conty 2017; see
 * src/optics/bsdf_dielectric_ms.c): the single-scattering albedo E_s(mu) of
 * side s (0: outside, 1: inside), counted without refraction's radiance
 * scaling, at mu = k / SS_DIELECTRIC_MS_NODES; its cosine average E_avg,s;
 * the share x_s of the lost energy that is transmitted. */
#define SS_DIELECTRIC_MS_NODES 32
typedef struct {
  int on;
  double e[2][SS_DIELECTRIC_MS_NODES + 1];
  double e_avg[2];
  double x[2];
} ss_dielectric_ms;

/* Energy compensation of a rough conductor (src/optics/conductor_ms.c). */
typedef struct ss_conductor_ms ss_conductor_ms;

struct ss_bsdf {
  const ss_bsdf_ops *ops;
  unsigned lobes; /* SS_BSDF_* flags this BSDF can produce */
  ss_transport_mode mode;
  double eta;          /* dielectrics: n_inside / n_outside; 1 for thin surfaces */
  ss_microfacet mf;    /* rough dielectric or conductor */
  ss_vec3 reflectance; /* diffuse albedo, mirror and diffuse-transmission reflectance (RGB) */
  ss_dielectric_ms ms; /* rough dielectric with energy compensation */
  /* Conductors: the complex index eta_c + i k_c per channel relative to the
   * outside; a rough one's compensation tables (shared, NULL when off) and
   * the Kulla-Conty Fresnel factor of its lost energy per channel. */
  ss_vec3 eta_c, k_c;
  const ss_conductor_ms *cms;
  ss_vec3 f_ms;
  /* Thin dielectric and coated diffuse: the sheet's or coat's index over
   * the outside's; coated diffuse: the base's reflectance seen through the
   * coat's internal reflections, R / (1 - R F_int) per channel, and the
   * coat's hemispherical reflectance from outside F_avg. */
  double eta_sheet;
  ss_vec3 coated_base;
  double coat_f_avg;
  ss_vec3 transmittance; /* diffuse transmission (RGB) */
  /* Two-sided (part[0] seen from either side) and mix (weight of part[0],
   * 1 - weight of part[1]): the parts' BSDFs, owned elsewhere. */
  const ss_bsdf *part[2];
  double weight;
};

/* Lambertian reflection, two-sided (reflects on whichever side wo is),
 * cosine-weighted sampling. Reflectance components in [0, 1]. */
ss_status ss_bsdf_diffuse_init(ss_bsdf *b, ss_vec3 reflectance, ss_error *err);
/* Smooth dielectric interface: delta reflection and refraction chosen with
 * the Fresnel probabilities F and 1 - F. eta > 0; eta == 1 passes straight
 * through (index matched). */
ss_status ss_bsdf_dielectric_init(ss_bsdf *b, double eta, ss_transport_mode mode, ss_error *err);
/* Rough dielectric (Walter et al. 2007) with visible-normal sampling; an
 * alpha below 1e-3 (pbrt-v4's rule) or eta == 1 falls back to the smooth
 * dielectric. */
ss_status ss_bsdf_rough_dielectric_init(ss_bsdf *b, double eta, const ss_microfacet *mf,
                                        ss_transport_mode mode, ss_error *err);
/* The same with multiple-scattering energy compensation (Kulla & Conty
 * 2017): lobes of 1 - E(mu) added on both sides so that no energy is lost
 * between microfacets (albedo 1 from every direction, reciprocal). Builds
 * the albedo tables from this BSDF (about 0.2 M BSDF samples). */
ss_status ss_bsdf_rough_dielectric_ms_init(ss_bsdf *b, double eta, const ss_microfacet *mf,
                                           ss_transport_mode mode, ss_error *err);
/* Energy compensation where the roughness varies over a surface (a
 * textured alpha): the tables of one distribution and eta on a grid of
 * alpha (1e-3, then steps of 0.025 to 1 and of 0.125 to 4), interpolated
 * linearly in alpha (src/optics/dielectric_ms_alpha.c). One per
 * (distribution, eta) in the process, shared by every material that asks
 * for it and kept until the process ends; the nodes covering a range are
 * built when first asked for (about as many tables as nodes). */
typedef struct ss_dielectric_ms_alpha ss_dielectric_ms_alpha;
/* The shared tables of (type, eta), with the nodes covering [alpha_lo,
 * alpha_hi] built; eta != 1, 0 <= alpha_lo <= alpha_hi <= 4. Thread-safe. */
ss_status ss_dielectric_ms_alpha_get(ss_microfacet_type type, double eta, double alpha_lo,
                                     double alpha_hi, const ss_dielectric_ms_alpha **out,
                                     ss_error *err);
/* The rough dielectric with energy compensation from tables t (of mf's
 * distribution and this eta) at mf->alpha, which must lie in the range t
 * was built for. Falls back like ss_bsdf_rough_dielectric_init. */
ss_status ss_bsdf_rough_dielectric_ms_at(ss_bsdf *b, double eta, const ss_microfacet *mf,
                                         ss_transport_mode mode, const ss_dielectric_ms_alpha *t,
                                         ss_error *err);
/* The tabulated single-scattering albedo of side s at cosine mu (linear
 * interpolation). */
double ss_dielectric_ms_albedo(const ss_dielectric_ms *ms, int side, double mu);

/* Conductor (src/optics/bsdf_conductor.c): one-sided (it reflects when wo
 * is outside, z > 0; black from inside: wrap it in ss_bsdf_two_sided_init
 * for sheets), with the exact Fresnel reflectance of the complex index
 * eta + i k per channel (fresnel.h). mf == NULL or an alpha below 1e-3 is
 * smooth (a delta reflection), otherwise rough (Walter et al. 2007's
 * reflection with visible-normal sampling), isotropic or anisotropic; with
 * compensate the rough conductor adds Kulla & Conty 2017's lobe for the
 * energy lost between microfacets (tables shared in the process,
 * ss_conductor_ms_get). eta > 0 and k >= 0 per channel. */
ss_status ss_bsdf_conductor_init(ss_bsdf *b, ss_vec3 eta, ss_vec3 k, const ss_microfacet *mf,
                                 int compensate, ss_error *err);
/* The shared compensation tables of a distribution and roughness (the
 * single-scattering albedo of the conductor with F = 1 over cos(theta_o)
 * and, anisotropic, azimuth; a few hundred thousand microfacet samples when
 * first asked for, then kept until the process ends). Thread-safe. */
ss_status ss_conductor_ms_get(const ss_microfacet *mf, const ss_conductor_ms **out, ss_error *err);
/* Its albedo E(wo) at a direction wo (z > 0) and its cosine average E_avg. */
double ss_conductor_ms_albedo(const ss_conductor_ms *t, ss_vec3 wo);
double ss_conductor_ms_average(const ss_conductor_ms *t);

/* Perfect mirror, one-sided like the conductor: delta reflection of
 * `reflectance` (components in [0, 1]). */
ss_status ss_bsdf_mirror_init(ss_bsdf *b, ss_vec3 reflectance, ss_error *err);
/* Thin dielectric sheet (a window pane) of index eta over the outside's,
 * the same medium on both sides: delta reflection with the sum of the
 * sheet's internal reflections R' = R + T^2 R / (1 - R^2) and straight
 * transmission T' = 1 - R' (no lateral offset, no absorption). */
ss_status ss_bsdf_thin_dielectric_init(ss_bsdf *b, double eta, ss_error *err);
/* Diffuse transmission (pbrt's translucent surface): Lambertian reflection
 * of `reflectance` on wo's side and Lambertian transmission of
 * `transmittance` to the other; components in [0, 1] with R + T <= 1. */
ss_status ss_bsdf_diffuse_transmission_init(ss_bsdf *b, ss_vec3 reflectance, ss_vec3 transmittance,
                                            ss_error *err);
/* Coated diffuse (smooth plastic; src/optics/bsdf_coated_diffuse.c): a
 * smooth dielectric coat of index eta (> 1) over a Lambertian base of
 * `reflectance` (components in [0, 1]) in optical contact, the light
 * bouncing between base and coat summed in closed form. One-sided like
 * the conductor. A white base conserves energy. */
ss_status ss_bsdf_coated_diffuse_init(ss_bsdf *b, ss_vec3 reflectance, double eta, ss_error *err);
/* The BSDF `front` seen from both sides: from inside (wo.z < 0) both
 * directions are mirrored into the outside. `front` must outlive b. */
ss_status ss_bsdf_two_sided_init(ss_bsdf *b, const ss_bsdf *front, ss_error *err);
/* weight a + (1 - weight) b, weight in [0, 1]; a and b must outlive m. */
ss_status ss_bsdf_mix_init(ss_bsdf *m, const ss_bsdf *a, const ss_bsdf *b, double weight,
                           ss_error *err);

static inline ss_vec3 ss_bsdf_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  return b->ops->eval(b, wo, wi);
}
static inline double ss_bsdf_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  return b->ops->pdf(b, wo, wi);
}
static inline int ss_bsdf_sample_dir(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                                     ss_bsdf_sample *s) {
  return b->ops->sample(b, wo, uc, u1, u2, s);
}
static inline const char *ss_bsdf_name(const ss_bsdf *b) { return b->ops->name; }

#endif
