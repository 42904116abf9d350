/* The volumetric random walk of `volpath` and `hybrid` (medium_walk.c
 * documents it): exact free flights through the media bounded by the
 * scene's closed meshes, phase sampling, surface events, next-event
 * estimation and spectral MIS over the channels (spectral_mis.h). The
 * optional parts a strategy switches on are the manifold next-event
 * estimation through smooth boundaries (mnee.h) and the guided walk toward
 * a delta light (guided_walk.h); textured materials and nested media are
 * followed whenever the scene has them. A strategy may react to the walk's
 * medium events (the path entering a medium, scattering in one), and end
 * the walk there with an estimate of its own (the hybrid's hand-over).
 * Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_MEDIUM_WALK_H
#define SUBSURF_RENDER_INTEGRATORS_MEDIUM_WALK_H

#include "render/integrators/guided_walk.h"
#include "render/integrators/mnee.h"
#include "render/integrators/path_state.h"
#include "render/integrators/spectral_mis.h"

/* What a reaction sees of the path at a medium event: its throughput and
 * MIS state, its channel ratios and hero, and the events so far. */
typedef struct {
  const ss_path_state *k;
  const ss_spectral *sp;
  int depth;
} ss_walk_view;

/* A strategy's reactions to medium events; each returns 1 to end the walk
 * there, having added its estimate of the rest of the path to *L. */
typedef struct {
  /* The path entered the medium of coefficients `med` behind the surface of
   * material m at hit (refracted or crossed into it). */
  int (*entered)(void *ctx, const ss_walk_view *w, const ss_material *m, const ss_medium *med,
                 const ss_hit *hit, ss_rgb *L, ss_rng *rng, ss_path_stats *stats);
  /* A real scattering event at p (after the throughput's renormalisation). */
  int (*scattered)(void *ctx, const ss_walk_view *w, ss_vec3 p, ss_rgb *L, ss_rng *rng,
                   ss_path_stats *stats);
  void *ctx;
} ss_walk_reaction;

/* The parts a strategy switches on: MNEE's options (ss_mnee_defaults: off),
 * the guide (NULL or q = 0: the classical walk) and the reactions (NULL:
 * none). */
typedef struct {
  const ss_mnee_options *mnee;
  const ss_guide *guide;
  const ss_walk_reaction *reaction;
} ss_walk_parts;

/* The radiance along a camera ray. */
ss_rgb ss_medium_walk(const ss_scene *scene, const ss_walk_parts *parts, ss_ray ray, ss_rng *rng,
                      ss_path_stats *stats);

#endif
