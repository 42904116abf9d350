/* The per-element coefficients of the `fem` integrator from a scene medium
 * (Jakob2010 sec. 5-6.2): one colour channel of an
 * isotropic medium, of micro-flakes, and of either scaled by a grid's
 * density with, for flakes, the grid's per-voxel axis (volume.h), sampled at
 * each tetrahedron's centroid through the ss_fem_medium_fn callback of
 * include/subsurf/fem.h. Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_FEM_MEDIUM_H
#define SUBSURF_RENDER_INTEGRATORS_FEM_MEDIUM_H

#include "subsurf/fem.h"
#include "subsurf/flake_diffusion.h"
#include "subsurf/mat3.h"
#include "subsurf/material.h"

typedef struct {
  const ss_medium *med;
  int channel;
  double min_density; /* densities below min_density max_density are raised to it */
  ss_microflake *mf;  /* flakes about +z with this channel's albedo, or NULL */
  ss_mat3 M1;         /* flakes: M at unit grid density about +z (eq. 34) */
  double mu0_1;       /* flakes: mu0 at unit grid density (eq. 28) */
} ss_fem_scene_medium;

ss_status ss_fem_scene_medium_init(ss_fem_scene_medium *c, const ss_medium *med, int channel,
                                   double min_density, ss_error *err);
void ss_fem_scene_medium_release(ss_fem_scene_medium *c);

/* The ss_fem_medium_fn: (M, mu0) at x (ctx: an ss_fem_scene_medium). */
ss_status ss_fem_scene_medium_at(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err);

/* The shortest transport mean free path anywhere in the medium: 9 / trace M
 * at the largest density (1 / sigma_t' when isotropic). */
double ss_fem_scene_medium_mfp(const ss_fem_scene_medium *c);

/* The attenuation exp(-sigma_a / sigma_s) of the refracted irradiance
 * before the first scattering (Jakob2010 eq. 37), with the reduced
 * sigma_s' for an isotropic medium and sigma_a / sigma_s = (1 - alpha) /
 * alpha for flakes of constant albedo alpha; a grid's density cancels. */
double ss_fem_scene_medium_attenuation(const ss_fem_scene_medium *c);

/* The first scattering events of refracted light entering along the unit
 * direction w at x (density at least min_density of the largest), for the
 * rays' volume source (fem_rays.c): the extinction and the albedo of the
 * first event, the reduced sigma_t' and sigma_s'/sigma_t' when isotropic
 * (the dipole's source depth 1/sigma_t'), and for flakes their sigma_t(w)
 * of Jakob2010 eq. 11 about the local axis reduced by the similarity
 * relation with the mean direction g(w) of the once-scattered light
 * (ss_flake_reduced_first_event: sigma_t (1 - alpha w.g), alpha (1 - w.g) /
 * (1 - alpha w.g)). */
ss_flake_first_event ss_fem_scene_medium_first_event(const ss_fem_scene_medium *c, ss_vec3 x,
                                                     ss_vec3 w);
/* Its extinction alone (what ss_fem_spot_rays asks per direction). */
double ss_fem_scene_medium_sigma(const ss_fem_scene_medium *c, ss_vec3 x, ss_vec3 w);

/* Refinement where the medium varies (fem_size_field.c): the size field of
 * the medium's grid over [lo, hi], sampled at the grid's smallest voxel side,
 * size_min where the coefficients change by 10 % over less than that size
 * (tolerance 0.1), growing by half the distance (grade 0.5) to size_max.
 * *out is NULL for a medium without a grid (nothing varies). */
ss_status ss_fem_scene_medium_size_field(ss_fem_scene_medium *c, ss_vec3 lo, ss_vec3 hi,
                                         double size_min, double size_max, ss_fem_size_field **out,
                                         ss_error *err);

/* An ss_fem_sigma_fn: ss_fem_scene_medium_sigma of ctx at ctx's point. */
typedef struct {
  const ss_fem_scene_medium *medium;
  ss_vec3 at;
} ss_fem_scene_sigma_at;
double ss_fem_scene_sigma_fn(void *ctx, ss_vec3 w);

#endif
