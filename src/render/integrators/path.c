/* `path`: unidirectional path tracing of surfaces (media are ignored:
 * interfaces act as clear dielectrics), with next-event estimation and
 * multiple importance sampling of BSDF and light sampling by the power
 * heuristic (Veach1997 ch. 9; pbrt-v4's PathIntegrator). */
#include "render/integrators/emission.h"
#include "render/integrators/surface_vertex.h"

static ss_rgb path_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                      ss_path_stats *stats) {
  (void)state;
  ss_rgb L = ss_rgb_gray(0.0);
  ss_path_state s = ss_path_start(ray.o);
  int depth = 0, crossings = 0;
  for (;;) {
    ss_hit hit;
    int found = ss_accel_intersect(scene->accel, &ray, &hit);
    L = ss_rgb_add(L, ss_path_emitted(scene, &s, found ? &hit : NULL, ray.d));
    const ss_material *m = found ? ss_scene_hit_material(scene, &hit) : NULL;
    if (!m) {
      break;
    }
    if (ss_material_is_null(m)) {
      if (!ss_cross_null_interface(&hit, &ray, &crossings, stats)) {
        break;
      }
      continue;
    }
    ss_vertex v;
    if (depth++ >= scene->integrator.max_depth) {
      break;
    }
    ss_vertex_at_bsdf(&v, m, &hit, ray.d);
    if (!ss_path_advance(scene, &s, &v, depth, &ray, &L, rng, stats)) {
      break;
    }
  }
  return L;
}

static ss_status path_check(const ss_scene *scene, ss_error *err) {
  return ss_refuse_nested_media(scene, "path", err);
}

static ss_status path_prepare(const ss_scene *scene, void **state, ss_error *err) {
  *state = NULL;
  return path_check(scene, err);
}

const ss_integrator_ops ss_integrator_path = {
    .name = "path",
    .summary = "surface path tracing, BSDF and light sampling with MIS (Veach 1997)",
    .options = NULL,
    .check = path_check,
    .prepare = path_prepare,
    .release = NULL,
    .li = path_li,
};
