/* Emission a path finds by unidirectional sampling, and its multiple
 * importance sampling weight against the light sampling at the previous
 * vertex (Veach1997 ch. 9), for every path integrator. Private to
 * src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_EMISSION_H
#define SUBSURF_RENDER_INTEGRATORS_EMISSION_H

#include "render/integrators/path_state.h"

/* The radiance emitted toward the path along d (unit) by the surface of
 * `hit`, or by the environment when hit is NULL (the ray escaped); black
 * when there is none. *p_light: the density with which light sampling from
 * prev_p would have produced the same direction (the pick's probability
 * included), set when the radiance is not black. */
ss_rgb ss_emission_found(const ss_scene *scene, const ss_hit *hit, ss_vec3 d, ss_vec3 prev_p,
                         double *p_light);

/* The emission found along d, times the path's throughput and its power
 * heuristic weight against light sampling (1 after a vertex without light
 * samples): the contribution of the BSDF technique. */
ss_rgb ss_path_emitted(const ss_scene *scene, const ss_path_state *s, const ss_hit *hit, ss_vec3 d);

#endif
