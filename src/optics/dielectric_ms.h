/* The compensation lobes of rough dielectrics (bsdf_dielectric_ms.c), used
 * by bsdf_dielectric.c; private to src/optics. */
#ifndef SUBSURF_OPTICS_DIELECTRIC_MS_H
#define SUBSURF_OPTICS_DIELECTRIC_MS_H

#include "subsurf/bsdf.h"

/* Fills the tables from the single-scattering BSDF `single`. */
void ss_dielectric_ms_build(ss_dielectric_ms *ms, const ss_bsdf *single);
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
