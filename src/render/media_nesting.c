/* Nested and touching media (media_nesting.h): the rules of priorities of
 * Schmidt & Budge 2002, "Simple Nested Dielectrics in Ray Traced Images",
 * checked on the geometry once. */
#include "render/media_nesting.h"

#include "render/mesh_apart.h"

#include <math.h>

static int is_region(const ss_scene *s, const ss_shape *sh) {
  return sh->material >= 0 && s->materials[sh->material].kind == SS_MATERIAL_INTERFACE;
}

static double diagonal(const ss_mesh *m) {
  ss_vec3 lo, hi;
  ss_mesh_bounds(m, &lo, &hi);
  return ss_vec3_length(ss_vec3_sub(hi, lo));
}

/* The rules for two different materials whose regions overlap. */
static ss_status check_pair(const ss_scene *s, const ss_shape *a, const ss_shape *b,
                            const char *how, ss_error *err) {
  const ss_material *ma = &s->materials[a->material], *mb = &s->materials[b->material];
  if (ma->priority == mb->priority) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "shapes '%s' (material '%s') and '%s' (material '%s') %s with the same "
                        "priority %d: give the material that fills the overlap a higher "
                        "'priority'",
                        a->name, ma->name, b->name, mb->name, how, ma->priority);
  }
  for (int k = 0; k < 2; ++k) {
    const ss_material *m = k ? mb : ma, *o = k ? ma : mb;
    if (m->boundary == SS_BOUNDARY_INDEX_MATCHED && o->eta != 1.0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "shapes '%s' and '%s' %s, and material '%s' is index-matched (no index "
                          "of its own) against '%s' of eta %g: the interface between them has no "
                          "defined index; give '%s' a \"smooth\" or \"rough\" 'boundary' and an "
                          "'eta'",
                          a->name, b->name, how, m->name, o->name, o->eta, m->name);
    }
  }
  return SS_OK;
}

ss_status ss_scene_check_media(ss_scene *s, ss_error *err) {
  s->nested_material = -1;
  s->camera_media.n = 0;
  for (size_t i = 0; i < s->num_shapes; ++i) {
    for (size_t j = i + 1; j < s->num_shapes && is_region(s, &s->shapes[i]); ++j) {
      const ss_shape *a = &s->shapes[i], *b = &s->shapes[j];
      if (!is_region(s, b)) {
        continue;
      }
      double eps = 1e-6 * fmax(diagonal(a->mesh), diagonal(b->mesh));
      ss_mesh_relation rel = ss_mesh_relation_of(a->mesh, b->mesh, eps);
      if (rel == SS_MESHES_UNKNOWN) {
        return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
      }
      if (rel == SS_MESHES_APART) {
        continue;
      }
      const char *how = rel == SS_MESHES_TOUCH ? "touch or cross" : "nest";
      ss_status st;
      if (a->material != b->material && (st = check_pair(s, a, b, how, err)) != SS_OK) {
        return st;
      }
      s->nested_material = a->material;
    }
  }
  for (size_t i = 0; i < s->num_materials && s->nested_material >= 0; ++i) {
    if (ss_material_varies(&s->materials[i])) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "material '%s' has a textured 'albedo' or 'mfp', and the media of "
                          "material '%s' touch or nest: a scene with nested media needs "
                          "constant coefficients",
                          s->materials[i].name, s->materials[s->nested_material].name);
    }
  }
  for (size_t i = 0; i < s->num_shapes && s->nested_material >= 0; ++i) {
    const ss_shape *sh = &s->shapes[i];
    if (!is_region(s, sh) || !ss_mesh_contains(sh->mesh, s->camera.position)) {
      continue;
    }
    if (s->camera_media.n == SS_MEDIUM_STACK_SIZE) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "the camera lies inside more than %d shapes bounding media",
                          SS_MEDIUM_STACK_SIZE);
    }
    s->camera_media.material[s->camera_media.n++] = sh->material;
  }
  return SS_OK;
}
