/* The path tracer shared by the integrators that take the diffusion term of
 * a translucent surface from a precomputed solution (`hierarchical`: an
 * octree of irradiance points; `fem`: a finite-element solution): surfaces
 * are path traced as in `bssrdf`, except at a translucent surface seen from
 * outside at x_o toward w_o, where the diffusion term of the caller's
 * callback is added, the single scattering term of Jensen et al. 2001 for
 * "single_scattering" materials (bssrdf_vertex.h; in grids and micro-flakes
 * tracked, single_scatter.h), and the path continues
 * by the boundary's reflection lobe only (no branch: both terms are taken
 * every time). Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_DIFFUSION_PATH_H
#define SUBSURF_RENDER_INTEGRATORS_DIFFUSION_PATH_H

#include "subsurf/integrator.h"

/* The diffusion radiance leaving the translucent surface at `hit` along -d. */
typedef ss_rgb (*ss_diffusion_term_fn)(const void *ctx, const ss_hit *hit, ss_vec3 d,
                                       ss_path_stats *stats);

/* The radiance along a camera ray. */
ss_rgb ss_diffusion_path_li(const ss_scene *scene, ss_diffusion_term_fn term, const void *ctx,
                            ss_ray ray, ss_rng *rng, ss_path_stats *stats);

#endif
