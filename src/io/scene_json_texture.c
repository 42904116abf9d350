/* Textured material parameters in scene files: a colour (or
 * data) parameter is a constant or {"texture": TEX}, TEX an image file
 * name or an object {"type": "image" | "checker" | "noise", ...} whose
 * colours `a` and `b` may be textures again (docs/scene-format.md). */
#include "io/scene_json.h"

#include "subsurf/texture_io.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static ss_status read_colour(ss_scene_reader *r, const cJSON *obj, const char *key, int srgb,
                             ss_rgb *value, const ss_texture **tex);

/* "scale": a number or [su, sv]; "offset": [ou, ov]. */
static ss_status read_pair(ss_scene_reader *r, const cJSON *obj, const char *key, int allow_number,
                           double out[2]) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    return SS_OK;
  }
  if (allow_number && cJSON_IsNumber(v)) {
    out[0] = out[1] = v->valuedouble;
  } else if (cJSON_IsArray(v) && cJSON_GetArraySize(v) == 2 &&
             cJSON_IsNumber(cJSON_GetArrayItem(v, 0)) && cJSON_IsNumber(cJSON_GetArrayItem(v, 1))) {
    out[0] = cJSON_GetArrayItem(v, 0)->valuedouble;
    out[1] = cJSON_GetArrayItem(v, 1)->valuedouble;
  } else {
    return ss_json_fail_key(&r->json, key,
                            allow_number ? "expected a number or [u, v]" : "expected [u, v]");
  }
  for (int k = 0; k < 2; ++k) {
    if (!(fabs(out[k]) <= 1e6) || (allow_number && out[k] == 0.0)) {
      return ss_json_fail_key(&r->json, key, "%g is out of range (|x| <= 1e6%s)", out[k],
                              allow_number ? ", non-zero" : "");
    }
  }
  return SS_OK;
}

static ss_status read_image(ss_scene_reader *r, const cJSON *spec, int srgb, ss_texture **out) {
  ss_json_ctx *c = &r->json;
  char file[SS_PATH_SIZE] = "", path[2 * SS_PATH_SIZE], wrap_name[16] = "repeat", space[16] = "";
  ss_status st = SS_OK;
  const char *file_key = NULL;
  if (cJSON_IsString(spec)) {
    snprintf(file, sizeof file, "%s", spec->valuestring);
  } else {
    file_key = "file";
    st = ss_json_require(c, spec, "file");
    if (st == SS_OK)
      st = ss_json_string(c, spec, "file", file, sizeof file);
    if (st == SS_OK)
      st = ss_json_string(c, spec, "wrap", wrap_name, sizeof wrap_name);
    if (st == SS_OK)
      st = ss_json_string(c, spec, "colorspace", space, sizeof space);
  }
  ss_wrap wrap = SS_WRAP_REPEAT;
  if (st == SS_OK && !ss_wrap_from_name(wrap_name, &wrap)) {
    st = ss_json_fail_key(c, "wrap", "unknown wrap mode '%s' (repeat, clamp, mirror)", wrap_name);
  }
  if (st == SS_OK && space[0]) {
    if (strcmp(space, "srgb") && strcmp(space, "linear")) {
      st = ss_json_fail_key(c, "colorspace", "unknown colour space '%s' (srgb, linear)", space);
    }
    srgb = !strcmp(space, "srgb");
  }
  if (st != SS_OK) {
    return st;
  }
  if (!file[0]) {
    return file_key ? ss_json_fail_key(c, file_key, "must not be empty")
                    : ss_json_fail(c, SS_ERR_PARSE, "must not be empty");
  }
  snprintf(path, sizeof path, file[0] == '/' ? "%s%s" : "%s/%s", file[0] == '/' ? "" : r->base_dir,
           file);
  ss_image *img;
  st = ss_texture_image_read(path, srgb, &img, c->err);
  if (st == SS_OK) {
    st = ss_texture_create_image(img, wrap, out, c->err);
  }
  if (st != SS_OK) {
    if (file_key) {
      ss_json_push_key(c, file_key);
    }
    st = ss_json_wrap(c, st == SS_ERR_IO ? SS_ERR_IO : SS_ERR_PARSE);
    if (file_key) {
      ss_json_pop(c);
    }
  }
  return st;
}

static ss_status read_noise_params(ss_scene_reader *r, const cJSON *spec, ss_noise_params *q) {
  ss_json_ctx *c = &r->json;
  long octaves = 4, seed = 0;
  double range[2] = {0.0, 1.0};
  char space[16] = "uv";
  *q = (ss_noise_params){.lacunarity = 2.0, .gain = 0.5};
  ss_status st = ss_json_int(c, spec, "octaves", 1, 16, &octaves);
  if (st == SS_OK)
    st = ss_json_number(c, spec, "lacunarity", 1.01, 16.0, &q->lacunarity);
  if (st == SS_OK)
    st = ss_json_number(c, spec, "gain", 0.01, 0.99, &q->gain);
  if (st == SS_OK)
    st = ss_json_int(c, spec, "seed", 0, 4294967295L, &seed);
  if (st == SS_OK)
    st = ss_json_bool(c, spec, "ridged", &q->ridged);
  if (st == SS_OK)
    st = read_pair(r, spec, "range", 0, range);
  if (st == SS_OK && !(range[0] < range[1])) {
    st = ss_json_fail_key(c, "range", "expected [lo, hi] with lo < hi");
  }
  if (st == SS_OK)
    st = ss_json_string(c, spec, "space", space, sizeof space);
  if (st == SS_OK && strcmp(space, "uv") && strcmp(space, "world")) {
    st = ss_json_fail_key(c, "space", "unknown space '%s' (uv, world)", space);
  }
  q->octaves = (int)octaves;
  q->seed = (uint32_t)seed;
  q->lo = range[0];
  q->hi = range[1];
  q->world = !strcmp(space, "world");
  return st;
}

