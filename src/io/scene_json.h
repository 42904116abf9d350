/* Internal pieces of the scene reader shared by scene_json.c and
 * scene_json_shapes.c. */
#ifndef SUBSURF_IO_SCENE_JSON_H
#define SUBSURF_IO_SCENE_JSON_H

#include "io/json_path.h"
#include "subsurf/scene.h"

typedef struct {
  ss_json_ctx json;
  const char *base_dir;
  ss_scene *scene;
} ss_scene_reader;

/* Each reads one top-level array (the path is already pushed). */
ss_status ss_scene_json_shapes(ss_scene_reader *r, const cJSON *array);
ss_status ss_scene_json_lights(ss_scene_reader *r, const cJSON *array);

/* Reads a translucent material's "bssrdf" (a model name, or an object with
 * "model" and the model's options), "single_scattering" and "lod". */
ss_status ss_scene_json_bssrdf(ss_scene_reader *r, const cJSON *obj, ss_material *m);

/* When the material parameter p's key holds an object, reads it as
 * {"texture": TEX} into m->textures[p] (the scene owns the texture) and
 * checks its values against the parameter's range; otherwise does nothing
 * (the caller reads the constant). */
ss_status ss_scene_json_texture(ss_scene_reader *r, const cJSON *obj, ss_material *m,
                                ss_material_param p);

/* A translucent material's "albedo" and "mfp" (with "g" and
 * "albedo_inversion") instead of "medium": checks the pairing and, when they
 * are given, adds the converted medium (scene_json_albedo.c). The boundary
 * and eta must be read before. */
int ss_scene_json_has_albedo(const cJSON *obj);
ss_status ss_scene_json_albedo(ss_scene_reader *r, const cJSON *obj, ss_material *m);

/* The surface materials (scene_json_surface.c): 1 when `type` names one;
 * reads its keys into m (kind, parameters, parts by name). */
int ss_scene_json_is_surface(const char *type);
ss_status ss_scene_json_surface(ss_scene_reader *r, const cJSON *obj, const char *type,
                                ss_material *m);

/* A medium's "flakes" (read before ss_medium_init) and "grid" (read or
 * generated last, into m->grid, which the scene takes in
 * ss_scene_add_medium); scene_json_volume.c. */
ss_status ss_scene_json_flakes(ss_scene_reader *r, const cJSON *obj, ss_medium *m);
ss_status ss_scene_json_grid(ss_scene_reader *r, const cJSON *obj, ss_medium *m);

/* An environment light's "map" (latitude-longitude image file), "up",
 * "front" and "rotation" into l->map (the light owns it), and its "scale"
 * multiplied into l->value; scene_json_envmap.c. */
ss_status ss_scene_json_envmap(ss_scene_reader *r, const cJSON *obj, ss_light *l);

/* Requires `arr` to be an array of objects; calls fn on each with the index
 * pushed on the path. */
ss_status ss_scene_json_each(ss_scene_reader *r, const cJSON *arr,
                             ss_status (*fn)(ss_scene_reader *r, const cJSON *item, int index));

/* Reads a required string member that names an item of another array;
 * fails with "no <kind> named ..." when find() returns -1. */
ss_status ss_scene_json_reference(ss_scene_reader *r, const cJSON *obj, const char *key,
                                  const char *kind, int (*find)(const ss_scene *, const char *),
                                  int *index);

#endif
