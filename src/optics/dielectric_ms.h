/* The compensation lobes of rough dielectrics (bsdf_dielectric_ms.c), used
 * by bsdf_dielectric.c; private to src/optics. */
#ifndef SUBSURF_OPTICS_DIELECTRIC_MS_H
#define SUBSURF_OPTICS_DIELECTRIC_MS_H

#include "subsurf/bsdf.h"

/* Fills the tables from the single-scattering BSDF `single`. */
void ss_dielectric_ms_build(ss_dielectric_ms *ms, const ss_bsdf *single);
/* One table node: the albedo *e of side `side` at mu = k / NODES and its
 * transmitted part *trans, from `single` (its own seed per node). */
void ss_dielectric_ms_node(const ss_bsdf *single, int side, int k, double *e, double *trans);
/* The cosine average 2 int_0^1 v(mu) mu dmu of the linear interpolant of
 * the node values v[0..NODES]. */
double ss_dielectric_ms_average(const double *v);
/* Sets x and on from e_avg and the transmitted averages t_avg. */
void ss_dielectric_ms_finish(ss_dielectric_ms *ms, double eta, const double t_avg[2]);
/* The tables of t at roughness alpha (within the range t was asked for),
 * interpolated linearly between the grid's nodes (dielectric_ms_alpha.c). */
void ss_dielectric_ms_alpha_at(const ss_dielectric_ms_alpha *t, double alpha, ss_dielectric_ms *ms);
/* f of the compensated BSDF given the single-scattering value. */
ss_vec3 ss_dielectric_ms_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, ss_vec3 single);
/* Its sampling density given the single-scattering density. */
double ss_dielectric_ms_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, double single);
/* Chooses the lobe with uc: returns 0 for the single-scattering BSDF (uc
 * rescaled to [0, 1) for its own lobe choice), or 1 with a compensation
 * direction in *wi drawn from (u1, u2). */
int ss_dielectric_ms_pick(const ss_bsdf *b, ss_vec3 wo, double *uc, double u1, double u2,
                          ss_vec3 *wi);

#endif
