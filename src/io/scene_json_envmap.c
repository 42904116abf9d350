/* The scene reader: an environment light's map, its orientation and its
 * scale (see envmap.h for the orientation's meaning). */
#include "io/scene_json.h"

#include "subsurf/envmap.h"
#include "subsurf/texture_io.h"

#include <stdio.h>

ss_status ss_scene_json_envmap(ss_scene_reader *r, const cJSON *obj, ss_light *l) {
  ss_json_ctx *c = &r->json;
  double scale = 1.0, rotation = 0.0;
  ss_vec3 up = ss_vec3_make(0, 1, 0), front = ss_vec3_make(0, 0, -1);
  char file[SS_PATH_SIZE] = "", path[2 * SS_PATH_SIZE];
  ss_status st = ss_json_number(c, obj, "scale", 0.0, SS_LIGHT_MAX_VALUE, &scale);
  l->value = ss_rgb_scale(l->value, scale);
  if (st != SS_OK || !cJSON_HasObjectItem(obj, "map")) {
    if (st == SS_OK && (cJSON_HasObjectItem(obj, "up") || cJSON_HasObjectItem(obj, "front") ||
                        cJSON_HasObjectItem(obj, "rotation"))) {
      const char *key = cJSON_HasObjectItem(obj, "up")      ? "up"
                        : cJSON_HasObjectItem(obj, "front") ? "front"
                                                            : "rotation";
      st = ss_json_fail_key(c, key, "orients a map: give \"map\" too");
    }
    return st;
  }
  st = ss_json_string(c, obj, "map", file, sizeof file);
  if (st == SS_OK)
    st = ss_json_vec3(c, obj, "up", &up);
  if (st == SS_OK)
    st = ss_json_vec3(c, obj, "front", &front);
  if (st == SS_OK)
    st = ss_json_number(c, obj, "rotation", -360.0, 360.0, &rotation);
  if (st == SS_OK && !file[0]) {
    st = ss_json_fail_key(c, "map", "must not be empty");
  }
  if (st != SS_OK) {
    return st;
  }
  ss_envmap_frame frame;
  const char *bad_key;
  if (ss_envmap_frame_make(up, front, rotation, &frame, &bad_key, c->err) != SS_OK) {
    ss_json_push_key(c, bad_key);
    st = ss_json_wrap(c, SS_ERR_PARSE);
    ss_json_pop(c);
    return st;
  }
  snprintf(path, sizeof path, file[0] == '/' ? "%s%s" : "%s/%s", file[0] == '/' ? "" : r->base_dir,
           file);
  ss_image *img;
  /* A PNG map holds sRGB-encoded colours, as a colour texture does. */
  st = ss_texture_image_read(path, 1, &img, c->err);
  if (st == SS_OK && (st = ss_envmap_create(img, &frame, &l->map, c->err)) != SS_OK) {
    ss_error_prefix(c->err, "%s: ", path);
  }
  if (st != SS_OK) {
    ss_json_push_key(c, "map");
    st = ss_json_wrap(c, st == SS_ERR_IO ? SS_ERR_IO : SS_ERR_PARSE);
    ss_json_pop(c);
  }
  return st;
}
