/* Microfacet distributions (Beckmann and GGX) in the local frame (macro
 * normal = +z), isotropic or anisotropic with roughness alpha along x (u)
 * and alpha_v along y (v) by stretching (Heitz 2014). Micronormals
 * wm always lie in the upper hemisphere.
 *
 * Masking-shadowing: the Smith model. G is the HEIGHT-CORRELATED form
 * G(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014, "Understanding
 * the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99 without
 * the transmission Beta term, as in pbrt-v4), used for reflection and
 * refraction alike. Visible-normal sampling: GGX by Heitz 2018 ("Sampling the
 * GGX Distribution of Visible Normals"), Beckmann by Heitz & d'Eon 2014
 * (stretch, sample the visible slope distribution, unstretch). */
#ifndef SUBSURF_MICROFACET_H
#define SUBSURF_MICROFACET_H

#include "subsurf/status.h"
#include "subsurf/vec3.h"

typedef enum {
  SS_MICROFACET_BECKMANN,
  SS_MICROFACET_GGX,
} ss_microfacet_type;

typedef struct {
  ss_microfacet_type type;
  double alpha;   /* roughness (RMS slope * sqrt(2) for Beckmann) along x, > 0 */
  double alpha_v; /* roughness along y; 0 means alpha (isotropic) */
} ss_microfacet;

/* Validates alpha (finite, 1e-4 <= alpha <= 4); isotropic. */
ss_status ss_microfacet_init(ss_microfacet *m, ss_microfacet_type type, double alpha,
                             ss_error *err);
/* Anisotropic: alpha_u along x, alpha_v along y, each as alpha above. */
ss_status ss_microfacet_init_anisotropic(ss_microfacet *m, ss_microfacet_type type, double alpha_u,
                                         double alpha_v, ss_error *err);
/* The roughness along y (alpha_v, or alpha when isotropic). */
static inline double ss_microfacet_alpha_v(const ss_microfacet *m) {
  return m->alpha_v > 0.0 ? m->alpha_v : m->alpha;
}
/* 1 when alpha_v differs from alpha. */
static inline int ss_microfacet_is_anisotropic(const ss_microfacet *m) {
  return ss_microfacet_alpha_v(m) != m->alpha;
}
/* "beckmann" or "ggx" (case-insensitive); returns 0 on an unknown name. */
int ss_microfacet_type_from_name(const char *name, ss_microfacet_type *type);
const char *ss_microfacet_type_name(ss_microfacet_type type);

/* Normal distribution D(wm), normalised so that int D(wm) cos(theta_m) dwm = 1;
 * 0 for wm.z <= 0. wm must be unit. */
double ss_microfacet_d(const ss_microfacet *m, ss_vec3 wm);
/* Smith Lambda(w) (depends on |w.z| and, when anisotropic, the azimuth). */
double ss_microfacet_lambda(const ss_microfacet *m, ss_vec3 w);
/* Smith G1(w, wm) = chi+(dot(w, wm) * w.z) / (1 + Lambda(w)). */
double ss_microfacet_g1(const ss_microfacet *m, ss_vec3 w, ss_vec3 wm);
/* Height-correlated G(wo, wi, wm), with the chi+ terms of both directions. */
double ss_microfacet_g(const ss_microfacet *m, ss_vec3 wo, ss_vec3 wi, ss_vec3 wm);

/* Samples a micronormal from the distribution of normals visible from w
 * (either hemisphere: w is first turned into the upper one), with density
 * ss_microfacet_pdf_visible. u1, u2 in [0, 1). */
ss_vec3 ss_microfacet_sample_visible(const ss_microfacet *m, ss_vec3 w, double u1, double u2);
/* D_w(wm) = G1(w', wm) max(0, dot(w', wm)) D(wm) / |w.z| with w' = w turned
 * into the upper hemisphere (Heitz 2014, eq. 38); solid-angle density of wm. */
double ss_microfacet_pdf_visible(const ss_microfacet *m, ss_vec3 w, ss_vec3 wm);

#endif
