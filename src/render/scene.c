/* Scene assembly and commit (see scene.h). */
#include "subsurf/scene.h"

#include "render/media_nesting.h"
#include "render/mesh_apart.h"
#include "render/name_index.h"
#include "subsurf/grid.h"
#include "subsurf/volume.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_scene_create(ss_scene **out, ss_error *err) {
  ss_scene *s = calloc(1, sizeof *s);
  *out = NULL;
  if (!s) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  ss_camera_default(&s->camera);
  snprintf(s->integrator.name, sizeof s->integrator.name, "volpath");
  s->integrator.max_depth = 100000;
  s->integrator.rr_depth = 5;
  s->render.spp = 16;
  s->render.png = 1;
  s->render.table_cache = 1;
  s->environment = -1;
  *out = s;
  return SS_OK;
}

void ss_scene_destroy(ss_scene *s) {
  if (!s) {
    return;
  }
  ss_accel_destroy(s->accel);
  ss_subsurface_destroy(s->subsurface);
  free(s->see_through);
  for (size_t i = 0; i < s->num_shapes; ++i) {
    ss_mesh_destroy(s->shapes[i].mesh);
  }
  for (size_t i = 0; i < s->num_lights; ++i) {
    ss_light_free(&s->lights[i]);
  }
  for (size_t i = 0; i < s->num_textures; ++i) {
    ss_texture_destroy(s->textures[i]);
  }
  free(s->textures);
  for (size_t i = 0; i < s->num_media; ++i) {
    ss_medium_release_volume(&s->media[i]);
  }
  free(s->media);
  free(s->materials);
  free(s->shapes);
  free(s->lights);
  ss_name_index_destroy(s->shape_index);
  ss_name_index_destroy(s->light_index);
  free(s);
}

/* Grows an array by one element; returns the new element or NULL. The
 * storage doubles when the count reaches a power of two (it holds the next
 * power of two), so that n additions copy O(n) elements. */
static void *grow(void **array, size_t *count, size_t elem) {
  size_t n = *count;
  if ((n & (n - 1)) == 0) {
    void *p = realloc(*array, (n ? 2 * n : 1) * elem);
    if (!p) {
      return NULL;
    }
    *array = p;
  }
  return (char *)*array + (*count)++ * elem;
}

static ss_named shape_names(const ss_scene *s) {
  return (ss_named){s->shapes ? s->shapes->name : NULL, sizeof *s->shapes};
}

static ss_named light_names(const ss_scene *s) {
  return (ss_named){s->lights ? s->lights->name : NULL, sizeof *s->lights};
}

static ss_status check_name(const char *kind, const char *name, int existing, ss_error *err) {
  if (!name[0]) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: empty name", kind);
  }
  if (existing >= 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s '%s' is defined twice", kind, name);
  }
  return SS_OK;
}

