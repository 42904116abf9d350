/* The path tracer of surfaces in which translucent materials scatter light
 * below their surface through their BSSRDF model (the `bssrdf` integrator's,
 * bssrdf_pt.c, which documents it): the estimate of a ray for the `bssrdf`
 * integrator, for the indirect light of the irradiance points
 * (irradiance_points.c) and for the continuation of the `hybrid`'s
 * hand-over. Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_BSSRDF_PATH_H
#define SUBSURF_RENDER_INTEGRATORS_BSSRDF_PATH_H

#include "render/integrators/bssrdf_vertex.h"

/* 1 when translucent material m is traced volumetrically (level of detail
 * "volpath") instead of through its model. */
int ss_bssrdf_path_volumetric(const ss_scene *scene, const ss_material *m);

/* The radiance along a camera ray; all_hits: every hit of a probe chord is
 * an entry point (1) or one is chosen (0, SS_BSSRDF_DEFAULT_ALL_HITS). */
ss_rgb ss_bssrdf_path_li(const ss_scene *scene, int all_hits, ss_ray ray, ss_rng *rng,
                         ss_path_stats *stats);

/* Continues a path from vertex v (an ENTRY vertex of the `hybrid`
 * integrator's hand-over; v->d set), reached with throughput beta after
 * `depth` events, with hero channel `hero` and the channel density ratios
 * r (p_i / p_hero of the path so far with the hero choice's 3 pmf_i, mean
 * 1, beta divided by the same mean) for materials traced volumetrically,
 * and the radiance scaling eta_scale of the refractions so far: light
 * sampled at v (unless v->lit), the next direction sampled from it and the
 * path traced on. Releases v. Returns the radiance, beta included. */
ss_rgb ss_bssrdf_path_continue(const ss_scene *scene, ss_vertex *v, ss_rgb beta, ss_rgb r, int hero,
                               int depth, double eta_scale, ss_rng *rng, ss_path_stats *stats);

#endif
