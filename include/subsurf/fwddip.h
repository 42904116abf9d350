/* Importance sampling for the forward scattering dipole models (Frederickx
 * & Dutré 2017; docs/fwddip.md has the derivations). Directions follow
 * bssrdf.h: outside, pointing away from the surface, normal +z in the local
 * frame. Each sampler draws exactly from the density its pdf returns. */
#ifndef SUBSURF_FWDDIP_H
#define SUBSURF_FWDDIP_H

#include "subsurf/bssrdf.h"

/* fwddip-brdf: an outgoing direction for incidence w_i from a mixture of a
 * cosine lobe and three von Mises-Fisher lobes about the mirror direction
 * (where the forward peak of eq. 17 sits). The direction may lie below the
 * horizon (f_r = 0 there); *pdf is per unit solid angle on the sphere.
 * Returns 0 for a model other than fwddip-brdf. */
int ss_fwddip_brdf_sample(const ss_bssrdf *b, ss_vec3 w_i, double u1, double u2, ss_vec3 *w_o,
                          double *pdf);
double ss_fwddip_brdf_pdf(const ss_bssrdf *b, ss_vec3 w_i, ss_vec3 w_o);

#endif