ss_status ss_scene_add_medium(ss_scene *s, const ss_medium *m, int *index, ss_error *err) {
  ss_status st = check_name("medium", m->name, ss_scene_find_medium(s, m->name), err);
  ss_medium *dst = st == SS_OK ? grow((void **)&s->media, &s->num_media, sizeof *dst) : NULL;
  if (!dst) {
    ss_grid_destroy(m->grid);
    return st != SS_OK ? st : ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  *dst = *m;
  dst->flakes = NULL; /* derived at commit */
  dst->majorant_exceeded = NULL;
  if (index) {
    *index = (int)s->num_media - 1;
  }
  return SS_OK;
}

ss_status ss_scene_add_material(ss_scene *s, const ss_material *m, int *index, ss_error *err) {
  ss_status st = check_name("material", m->name, ss_scene_find_material(s, m->name), err);
  if (st != SS_OK) {
    return st;
  }
  ss_material *dst = grow((void **)&s->materials, &s->num_materials, sizeof *dst);
  if (!dst) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  *dst = *m;
  if (index) {
    *index = (int)s->num_materials - 1;
  }
  return SS_OK;
}

ss_status ss_scene_add_texture(ss_scene *s, ss_texture *t, ss_error *err) {
  ss_texture **dst = grow((void **)&s->textures, &s->num_textures, sizeof *dst);
  if (!dst) {
    ss_texture_destroy(t);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  *dst = t;
  return SS_OK;
}

ss_status ss_scene_add_shape(ss_scene *s, const char *name, ss_mesh *mesh, int material, int *index,
                             ss_error *err) {
  ss_status st = check_name("shape", name, ss_scene_find_shape(s, name), err);
  if (st == SS_OK && strlen(name) >= SS_NAME_SIZE) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "shape name '%s' is too long", name);
  }
  if (st == SS_OK && (material < -1 || material >= (int)s->num_materials)) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "shape '%s': no material %d", name, material);
  }
  if (st == SS_OK && (st = ss_mesh_validate(mesh, NULL, err)) != SS_OK) {
    ss_error_prefix(err, "shape '%s': ", name);
  }
  ss_material_param param;
  if (st == SS_OK && material >= 0 && !mesh->uvs &&
      ss_material_uses_uv(&s->materials[material], &param)) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "shape '%s': material '%s' textures '%s' by texture coordinates, but the "
                      "mesh has none",
                      name, s->materials[material].name, ss_material_param_name(param));
  }
  ss_vec3 lo, hi;
  ss_mesh_bounds(mesh, &lo, &hi);
  if (st == SS_OK && mesh->num_vertices > 0 && !(ss_in_world(lo) && ss_in_world(hi))) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "shape '%s': vertices must have coordinates in [-%g, %g]", name,
                      SS_WORLD_LIMIT, SS_WORLD_LIMIT);
  }
  if (st == SS_OK && material >= 0 && s->materials[material].kind == SS_MATERIAL_INTERFACE) {
    /* A medium (or a dielectric's interior) is only well defined inside a
     * closed, outward-oriented surface: otherwise paths leak. Generated
     * shapes are closed by construction (mesh.h). */
    if (!mesh->closed && (st = ss_mesh_check_closed(mesh, err)) != SS_OK) {
      ss_error_prefix(err, "shape '%s': material '%s' needs a closed mesh: ", name,
                      s->materials[material].name);
    } else if (!(ss_mesh_signed_volume(mesh) > 0.0)) {
      st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "shape '%s': the mesh is oriented inward (negative volume); flip its "
                        "faces",
                        name);
    }
  }
  if (st != SS_OK) {
    ss_mesh_destroy(mesh);
    return st;
  }
  ss_shape *dst = grow((void **)&s->shapes, &s->num_shapes, sizeof *dst);
  if (dst) {
    memset(dst, 0, sizeof *dst);
    snprintf(dst->name, sizeof dst->name, "%s", name);
    if (ss_name_index_add(&s->shape_index, shape_names(s), (int)s->num_shapes - 1) != 0) {
      s->num_shapes--;
      dst = NULL;
    }
  }
  if (!dst) {
    ss_mesh_destroy(mesh);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  dst->mesh = mesh;
  dst->material = material;
  dst->light = -1;
  if (index) {
    *index = (int)s->num_shapes - 1;
  }
  return SS_OK;
}

ss_status ss_scene_add_light(ss_scene *s, const ss_light *l, int *index, ss_error *err) {
  ss_status st = check_name("light", l->name,
                            ss_name_index_find(s->light_index, light_names(s), l->name), err);
  if (st != SS_OK) {
    return st;
  }
  if (l->type == SS_LIGHT_AREA) {
    if (l->shape < 0 || l->shape >= (int)s->num_shapes) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "light '%s': no shape %d", l->name,
                          l->shape);
    }
    if (s->shapes[l->shape].light >= 0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "light '%s': shape '%s' already emits light", l->name,
                          s->shapes[l->shape].name);
    }
  }
  if (l->type == SS_LIGHT_ENVIRONMENT && s->environment >= 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "light '%s': a scene has at most one environment light", l->name);
  }
  ss_light *dst = grow((void **)&s->lights, &s->num_lights, sizeof *dst);
  if (dst) {
    *dst = *l;
    if (ss_name_index_add(&s->light_index, light_names(s), (int)s->num_lights - 1) != 0) {
      s->num_lights--;
      dst = NULL;
    }
  }
  if (!dst) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  memset(&dst->tris, 0, sizeof dst->tris);
  int i = (int)s->num_lights - 1;
  if (l->type == SS_LIGHT_AREA) {
    s->shapes[l->shape].light = i;
  }
  if (l->type == SS_LIGHT_ENVIRONMENT) {
    s->environment = i;
  }
  if (index) {
    *index = i;
  }
  return SS_OK;
}

int ss_scene_find_medium(const ss_scene *s, const char *name) {
  for (size_t i = 0; i < s->num_media; ++i) {
    if (!strcmp(s->media[i].name, name)) {
      return (int)i;
    }
  }
  return -1;
}

