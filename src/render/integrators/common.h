/* Helpers shared by the integrators (private to src/render/integrators). */
#ifndef SUBSURF_RENDER_INTEGRATORS_COMMON_H
#define SUBSURF_RENDER_INTEGRATORS_COMMON_H

#include "subsurf/integrator.h"

/* Veach1997 eq. 9.13: the power heuristic with beta = 2. */
static inline double ss_power_heuristic(double pf, double pg) {
  double f = pf * pf, g = pg * pg;
  return f + g > 0.0 ? f / (f + g) : 0.0;
}

/* Picks one light uniformly; returns its index (or -1 when there is none)
 * and its probability in *pmf. */
int ss_pick_light(const ss_scene *scene, double u, double *pmf);
/* A light picked (ss_pick_light, one uniform) and sampled from p (two
 * uniforms, drawn also when there is no light): 1 with *ls and the pick's
 * probability *pmf, or 0 when the scene has no light or the sample failed. */
int ss_sample_light(const ss_scene *scene, ss_vec3 p, ss_rng *rng, ss_light_sample *ls,
                    double *pmf);
/* The probability that ss_pick_light returns a given light. */
static inline double ss_light_pmf(const ss_scene *scene) {
  return scene->num_lights ? 1.0 / (double)scene->num_lights : 0.0;
}

/* The shadow ray from p (geometric normal n, zero off surfaces) toward a
 * light sample. Index-matched interfaces are crossed (they are not events);
 * any other surface blocks. When `with_media` is set, the homogeneous media
 * crossed attenuate per channel (Beer-Lambert), starting in `medium` (-1:
 * none) and switching at every index-matched crossing. Returns the
 * transmittance (black when blocked). */
ss_rgb ss_shadow_transmittance(const ss_scene *scene, ss_vec3 p, ss_vec3 n, int medium,
                               const ss_light_sample *ls, int with_media, ss_path_stats *stats);
/* The same, starting in the medium of coefficients `med` (NULL: none). A
 * shadow ray entering a translucent material whose coefficients vary takes
 * those at its entry point (ss_material_optics_at), as volpath's paths do. */
ss_rgb ss_shadow_transmittance_in(const ss_scene *scene, ss_vec3 p, ss_vec3 n, const ss_medium *med,
                                  const ss_light_sample *ls, int with_media, ss_path_stats *stats);

/* The same for volpath's spectral MIS: grids crossed are tracked by ratio
 * tracking with the path's hero channel (volume.h), which multiplies *a_l
 * by the light technique's density ratio; other media as above. Without a
 * tracking state (tk NULL) a grid blocks: only volpath renders grids. */
typedef struct {
  int hero;
  ss_rng *rng;
  ss_rgb *a_l;
} ss_tracking;
ss_rgb ss_shadow_transmittance_tracked(const ss_scene *scene, ss_vec3 p, ss_vec3 n,
                                       const ss_medium *med, const ss_light_sample *ls,
                                       int with_media, const ss_tracking *tk, ss_path_stats *stats);

/* The BSDF frame of a hit: the geometric normal for dielectric interfaces
 * (exact for the mesh, and the side a direction lies on then agrees with the
 * geometry) and the shading normal for surfaces (diffuse, metals, ...). */
static inline ss_frame ss_hit_frame(const ss_material *m, const ss_hit *hit) {
  return ss_frame_from_normal(m->kind != SS_MATERIAL_INTERFACE ? hit->ns : hit->ng);
}

/* A material with a medium behind its boundary: what the BSSRDF and
 * diffusion integrators treat as translucent. */
static inline int ss_material_is_translucent(const ss_material *m) {
  return m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0;
}

/* Where a hit looks up its material's textures. */
static inline ss_texcoord ss_hit_texcoord(const ss_hit *hit) {
  ss_texcoord tc = {hit->st[0], hit->st[1], hit->p};
  return tc;
}

static inline ss_rgb ss_rgb_from_vec3(ss_vec3 v) { return ss_rgb_make(v.x, v.y, v.z); }

/* Emission of the shape hit along direction d (unit), black when none. */
static inline ss_rgb ss_hit_emission(const ss_scene *scene, const ss_hit *hit, ss_vec3 d) {
  int l = scene->shapes[hit->geom_id].light;
  return l >= 0 ? ss_light_le(&scene->lights[l], hit->ng, ss_vec3_neg(d)) : ss_rgb_gray(0.0);
}

/* SS_OK when the scene's media are apart; else an error naming a material
 * whose medium touches or contains another, for integrators that cannot
 * follow nested media (only volpath carries a stack of media). */
ss_status ss_refuse_nested_media(const ss_scene *scene, const char *integrator, ss_error *err);
/* SS_OK when no translucent material has a textured albedo or mfp; else a
 * bad-input error naming the first, for integrators whose kernels hold
 * constant coefficients; `instead` says what to use. */
ss_status ss_refuse_varying_media(const ss_scene *scene, const char *integrator,
                                  const char *instead, ss_error *err);

/* Number of index-matched crossings after which a ray is abandoned (a ray
 * grazing a tessellated surface can otherwise alternate forever). */
#define SS_MAX_NULL_CROSSINGS 256

/* Passes an index-matched interface: the ray continues past the hit in the
 * same direction. Returns 0 (abandon the path) once it has made more than
 * SS_MAX_NULL_CROSSINGS crossings. */
int ss_cross_null_interface(const ss_hit *hit, ss_ray *ray, int *crossings, ss_path_stats *stats);

#endif
