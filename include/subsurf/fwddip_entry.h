/* Entry points for the forward scattering dipole (Frederickx & Dutré 2017,
 * eq. 16): one-sample MIS of the probe rays' planar-offset projection
 * (probe.h) and a ray along the ballistic direction of eq. 10.
 *
 * With probability beta (the model's `ballistic` option,
 * ss_fwddip_ballistic_fraction) the ballistic strategy traces a ray from
 * x_o along a direction d drawn by ss_fwddip_sample_ballistic (about the
 * refracted exit direction, into the medium) and picks one of the object's
 * hits on it uniformly; its density per unit area at an entry point x_i at
 * distance t = |x_i - x_o| along d = (x_i - x_o)/t is
 *     p_b(x_i) = p_d(d) |n_i . d| / (t^2 N(d)),
 * p_d the direction density, n_i the geometric normal at x_i and N(d) the
 * number of the object's hits on that ray. Otherwise (1 - beta) the probe
 * rays sample it with density p_p (ss_probe_pdf). The sample's density is
 *     p(x_i) = beta p_b(x_i) + (1 - beta) p_p(x_i),
 * so that the estimator f/p is the balance heuristic's (the weights
 * beta p_b/p and (1 - beta) p_p/p sum to one). For other models beta = 0 and
 * this is ss_probe_sample_entry, drawing the same numbers. */
#ifndef SUBSURF_FWDDIP_ENTRY_H
#define SUBSURF_FWDDIP_ENTRY_H

#include "subsurf/probe.h"

/* Samples an entry point with 5 uniforms: u[0] picks the strategy (and is
 * rescaled for the probe's axis choice), then either the probe's u[1..4] or
 * the ballistic lobe (u[1]), polar angle (u[2]), azimuth (u[3]) and hit
 * (u[4]). out->axis is -1 for a ballistic sample; out->pdf is p(x_i). */
int ss_fwddip_entry_sample(const ss_probe *p, const double u[5], ss_probe_sample *out,
                           unsigned long long *queries);

/* p_b(x_i) of the ballistic strategy alone (one all-hits query; `count` the
 * ray's hit count when known, 0 to query it). */
double ss_fwddip_entry_ballistic_pdf(const ss_probe *p, const ss_hit *hit, size_t count,
                                     unsigned long long *queries);

/* p(x_i) of the combination (queries every technique). */
double ss_fwddip_entry_pdf(const ss_probe *p, const ss_hit *hit, unsigned long long *queries);

#endif