int ss_scene_find_material(const ss_scene *s, const char *name) {
  for (size_t i = 0; i < s->num_materials; ++i) {
    if (!strcmp(s->materials[i].name, name)) {
      return (int)i;
    }
  }
  return -1;
}

int ss_scene_find_shape(const ss_scene *s, const char *name) {
  return ss_name_index_find(s->shape_index, shape_names(s), name);
}

int ss_scene_emits(const ss_scene *s) {
  for (size_t i = 0; i < s->num_lights; ++i) {
    const ss_rgb v = s->lights[i].value;
    if (v.c[0] > 0.0 || v.c[1] > 0.0 || v.c[2] > 0.0) {
      return 1;
    }
  }
  return 0;
}

ss_status ss_scene_set_integrator_option(ss_scene *s, const char *name, double value,
                                         ss_error *err) {
  ss_integrator_settings *in = &s->integrator;
  if (strlen(name) >= SS_NAME_SIZE) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "integrator option '%s': name too long",
                        name);
  }
  for (size_t i = 0; i < in->num_options; ++i) {
    if (!strcmp(in->options[i].name, name)) {
      in->options[i].value = value;
      return SS_OK;
    }
  }
  if (in->num_options == SS_INTEGRATOR_MAX_OPTIONS) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "integrator: more than %d options",
                        SS_INTEGRATOR_MAX_OPTIONS);
  }
  snprintf(in->options[in->num_options].name, SS_NAME_SIZE, "%s", name);
  in->options[in->num_options++].value = value;
  return SS_OK;
}

double ss_scene_integrator_option(const ss_scene *s, const char *name, double fallback) {
  for (size_t i = 0; i < s->integrator.num_options; ++i) {
    if (!strcmp(s->integrator.options[i].name, name)) {
      return s->integrator.options[i].value;
    }
  }
  return fallback;
}

ss_status ss_scene_commit(ss_scene *s, ss_error *err) {
  if (s->committed) {
    return SS_OK;
  }
  ss_status st = ss_camera_init(&s->camera, err);
  if (st != SS_OK) {
    return st;
  }
  if (s->render.spp < 1) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "render: spp must be >= 1, got %d",
                        s->render.spp);
  }
  if (!(s->render.time_limit >= 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "render: time_limit must be >= 0");
  }
  for (size_t i = 0; i < s->num_media; ++i) {
    if ((st = ss_medium_init(&s->media[i], err)) != SS_OK ||
        (st = ss_medium_prepare_volume(&s->media[i], err)) != SS_OK) {
      return st;
    }
  }
  for (size_t i = 0; i < s->num_materials; ++i) {
    ss_material *m = &s->materials[i];
    if (m->medium >= (int)s->num_media) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "material '%s': no medium %d", m->name,
                          m->medium);
    }
    if ((st = ss_material_init(m, err)) != SS_OK ||
        (st = ss_material_link(m, s->materials, i, err)) != SS_OK) {
      return st;
    }
  }
  if (s->num_shapes == 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "scene: no shapes");
  }
  if ((st = ss_scene_check_media(s, err)) != SS_OK) {
    return st;
  }
  for (size_t i = 0; i < s->num_lights; ++i) {
    ss_light *l = &s->lights[i];
    const ss_mesh *mesh = l->type == SS_LIGHT_AREA ? s->shapes[l->shape].mesh : NULL;
    if ((st = ss_light_init(l, mesh, err)) != SS_OK) {
      return st;
    }
  }
  ss_subsurface_destroy(s->subsurface);
  s->subsurface = NULL;
  if ((st = ss_subsurface_create(s, &s->subsurface, err)) != SS_OK) {
    return st;
  }
  const ss_mesh **meshes = malloc(s->num_shapes * sizeof *meshes);
  free(s->see_through);
  s->see_through = malloc(s->num_shapes);
  if (!meshes || !s->see_through) {
    free(meshes);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  for (size_t i = 0; i < s->num_shapes; ++i) {
    int mat = s->shapes[i].material;
    meshes[i] = s->shapes[i].mesh;
    s->see_through[i] = mat >= 0 && ss_material_is_null(&s->materials[mat]);
  }
  st = ss_accel_create(meshes, s->num_shapes, &s->accel, err);
  free(meshes);
  if (st != SS_OK) {
    return st;
  }
  for (size_t i = 0; i < s->num_lights; ++i) {
    ss_light_bind(&s->lights[i], s->accel);
  }
  ss_accel_bounds(s->accel, &s->bounds_lo, &s->bounds_hi);
  s->committed = 1;
  return SS_OK;
}
