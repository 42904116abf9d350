/* Oriented and heterogeneous media in the renderer (Jakob2010 sec. 4
 * and 7).
 *
 * A scene medium (material.h) may carry micro-flakes (optics.flakes): its
 * extinction and scattering then depend on the direction of travel w,
 *   sigma_t(w) = 2 (sigma_s + sigma_a) sigma(w),  sigma_s(w) = 2 sigma_s s(w)
 * per channel, with sigma(w) the flakes' projected area and s(w) its part
 * weighted by the albedo shape alpha / alpha1 (microflake.h's convention:
 * sigma_s and sigma_a are those of the same flakes oriented uniformly, so
 * uniform flakes are the isotropic medium). The flakes scatter by their
 * phase function (Jakob2010 eq. 13), the same in every channel.
 *
 * A medium may also carry a grid (grid.h): a density d(x) that multiplies
 * both coefficients, and per voxel the flakes' axis. Its free flights are
 * sampled by delta tracking (Woodcock et al. 1965) against the majorant
 * max_x d(x) max_w sigma_t(w), with the spectral-MIS bookkeeping of
 * pbrt-v4's VolPathIntegrator (null collisions update r_u and r_l), and its
 * shadow rays estimate transmittance by ratio tracking (Novak2014)
 * against the same majorant. */
#ifndef SUBSURF_VOLUME_H
#define SUBSURF_VOLUME_H

#include "subsurf/material.h"
#include "subsurf/rng.h"

#include <stdint.h>

/* The medium at a point: the density there and the flakes' axis frame. */
typedef struct {
  double density;
  ss_frame axis;
} ss_volume_point;

/* 1 when the medium's coefficients depend on the point or the direction
 * (flakes or a grid): only volpath traces such media. */
static inline int ss_medium_is_volume(const ss_medium *m) {
  return m->grid || m->optics.flakes.type != SS_FLAKE_NONE;
}

/* Builds the derived data of ss_medium_init for flakes and grids: the flake
 * tables (allocated; released by ss_medium_release_volume), the axis frame
 * and the majorant. */
ss_status ss_medium_prepare_volume(ss_medium *m, ss_error *err);
/* Frees the flake tables and the grid. */
void ss_medium_release_volume(ss_medium *m);

ss_volume_point ss_volume_at(const ss_medium *m, ss_vec3 p);

/* Per-channel extinction and scattering along the unit direction w. */
ss_rgb ss_volume_sigma_t(const ss_medium *m, const ss_volume_point *q, ss_vec3 w);
ss_rgb ss_volume_sigma_s(const ss_medium *m, const ss_volume_point *q, ss_vec3 w);

/* The phase function for propagation directions w_in -> w_out (unit), per
 * unit solid angle, and an exact sample of it (two uniforms for the
 * ordinary phase functions, as volpath always drew; the flakes draw a
 * visible normal). */
double ss_volume_phase_eval(const ss_medium *m, const ss_volume_point *q, ss_vec3 w_in,
                            ss_vec3 w_out);
ss_vec3 ss_volume_phase_sample(const ss_medium *m, const ss_volume_point *q, ss_vec3 w_in,
                               ss_rng *rng);

/* The hero channel chosen uniformly by the uniform number u in [0, 1)
 * (0, 1 or 2; u rounding up to 1 counts as the last). */
static inline int ss_volume_uniform_hero(double u) {
  int h = (int)(3.0 * u);
  return h < 3 ? h : 2;
}

/* The path weights of volpath's spectral MIS (volpath.c). */
typedef struct {
  ss_rgb *beta, *r_u, *r_l;
} ss_volume_weights;

/* A free-flight distance drawn before the segment's end is known: the
 * exponential of the hero channel's sigma_t(d) in a homogeneous medium;
 * INFINITY for a grid (tracked once the segment's end is known). */
double ss_volume_sample_distance(const ss_medium *m, ss_vec3 d, int hero, ss_rng *rng);

/* The events of a segment o + t d (unit d), t in [0, tmax], given t_pre from
 * ss_volume_sample_distance: returns 1 for a scattering event at *t, 0 when
 * the segment reaches tmax, -1 when the path's density vanished (end it).
 * Updates the weights; *tentative, unless NULL, counts delta tracking's
 * collisions (bench_volume's rate). */
int ss_volume_segment(const ss_medium *m, ss_vec3 o, ss_vec3 d, double t_pre, double tmax, int hero,
                      ss_rng *rng, ss_volume_weights w, double *t, uint64_t *tentative);

/* The transmittance over [0, dist] along unit d from o, per channel: exact
 * in a homogeneous medium; in a grid, ratio tracking with the hero's
 * majorant, which multiplies *a_l by the light technique's density ratio
 * (pbrt-v4's r_l of a shadow ray; 1 for exact transmittance). */
ss_rgb ss_volume_transmittance(const ss_medium *m, ss_vec3 o, ss_vec3 d, double dist, int hero,
                               ss_rng *rng, ss_rgb *a_l);

/* Delta and ratio tracking are unbiased only while sigma_t(x, w) <= the
 * majorant: each tentative collision checks it (to a relative 1e-12 of
 * rounding) and counts a violation in the medium (atomically; the estimate
 * goes on, biased). The count since ss_medium_prepare_volume: zero unless
 * the majorant is wrong (the caller reports it; the library does not print). */
uint64_t ss_medium_majorant_exceeded(const ss_medium *m);

#endif
