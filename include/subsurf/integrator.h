/* Light transport integrators, registered by name (in the style of the
 * BSSRDF registry): an integrator estimates the radiance arriving along a
 * camera ray. A new integrator is one file in src/render/integrators/ that
 * defines a `const ss_integrator_ops` plus one line in registry.c. */
#ifndef SUBSURF_INTEGRATOR_H
#define SUBSURF_INTEGRATOR_H

#include "subsurf/accel.h"
#include "subsurf/rgb.h"
#include "subsurf/rng.h"
#include "subsurf/scene.h"
#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

/* Counters of one thread's work; summed into ss_render_stats. */
typedef struct {
  uint64_t camera_rays;
  uint64_t extension_rays; /* closest-hit queries after the camera ray */
  uint64_t shadow_rays;    /* visibility / transmittance queries */
  uint64_t scatter_events; /* real scattering events in media */
  uint64_t probe_rays;     /* BSSRDF probe queries (all hits of one object) */
  uint64_t paths;
} ss_path_stats;

static inline void ss_path_stats_add(ss_path_stats *a, const ss_path_stats *b) {
  a->camera_rays += b->camera_rays;
  a->extension_rays += b->extension_rays;
  a->shadow_rays += b->shadow_rays;
  a->scatter_events += b->scatter_events;
  a->probe_rays += b->probe_rays;
  a->paths += b->paths;
}

typedef struct ss_integrator_ops {
  const char *name;
  const char *summary; /* one line for --help, citing the method */
  /* Names of the integrator-specific numeric options it reads (besides
   * max_depth and rr_depth), NULL-terminated; scene files may set only these.
   * "cache" among them is the file of its precomputation (a string, the
   * scene's integrator.cache), not a number. */
  const char *const *options;
  /* Optional: checks the scene's integrator options and what the
   * integrator refuses, without precomputing (the bad-input failures of
   * prepare, which calls it), so that callers can refuse before any work. */
  ss_status (*check)(const ss_scene *scene, ss_error *err);
  /* Optional: per-scene precomputation before rendering (may be NULL). */
  ss_status (*prepare)(const ss_scene *scene, void **state, ss_error *err);
  void (*release)(void *state);
  /* Radiance along `ray` (a camera ray; counted by the caller). Must use
   * only `rng` for randomness so that results are reproducible. */
  ss_rgb (*li)(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
               ss_path_stats *stats);
} ss_integrator_ops;

size_t ss_integrator_count(void);
const ss_integrator_ops *ss_integrator_at(size_t i);
/* NULL when unknown. */
const ss_integrator_ops *ss_integrator_find(const char *name);
/* "a, b, c" for error messages. */
void ss_integrator_names(char *buf, size_t size);
/* The check of the scene's integrator (ops->check): SS_OK when it has none;
 * an unknown integrator is an error. */
ss_status ss_integrator_check(const ss_scene *scene, ss_error *err);
/* 1 when `option` is max_depth, rr_depth or one of the integrator's own. */
int ss_integrator_accepts_option(const ss_integrator_ops *ops, const char *option);

#endif
