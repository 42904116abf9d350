/* The translucent objects' pixels (translucent_mask.h). */
#include "subsurf/translucent_mask.h"

#include "subsurf/camera.h"

/* Steps past clear index-matched surfaces at most this many times. */
#define MAX_CROSSINGS 64

static int is_translucent(const ss_material *m) {
  return m && m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0;
}

static int sees_translucent(const ss_scene *scene, ss_ray ray) {
  for (int k = 0; k < MAX_CROSSINGS; ++k) {
    ss_hit hit;
    if (!ss_accel_intersect(scene->accel, &ray, &hit)) {
      return 0;
    }
    const ss_material *m = ss_scene_hit_material(scene, &hit);
    if (is_translucent(m)) {
      return 1;
    }
    if (!m || !ss_material_is_null(m)) {
      return 0;
    }
    ray = ss_ray_spawn(hit.p, hit.ng, ray.d);
  }
  return 0;
}

ss_status ss_translucent_mask(const ss_scene *scene, ss_image **out, ss_error *err) {
  *out = NULL;
  if (!scene->committed) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "translucent mask: scene not committed");
  }
  int w = scene->camera.width, h = scene->camera.height;
  ss_image *mask = ss_image_create(w, h, 1);
  if (!mask) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "translucent mask: out of memory for %d x %d", w, h);
  }
  ss_camera centre = scene->camera; /* a box filter's sample (0.5, 0.5) is the centre */
  centre.filter = ss_filter_default(SS_FILTER_BOX);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_ray ray = ss_camera_generate_ray(&centre, x, y, 0.5, 0.5);
      *ss_image_pixel(mask, x, y) = (float)sees_translucent(scene, ray);
    }
  }
  *out = mask;
  return SS_OK;
}
