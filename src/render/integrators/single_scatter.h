/* Jensen et al. 2001's single scattering below a translucent surface
 * (sec. 2.2-2.4): the geometry shared by the estimate in homogeneous media
 * (ss_single_scatter, bssrdf_vertex.h) and its tracked variant for grids and
 * micro-flakes (ss_volume_single_scatter below). Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_SINGLE_SCATTER_H
#define SUBSURF_RENDER_INTEGRATORS_SINGLE_SCATTER_H

#include "render/integrators/common.h"

/* The boundary's index ratio as single scattering sees it: 1 when index
 * matched, else the material's eta (a rough boundary is taken as smooth). */
static inline double ss_single_scatter_eta(const ss_material *m) {
  return m->boundary == SS_BOUNDARY_INDEX_MATCHED ? 1.0 : m->eta;
}

/* The refracted direction into the medium of a direction w outside (both
 * pointing away from the surface, n outward); w itself, reversed, when
 * index matched. 0 when there is none. */
int ss_single_scatter_refract_in(ss_vec3 w, ss_vec3 n, double eta, ss_vec3 *w_t);

/* The point where the straight line from x along wi leaves the object
 * geom_id (the first surface it meets must be that object's, from inside). */
int ss_single_scatter_exit(const ss_scene *scene, unsigned geom_id, ss_vec3 x, ss_vec3 wi,
                           ss_hit *hit, ss_path_stats *stats);

/* A light sample for the scattering point x inside the object geom_id: the
 * straight line toward the light leaves the object at xi, and the light is
 * taken to enter there by Snell's law at xi's geometric normal. Per unit
 * outside solid angle of the light direction, it reaches x after the
 * refracted distance s_in = z / cos_i' (z the depth of x below xi's tangent
 * plane) along d_in, with the radiance change Ft eta^2 on entering and the
 * solid-angle compression cos_i / (eta^2 cos_i') (Jensen et al. 2001, eq.
 * 4-6): `entry` = Ft(cos_i) cos_i / cos_i'. Exact for a flat boundary under
 * a light at infinity; with eta = 1 the straight segment x -> xi, exact for
 * any boundary and light. */
typedef struct {
  ss_light_sample ls;
  double pmf;   /* the probability of the light's choice */
  ss_hit xi;    /* where the straight line toward the light leaves */
  double entry; /* Ft(cos_i) cos_i / cos_i' */
  double s_in;  /* refracted distance from the boundary to x */
  ss_vec3 d_in; /* refracted propagation direction (toward x) */
} ss_single_scatter_light;

/* Picks a light (three uniforms of rng) and fills *l; 0 when it contributes
 * nothing: no light, a light that cannot reach x, a line that does not
 * leave through the object's own surface, or a light inside the object. */
int ss_single_scatter_light_sample(const ss_scene *scene, unsigned geom_id, ss_vec3 x, double eta,
                                   ss_rng *rng, ss_single_scatter_light *l, ss_path_stats *stats);

/* Single scattering at exit point x_o (hit, seen along d) of a translucent
 * material whose medium is a grid or micro-flakes (volume.h): the estimate
 * of ss_single_scatter with volpath's tracking. The first event
 * along the refracted exit ray is sampled by delta tracking against the
 * majorant (exact free-flight sampling in homogeneous flakes) with a hero
 * channel and volpath's spectral-MIS weights; the flakes scatter by their
 * sigma_s(w) along that ray and their phase function toward the light;
 * the transmittance along the refracted entry segment, and beyond the
 * object's boundary through any media, by ratio tracking. Delta lights
 * behind a refracting boundary enter by Jensen et al.'s approximation
 * (ss_single_scatter_light), not by MNEE. Direct light only. */
ss_rgb ss_volume_single_scatter(const ss_scene *scene, const ss_material *m, const ss_hit *hit,
                                ss_vec3 d, ss_rng *rng, ss_path_stats *stats);

#endif
