/* A scene in memory: camera, media, materials, shapes (triangle meshes),
 * lights, the integrator to use and the render settings. Scene files
 * (scene_io.h) and tests fill one through the ss_scene_add_* functions,
 * then ss_scene_commit validates the cross references and builds the ray
 * accelerator and the lights' sampling data. A committed scene is read-only
 * and may be shared by any number of threads. */
#ifndef SUBSURF_SCENE_H
#define SUBSURF_SCENE_H

#include "subsurf/accel.h"
#include "subsurf/camera.h"
#include "subsurf/light.h"
#include "subsurf/material.h"
#include "subsurf/mesh.h"
#include "subsurf/status.h"
#include "subsurf/subsurface.h"

#include <stddef.h>
#include <stdint.h>

#define SS_INTEGRATOR_MAX_OPTIONS 16
#define SS_PATH_SIZE 4096

typedef struct {
  char name[SS_NAME_SIZE];
  ss_mesh *mesh; /* owned by the scene */
  int material;  /* index into materials, or -1: a black surface */
  int light;     /* index of the area light emitting from it, or -1 */
} ss_shape;

/* A named numeric option of an integrator (beyond the common ones). */
typedef struct {
  char name[SS_NAME_SIZE];
  double value;
} ss_integrator_option;

typedef struct {
  char name[SS_NAME_SIZE]; /* "path", "volpath", ... (integrator.h) */
  int max_depth;           /* bounces + scattering events per path */
  int rr_depth;            /* Russian roulette starts after this many */
  size_t num_options;
  ss_integrator_option options[SS_INTEGRATOR_MAX_OPTIONS];
  char cache[SS_PATH_SIZE]; /* file of the integrator's precomputation ("": none;
                               irradiance_cache.h) */
} ss_integrator_settings;

typedef struct {
  int spp;
  uint64_t seed;
  double time_limit;         /* seconds; 0: none */
  char output[SS_PATH_SIZE]; /* EXR path ("" : chosen by the caller) */
  int png;                   /* also write a tonemapped PNG beside it */
  int variance;              /* also write <base>-variance.exr */
  double exposure;           /* PNG exposure in stops */
  /* The disk cache of BSSRDF tables (subsurface.h): 0 turns it off;
   * table_cache_dir "" means the default directory. */
  int table_cache;
  char table_cache_dir[SS_PATH_SIZE];
  int crop[4]; /* the scene's crop window (pixels, render.h's ss_render_options.crop); all 0: none
                */
} ss_render_settings;

/* The interface materials whose regions hold a point, in the order they were
 * entered (nested and touching media, SchmidtBudge2002; at most
 * SS_MEDIUM_STACK_SIZE overlap anywhere). */
#define SS_MEDIUM_STACK_SIZE 8
typedef struct {
  int n;
  int material[SS_MEDIUM_STACK_SIZE];
} ss_medium_stack;

typedef struct ss_scene {
  ss_camera camera;
  ss_medium *media;
  size_t num_media;
  ss_material *materials;
  size_t num_materials;
  ss_shape *shapes;
  size_t num_shapes;
  ss_light *lights;
  size_t num_lights;
  ss_texture **textures; /* owned; materials point at them */
  size_t num_textures;
  ss_integrator_settings integrator;
  ss_render_settings render;

  /* Built by ss_scene_commit. */
  ss_accel *accel;
  ss_subsurface *subsurface;  /* the translucent materials' BSSRDFs */
  int environment;            /* index of the environment light, or -1 */
  unsigned char *see_through; /* per shape: 1 for index-matched interfaces */
  /* A material whose region touches or contains another's, or -1 when all
   * media are apart (then paths need no stack of media); with it, the
   * media that contain the camera. */
  int nested_material;
  ss_medium_stack camera_media;
  ss_vec3 bounds_lo, bounds_hi;
  int committed;
  /* The shapes' and lights' names, for lookups in O(1). */
  struct ss_name_index *shape_index, *light_index;
} ss_scene;

/* An empty scene with the default camera (camera.h), integrator "volpath"
 * (max_depth 100000, rr_depth 5), 16 spp, seed 0, no time limit, PNG on,
 * the default table cache, exposure 0 (rays that escape see black unless
 * there is an environment light). */
ss_status ss_scene_create(ss_scene **out, ss_error *err);
void ss_scene_destroy(ss_scene *scene);

/* Each add copies the struct (the shape takes ownership of its mesh, also on
 * failure) and returns its index in *index (may be NULL). Names must be
 * unique within their kind. A shape's mesh is validated (ss_mesh_validate),
 * and a shape whose material is an interface must be closed and outward
 * oriented. A medium's grid (volume.h) passes to the scene, also on
 * failure. */
ss_status ss_scene_add_medium(ss_scene *s, const ss_medium *m, int *index, ss_error *err);
ss_status ss_scene_add_material(ss_scene *s, const ss_material *m, int *index, ss_error *err);
ss_status ss_scene_add_shape(ss_scene *s, const char *name, ss_mesh *mesh, int material, int *index,
                             ss_error *err);
ss_status ss_scene_add_light(ss_scene *s, const ss_light *l, int *index, ss_error *err);
/* Takes ownership of a texture (destroyed with the scene, or at once on
 * failure), for materials (and other textures) to point at. A shape whose
 * material has a texture that reads (u, v) needs a mesh with uvs. */
ss_status ss_scene_add_texture(ss_scene *s, ss_texture *t, ss_error *err);

/* Index of the named item, or -1. */
int ss_scene_find_medium(const ss_scene *s, const char *name);
int ss_scene_find_material(const ss_scene *s, const char *name);
int ss_scene_find_shape(const ss_scene *s, const char *name);
/* 1 when some light has a positive value in some channel: else every image
 * of the scene is black. */
int ss_scene_emits(const ss_scene *s);

/* Sets a numeric integrator option (replacing one of the same name). */
ss_status ss_scene_set_integrator_option(ss_scene *s, const char *name, double value,
                                         ss_error *err);
/* The option's value, or `fallback` when it is not set. */
double ss_scene_integrator_option(const ss_scene *s, const char *name, double fallback);

/* Validates the camera, media, materials and lights, builds the lights'
 * sampling data, the accelerator and the BSSRDF of every translucent
 * material that names a model (subsurface.h). */
ss_status ss_scene_commit(ss_scene *s, ss_error *err);

/* The material of a hit's shape, or NULL for a black surface. */
static inline const ss_material *ss_scene_hit_material(const ss_scene *s, const ss_hit *hit) {
  int m = s->shapes[hit->geom_id].material;
  return m >= 0 ? &s->materials[m] : NULL;
}

#endif
