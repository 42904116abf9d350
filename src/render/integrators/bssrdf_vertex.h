/* The BSSRDF's vertices of the `bssrdf` integrator (bssrdf_pt.c): entry
 * points sampled by probe rays, the local thickness, single scattering and
 * the continuation the `hybrid` hands over to (surface_vertex.h holds the
 * vertex itself). */
#ifndef SUBSURF_RENDER_INTEGRATORS_BSSRDF_VERTEX_H
#define SUBSURF_RENDER_INTEGRATORS_BSSRDF_VERTEX_H

#include "render/integrators/surface_vertex.h"
#include "subsurf/probe.h"

/* The `bssrdf` integrator's option all_hits: every hit of a probe chord is
 * an entry point (1), or one hit chosen uniformly (0: the hit-count MIS of
 * probe.h, one all-hits query per other axis). */
#define SS_BSSRDF_DEFAULT_ALL_HITS 1

/* The object's thickness along the inward normal at a hit on its surface
 * (the multipole's local_thickness): a probe ray to where it next meets
 * the same object; 0 when it meets another first or escapes. */
double ss_local_thickness(const ss_scene *scene, const ss_hit *hit, ss_path_stats *stats);

/* Samples an entry point x_i by probe rays around the probe's centre
 * (probe.h; with the ballistic ray for fwddip, fwddip_entry.h) and makes v
 * an ENTRY vertex there: kind, p, ng, frame, query.x_i, query.n_i and
 * query.thickness (the local thickness at `surface` when the model uses
 * it); the caller sets query.x_o, n_o, w_o and the scale. Returns the area
 * density of x_i, 0 when the sample misses (v then untouched). */
double ss_vertex_sample_entry(const ss_scene *scene, const ss_probe *probe, const ss_hit *surface,
                              ss_rng *rng, ss_vertex *v, ss_path_stats *stats);

/* All the hits of one probe chord as entry points (probe.h,
 * ss_probe_sample_hits): v holds the model, its kind (ENTRY, or SOURCE for
 * the hybrid's point source), query.x_o, n_o, w_o and a scale factor. The
 * direct light at every hit x_j, weighted by v's scale / D(x_j), times
 * beta, is added to *L; v becomes the vertex of that kind at one hit chosen
 * uniformly among the n kept, with scale n / D(x_j) (the path continues
 * from it) and `lit` set. Returns 0 when the chord has no hit. */
int ss_vertex_sample_entries(const ss_scene *scene, const ss_probe *probe, const ss_hit *surface,
                             ss_rgb beta, ss_rng *rng, ss_vertex *v, ss_rgb *L,
                             ss_path_stats *stats);

/* Jensen et al. 2001's single scattering (sec. 2.2-2.4) at exit point x_o
 * (hit, seen along d) of a translucent material: a distance along the
 * refracted exit ray, a light sample whose straight line leaves the object at
 * x_i, the refracted distance and direction inside from Snell's law there;
 * exact for a flat boundary (then it equals the `single` model's f_r^(1)).
 * Direct light only. In a grid or micro-flakes, ss_volume_single_scatter
 * (single_scatter.h). */
ss_rgb ss_single_scatter(const ss_scene *scene, const ss_material *m, const ss_hit *hit, ss_vec3 d,
                         ss_rng *rng, ss_path_stats *stats);

#endif