static ss_status read_procedural(ss_scene_reader *r, const cJSON *spec, const char *type, int srgb,
                                 ss_texture **out) {
  ss_json_ctx *c = &r->json;
  ss_rgb col[2] = {ss_rgb_gray(0.0), ss_rgb_gray(1.0)};
  const ss_texture *in[2] = {NULL, NULL};
  ss_status st = read_colour(r, spec, "a", srgb, &col[0], &in[0]);
  if (st == SS_OK)
    st = read_colour(r, spec, "b", srgb, &col[1], &in[1]);
  if (st != SS_OK) {
    return st;
  }
  if (!strcmp(type, "checker")) {
    st = ss_texture_create_checker(col[0], col[1], out, c->err);
  } else {
    ss_noise_params q;
    st = read_noise_params(r, spec, &q);
    if (st == SS_OK) {
      st = ss_texture_create_noise(col[0], col[1], &q, out, c->err);
    }
  }
  if (st == SS_OK) {
    ss_texture_set_input(*out, 0, in[0]);
    ss_texture_set_input(*out, 1, in[1]);
  }
  return st;
}

/* The texture TEX at the current path; the scene owns it once read. */
static ss_status read_texture(ss_scene_reader *r, const cJSON *spec, int srgb,
                              const ss_texture **tex) {
  static const char *const image_keys[] = {"type",  "file",   "wrap", "colorspace",
                                           "scale", "offset", NULL};
  static const char *const checker_keys[] = {"type", "a", "b", "scale", "offset", NULL};
  static const char *const noise_keys[] = {"type",    "a",          "b",    "scale", "offset",
                                           "octaves", "lacunarity", "gain", "range", "ridged",
                                           "seed",    "space",      NULL};
  ss_json_ctx *c = &r->json;
  char type[16] = "";
  ss_texture *t = NULL;
  ss_status st = SS_OK;
  if (cJSON_IsString(spec)) {
    st = read_image(r, spec, srgb, &t);
  } else if (!cJSON_IsObject(spec)) {
    return ss_json_fail(c, SS_ERR_PARSE, "expected an image file name or a texture object");
  } else {
    st = ss_json_require(c, spec, "type");
    if (st == SS_OK)
      st = ss_json_string(c, spec, "type", type, sizeof type);
    if (st != SS_OK) {
      return st;
    }
    const char *const *keys = !strcmp(type, "image")     ? image_keys
                              : !strcmp(type, "checker") ? checker_keys
                              : !strcmp(type, "noise")   ? noise_keys
                                                         : NULL;
    if (!keys) {
      return ss_json_fail_key(c, "type", "unknown texture type '%s' (image, checker, noise)", type);
    }
    double scale[2] = {1.0, 1.0}, offset[2] = {0.0, 0.0};
    st = ss_json_check_keys(c, spec, keys);
    if (st == SS_OK)
      st = read_pair(r, spec, "scale", 1, scale);
    if (st == SS_OK)
      st = read_pair(r, spec, "offset", 0, offset);
    if (st == SS_OK) {
      st = keys == image_keys ? read_image(r, spec, srgb, &t)
                              : read_procedural(r, spec, type, srgb, &t);
    }
    if (st == SS_OK) {
      ss_texture_set_transform(t, scale, offset);
    }
  }
  if (st == SS_OK && ss_scene_add_texture(r->scene, t, c->err) != SS_OK) {
    return ss_json_wrap(c, SS_ERR_NO_MEMORY);
  }
  if (st == SS_OK) {
    *tex = t;
  }
  return st;
}

static ss_status read_colour(ss_scene_reader *r, const cJSON *obj, const char *key, int srgb,
                             ss_rgb *value, const ss_texture **tex) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v || !cJSON_IsObject(v)) {
    return ss_json_rgb(&r->json, obj, key, 0.0, value);
  }
  static const char *const keys[] = {"texture", NULL};
  ss_json_push_key(&r->json, key);
  ss_status st = ss_json_check_keys(&r->json, v, keys);
  if (st == SS_OK)
    st = ss_json_require(&r->json, v, "texture");
  if (st == SS_OK) {
    ss_json_push_key(&r->json, "texture");
    st = read_texture(r, cJSON_GetObjectItemCaseSensitive(v, "texture"), srgb, tex);
    ss_json_pop(&r->json);
  }
  ss_json_pop(&r->json);
  return st;
}

ss_status ss_scene_json_texture(ss_scene_reader *r, const cJSON *obj, ss_material *m,
                                ss_material_param p) {
  const char *key = ss_material_param_name(p);
  if (!cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(obj, key))) {
    return SS_OK;
  }
  ss_rgb unused;
  ss_status st = read_colour(r, obj, key, ss_material_param_is_colour(p), &unused, &m->textures[p]);
  if (st == SS_OK && ss_material_check_texture(m, p, r->json.err) != SS_OK) {
    ss_json_push_key(&r->json, key);
    st = ss_json_wrap(&r->json, SS_ERR_PARSE);
    ss_json_pop(&r->json);
  }
  return st;
}
