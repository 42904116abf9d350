/* The surface materials of scene files: conductor, roughconductor, mirror,
 * thindielectric, diffusetransmission, plastic, twosided, mix. */
#include "io/scene_json.h"

#include "subsurf/metals.h"

#include <string.h>

static const char *const surface_types[] = {"conductor",
                                            "roughconductor",
                                            "mirror",
                                            "thindielectric",
                                            "diffusetransmission",
                                            "plastic",
                                            "twosided",
                                            "mix",
                                            NULL};

int ss_scene_json_is_surface(const char *type) {
  for (int i = 0; surface_types[i]; ++i) {
    if (!strcmp(type, surface_types[i])) {
      return 1;
    }
  }
  return 0;
}

/* "metal": a name, or "eta" and "k" (numbers or RGB triples). */
static ss_status read_index(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  ss_json_ctx *c = &r->json;
  int has_metal = cJSON_HasObjectItem(obj, "metal");
  int has_eta = cJSON_HasObjectItem(obj, "eta"), has_k = cJSON_HasObjectItem(obj, "k");
  if (has_metal && (has_eta || has_k)) {
    return ss_json_fail_key(c, has_eta ? "eta" : "k", "give either metal or eta and k, not both");
  }
  if (has_metal) {
    char name[32] = "";
    ss_status st = ss_json_string(c, obj, "metal", name, sizeof name);
    if (st != SS_OK) {
      return st;
    }
    int i = ss_metal_find(name);
    if (i < 0) {
      return ss_json_fail_key(c, "metal", "unknown metal '%s' (known: %s)", name, ss_metal_names());
    }
    ss_vec3 eta, k;
    ss_metal_rgb((size_t)i, &eta, &k);
    m->conductor_eta = ss_rgb_make(eta.x, eta.y, eta.z);
    m->conductor_k = ss_rgb_make(k.x, k.y, k.z);
    return SS_OK;
  }
  if (!has_eta || !has_k) {
    return ss_json_fail_key(c, has_eta ? "k" : "eta",
                            "a conductor needs a metal (%s) or both eta and k", ss_metal_names());
  }
  ss_status st = ss_json_rgb(c, obj, "eta", 1e-6, &m->conductor_eta);
  if (st == SS_OK)
    st = ss_json_rgb(c, obj, "k", 0.0, &m->conductor_k);
  return st;
}

/* "distribution" and "alpha", or "alpha_u" and "alpha_v" (anisotropic). */
static ss_status read_roughness(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  ss_json_ctx *c = &r->json;
  char dist[32] = "ggx";
  m->mf.type = SS_MICROFACET_GGX;
  m->mf.alpha = 0.1;
  m->mf.alpha_v = 0.0;
  ss_status st = ss_json_string(c, obj, "distribution", dist, sizeof dist);
  if (st == SS_OK && !ss_microfacet_type_from_name(dist, &m->mf.type)) {
    return ss_json_fail_key(c, "distribution", "unknown distribution '%s' (beckmann, ggx)", dist);
  }
  int has_u = cJSON_HasObjectItem(obj, "alpha_u"), has_v = cJSON_HasObjectItem(obj, "alpha_v");
  if (st == SS_OK && (has_u || has_v)) {
    if (cJSON_HasObjectItem(obj, "alpha")) {
      return ss_json_fail_key(c, "alpha", "give alpha or alpha_u and alpha_v, not both");
    }
    if (!has_u || !has_v) {
      return ss_json_fail_key(c, has_u ? "alpha_u" : "alpha_v", "alpha_u and alpha_v go together");
    }
    st = ss_json_number(c, obj, "alpha_u", 1e-4, 4.0, &m->mf.alpha);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "alpha_v", 1e-4, 4.0, &m->mf.alpha_v);
    return st;
  }
  if (st == SS_OK)
    st = ss_json_number(c, obj, "alpha", 1e-4, 4.0, &m->mf.alpha);
  return st;
}

/* A required reference to an earlier surface material by name. */
static ss_status part_named(ss_scene_reader *r, const cJSON *v, const char *key, int *index) {
  if (!cJSON_IsString(v)) {
    return ss_json_fail_key(&r->json, key, "expected a material name");
  }
  *index = ss_scene_find_material(r->scene, v->valuestring);
  if (*index < 0) {
    return ss_json_fail_key(&r->json, key, "no material named '%s' before this one",
                            v->valuestring);
  }
  const ss_material *q = &r->scene->materials[*index];
  if (q->kind == SS_MATERIAL_INTERFACE || ss_material_is_textured(q)) {
    return ss_json_fail_key(&r->json, key,
                            "'%s' is a dielectric interface or textured; parts must be untextured "
                            "surface materials",
                            v->valuestring);
  }
  return SS_OK;
}

