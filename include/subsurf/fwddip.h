/* Importance sampling for the forward scattering dipole models (Frederickx
 * & Dutré 2017; docs/fwddip.md has the derivations). Directions follow
 * bssrdf.h: outside, pointing away from the surface, normal +z in the local
 * frame. Each sampler draws exactly from the density its pdf returns. */
#ifndef SUBSURF_FWDDIP_H
#define SUBSURF_FWDDIP_H

#include "subsurf/bssrdf.h"

/* The transport inside the boundary, for renderers that couple fwddip to a
 * boundary BSDF of their own (rough dielectrics, src/optics): directions
 * are inside propagation directions, wi_e into the medium at x_i and wo_e
 * toward the surface at x_o; no Fresnel factor is applied.
 * ss_fwddip_propagator: G^b_f of eq. 14 (eq. 15 with the model's
 * `reciprocal` option) at path length s for one channel, the integrand of
 * the eq. 16 estimator (may be negative where the image dominates).
 * ss_fwddip_transport: its integral over s for every channel (adaptive, to
 * the model's s_rtol), clamped at 0. Both are 0 for other models. */
double ss_fwddip_propagator(const ss_bssrdf *b, int channel, double s, ss_vec3 x_o, ss_vec3 n_o,
                            ss_vec3 wo_e, ss_vec3 x_i, ss_vec3 n_i, ss_vec3 wi_e);
void ss_fwddip_transport(const ss_bssrdf *b, ss_vec3 x_o, ss_vec3 n_o, ss_vec3 wo_e, ss_vec3 x_i,
                         ss_vec3 n_i, ss_vec3 wi_e, double out[SS_BSSRDF_CHANNELS]);

/* fwddip-brdf: an outgoing direction for incidence w_i from a mixture of a
 * cosine lobe and three von Mises-Fisher lobes about the mirror direction
 * (where the forward peak of eq. 17 sits). The direction may lie below the
 * horizon (f_r = 0 there); *pdf is per unit solid angle on the sphere.
 * Returns 0 for a model other than fwddip-brdf. */
int ss_fwddip_brdf_sample(const ss_bssrdf *b, ss_vec3 w_i, double u1, double u2, ss_vec3 *w_o,
                          double *pdf);
double ss_fwddip_brdf_pdf(const ss_bssrdf *b, ss_vec3 w_i, ss_vec3 w_o);

/* fwddip, eq. 16: the path length s for channel c given the distance
 * `dist` = |x_o - x_i| between the exit and the sampled entry point. A
 * one-sample mixture (1/2 each) of the long-path marginal of eq. 11 (an
 * inverse Gaussian in ps, drawn exactly) and a short-path log-normal about
 * the ballistic length `dist` (eq. 10's peak). u1 picks the component and
 * drives it, u2 is the inverse Gaussian's acceptance draw. *pdf per unit s.
 * Returns 0 for other models. */
int ss_fwddip_sample_length(const ss_bssrdf *b, int channel, double dist, double u1, double u2,
                            double *s, double *pdf);
double ss_fwddip_pdf_length(const ss_bssrdf *b, int channel, double dist, double s);

/* The next-event branch of eq. 16 (sec. 7.2.3): the light direction, hence
 * w_i^e, is drawn first, so the path length is drawn knowing both inside
 * directions: the same mixture, the log-normal centred where eq. 10's
 * Gaussian |R/s - (w_o^e + w_i^e)/2|^2 is smallest (docs/fwddip.md). */
int ss_fwddip_sample_length_directed(const ss_bssrdf *b, int channel, ss_vec3 x_o, ss_vec3 wo_e,
                                     ss_vec3 x_i, ss_vec3 wi_e, double u1, double u2, double *s,
                                     double *pdf);
double ss_fwddip_pdf_length_directed(const ss_bssrdf *b, int channel, ss_vec3 x_o, ss_vec3 wo_e,
                                     ss_vec3 x_i, ss_vec3 wi_e, double s);

/* fwddip, eq. 16: the propagation direction w_i^e into the medium at x_i
 * for path length s, exit x_o and inside exit direction w_o^e, from the
 * exponential in w' of eq. 9: G_f is proportional to e^{w'.h} with
 * h = E p (x_o - x_i) - D w_o^e, a von Mises-Fisher density about h with
 * concentration |h| (drawn exactly; uniform when h = 0). *pdf per unit solid
 * angle. Returns 0 for other models. */
int ss_fwddip_sample_direction(const ss_bssrdf *b, int channel, double s, ss_vec3 x_o, ss_vec3 wo_e,
                               ss_vec3 x_i, double u1, double u2, ss_vec3 *wi_e, double *pdf);
double ss_fwddip_pdf_direction(const ss_bssrdf *b, int channel, double s, ss_vec3 x_o, ss_vec3 wo_e,
                               ss_vec3 x_i, ss_vec3 wi_e);

/* fwddip, eq. 16: the second entry strategy, a ray along the ballistic
 * direction of eq. 10. Light leaving the exit point x_o (outward normal n_o)
 * toward w_o (outside) travelled inside along -refract(w_o); the renderer
 * traces a ray from x_o along a direction d drawn about refract(w_o) (into
 * the medium) from a mixture of von Mises-Fisher lobes (concentrations 1, 8,
 * 64, 512, weights 1/4; docs/fwddip.md) and takes an entry point on it.
 * u1 picks the lobe, u2 and u3 drive its polar angle and azimuth; *pdf per
 * unit solid angle. Returns 0 for other models, w_o below the surface or
 * total internal reflection. ss_fwddip_ballistic_fraction: the model option
 * `ballistic`, the probability of this strategy in the renderer's one-sample
 * MIS with the probe rays (0 for other models). */
int ss_fwddip_sample_ballistic(const ss_bssrdf *b, ss_vec3 n_o, ss_vec3 w_o, double u1, double u2,
                               double u3, ss_vec3 *d, double *pdf);
double ss_fwddip_pdf_ballistic(const ss_bssrdf *b, ss_vec3 n_o, ss_vec3 w_o, ss_vec3 d);
double ss_fwddip_ballistic_fraction(const ss_bssrdf *b);

#endif
