/* `volpath`: the ground-truth volumetric path tracer, the medium walk
 * (medium_walk.h: exact free flights, phase sampling, Fresnel events,
 * spectral MIS over the channels, nested media and textured materials
 * followed) with the parts its options switch on: manifold next-event
 * estimation through smooth boundaries (mnee.h, the `mnee` option) and, in
 * a scene lit by one delta light, the walk guided toward it (guided_walk.h,
 * the `guide` option). */
#include "render/integrators/medium_walk.h"
#include "subsurf/volume.h"

#include <stdlib.h>

/* The `guide` option's default: the probability of the guided technique
 * (0: the classical walk); 0.3-0.5 measured best on the index-matched skin
 * sphere (bench/RESULTS.md). */
#define SS_VOLPATH_DEFAULT_GUIDE 0.5

/* volpath's options: MNEE's (mnee.h) and `guide`, the probability of the
 * guided technique at a medium vertex (guided_walk.h). */
static const char *const volpath_option_names[] = {
    "mnee", "mnee_iterations", "mnee_tolerance", "mnee_solid_angle", "guide", NULL};

typedef struct {
  ss_mnee_options mnee;
  ss_guide guide;
} volpath_state;

static ss_status guide_option_read(const ss_scene *scene, double *q, ss_error *err) {
  *q = ss_scene_integrator_option(scene, "guide", SS_VOLPATH_DEFAULT_GUIDE);
  if (!(*q >= 0.0 && *q < 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "volpath: option guide: expected a probability in [0, 1), got %g", *q);
  }
  return SS_OK;
}

static ss_status volpath_check(const ss_scene *scene, ss_error *err) {
  /* The medium stack's shadow rays and free flights are homogeneous and
   * isotropic in direction. */
  for (size_t i = 0; scene->nested_material >= 0 && i < scene->num_media; ++i) {
    if (ss_medium_is_volume(&scene->media[i])) {
      return ss_error_set(err, SS_ERR_UNSUPPORTED,
                          "volpath: medium '%s': micro-flake and gridded media cannot be nested "
                          "or touch other media",
                          scene->media[i].name);
    }
  }
  ss_mnee_options o;
  double q;
  ss_status st = ss_mnee_options_read(scene, &o, err);
  return st != SS_OK ? st : guide_option_read(scene, &q, err);
}

/* The state is the MNEE options (mnee.h) and the guide (guided_walk.h),
 * checked before the first sample. */
static ss_status volpath_prepare(const ss_scene *scene, void **state, ss_error *err) {
  double q;
  ss_status st = volpath_check(scene, err);
  if (st != SS_OK || (st = guide_option_read(scene, &q, err)) != SS_OK) {
    return st;
  }
  volpath_state *v = malloc(sizeof *v);
  if (!v) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "volpath: out of memory");
  }
  if ((st = ss_mnee_options_read(scene, &v->mnee, err)) != SS_OK ||
      (st = ss_guide_init(&v->guide, scene, q, err)) != SS_OK) {
    free(v);
    return st;
  }
  *state = v;
  return SS_OK;
}

static void volpath_release(void *state) {
  volpath_state *v = state;
  if (v) {
    ss_guide_free(&v->guide);
  }
  free(v);
}

static ss_rgb volpath_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                         ss_path_stats *stats) {
  const volpath_state *v = state;
  ss_walk_parts parts = {v ? &v->mnee : &ss_mnee_defaults, v ? &v->guide : NULL, NULL};
  return ss_medium_walk(scene, &parts, ray, rng, stats);
}

const ss_integrator_ops ss_integrator_volpath = {
    .name = "volpath",
    .summary = "volumetric path tracing with spectral MIS over RGB and manifold next-event "
               "estimation through smooth boundaries (ground truth)",
    .options = volpath_option_names,
    .check = volpath_check,
    .prepare = volpath_prepare,
    .release = volpath_release,
    .li = volpath_li,
};