static ss_status read_mix(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  ss_json_ctx *c = &r->json;
  ss_status st = ss_json_require(c, obj, "materials");
  const cJSON *list = cJSON_GetObjectItemCaseSensitive(obj, "materials");
  if (st == SS_OK && (!cJSON_IsArray(list) || cJSON_GetArraySize(list) != 2)) {
    return ss_json_fail_key(c, "materials", "expected the names of two materials");
  }
  for (int i = 0; st == SS_OK && i < 2; ++i) {
    st = part_named(r, cJSON_GetArrayItem(list, i), "materials", &m->parts[i]);
  }
  double weight = 0.5;
  if (st == SS_OK)
    st = ss_json_number(c, obj, "weight", 0.0, 1.0, &weight);
  m->mix_weight = 1.0 - weight;
  return st;
}

ss_status ss_scene_json_surface(ss_scene_reader *r, const cJSON *obj, const char *type,
                                ss_material *m) {
  static const char *const conductor_keys[] = {"name", "type", "metal", "eta", "k", NULL};
  static const char *const rough_keys[] = {
      "name",  "type",    "metal",   "eta",          "k",
      "alpha", "alpha_u", "alpha_v", "distribution", "energy_compensation",
      NULL};
  static const char *const mirror_keys[] = {"name", "type", "reflectance", NULL};
  static const char *const thin_keys[] = {"name", "type", "eta", NULL};
  static const char *const dt_keys[] = {"name", "type", "reflectance", "transmittance", NULL};
  static const char *const plastic_keys[] = {"name", "type", "albedo", "eta", NULL};
  static const char *const two_sided_keys[] = {"name", "type", "material", NULL};
  static const char *const mix_keys[] = {"name", "type", "materials", "weight", NULL};
  ss_json_ctx *c = &r->json;
  ss_status st;
  if (!strcmp(type, "conductor") || !strcmp(type, "roughconductor")) {
    int rough = type[0] == 'r';
    m->kind = SS_MATERIAL_CONDUCTOR;
    m->boundary = rough ? SS_BOUNDARY_ROUGH : SS_BOUNDARY_SMOOTH;
    m->energy_compensation = rough;
    st = ss_json_check_keys(c, obj, rough ? rough_keys : conductor_keys);
    if (st == SS_OK)
      st = read_index(r, obj, m);
    if (st == SS_OK && rough)
      st = read_roughness(r, obj, m);
    if (st == SS_OK && rough)
      st = ss_json_bool(c, obj, "energy_compensation", &m->energy_compensation);
  } else if (!strcmp(type, "mirror")) {
    m->kind = SS_MATERIAL_MIRROR;
    m->albedo = ss_rgb_gray(1.0);
    st = ss_json_check_keys(c, obj, mirror_keys);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "reflectance", 0.0, &m->albedo);
  } else if (!strcmp(type, "thindielectric")) {
    m->kind = SS_MATERIAL_THIN_DIELECTRIC;
    m->eta = 1.5;
    st = ss_json_check_keys(c, obj, thin_keys);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "eta", 1e-3, 10.0, &m->eta);
  } else if (!strcmp(type, "diffusetransmission")) {
    m->kind = SS_MATERIAL_DIFFUSE_TRANSMISSION;
    m->albedo = ss_rgb_gray(0.25);
    m->transmittance = ss_rgb_gray(0.25);
    st = ss_json_check_keys(c, obj, dt_keys);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "reflectance", 0.0, &m->albedo);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "transmittance", 0.0, &m->transmittance);
  } else if (!strcmp(type, "plastic")) {
    m->kind = SS_MATERIAL_COATED_DIFFUSE;
    m->albedo = ss_rgb_gray(0.5);
    m->eta = 1.5;
    st = ss_json_check_keys(c, obj, plastic_keys);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "albedo", 0.0, &m->albedo);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "eta", 1.0 + 1e-6, 10.0, &m->eta);
  } else if (!strcmp(type, "twosided")) {
    m->kind = SS_MATERIAL_TWO_SIDED;
    st = ss_json_check_keys(c, obj, two_sided_keys);
    if (st == SS_OK)
      st = ss_json_require(c, obj, "material");
    if (st == SS_OK)
      st = part_named(r, cJSON_GetObjectItemCaseSensitive(obj, "material"), "material",
                      &m->parts[0]);
  } else {
    m->kind = SS_MATERIAL_MIX;
    st = ss_json_check_keys(c, obj, mix_keys);
    if (st == SS_OK)
      st = read_mix(r, obj, m);
  }
  return st;
}
