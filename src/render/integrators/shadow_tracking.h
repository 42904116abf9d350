/* Tracked shadow rays from medium vertices toward delta lights. */
#ifndef SUBSURF_RENDER_SHADOW_TRACKING_H
#define SUBSURF_RENDER_SHADOW_TRACKING_H

#include "render/integrators/common.h"

/* volpath's rate k of the shadow ray's free flight, a fraction of the
 * medium's smallest extinction: the ray survives a distance d in the medium
 * with probability exp(-k min(sigma_t) d). Measured on the index-matched
 * skin sphere (bench/RESULTS.md): 0 costs a full query per vertex, 1 adds
 * the most variance. */
#define SS_SHADOW_TRACKING_RATE 0.5

/* The transmittance from p, a vertex inside the homogeneous medium med
 * (not a grid or flakes), to the delta light sample ls, estimated without
 * bias: a free flight s of rate lambda = rate x min_c sigma_t[c] is sampled and
 * the ray traced only as far as s; when it reaches the medium's boundary at
 * d < s, the estimate is exp(-(sigma_t - lambda) d) times the transmittance
 * beyond the boundary (ss_shadow_transmittance_tracked), else 0. Deep
 * vertices, whose light is attenuated most, mostly end in a short query.
 * rate 0: the exact transmittance (the query runs to the boundary). */
ss_rgb ss_shadow_transmittance_sampled(const ss_scene *scene, ss_vec3 p, const ss_medium *med,
                                       const ss_light_sample *ls, double rate,
                                       const ss_tracking *tk, ss_path_stats *stats);

#endif
