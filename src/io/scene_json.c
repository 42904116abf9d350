/* The scene reader: document structure, camera, integrator, render
 * settings, media and materials (shapes and lights: scene_json_shapes.c). */
#include "subsurf/scene_io.h"

#include "io/json_strict.h"
#include "io/scene_file.h"
#include "io/scene_json.h"
#include "subsurf/bssrdf.h"
#include "subsurf/integrator.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_scene_json_each(ss_scene_reader *r, const cJSON *arr,
                             ss_status (*fn)(ss_scene_reader *r, const cJSON *item, int index)) {
  if (!cJSON_IsArray(arr)) {
    return ss_json_fail(&r->json, SS_ERR_PARSE, "expected an array of objects");
  }
  int i = 0;
  const cJSON *item;
  cJSON_ArrayForEach(item, arr) {
    ss_json_push_index(&r->json, i);
    ss_status st = ss_json_expect_object(&r->json, item);
    if (st == SS_OK) {
      st = fn(r, item, i);
    }
    ss_json_pop(&r->json);
    if (st != SS_OK) {
      return st;
    }
    ++i;
  }
  return SS_OK;
}

ss_status ss_scene_json_reference(ss_scene_reader *r, const cJSON *obj, const char *key,
                                  const char *kind, int (*find)(const ss_scene *, const char *),
                                  int *index) {
  char name[SS_NAME_SIZE] = "";
  ss_status st = ss_json_require(&r->json, obj, key);
  if (st == SS_OK) {
    st = ss_json_string(&r->json, obj, key, name, sizeof name);
  }
  if (st != SS_OK) {
    return st;
  }
  *index = find(r->scene, name);
  if (*index < 0) {
    return ss_json_fail_key(&r->json, key, "no %s named '%s'", kind, name);
  }
  return SS_OK;
}

/* A name for an item: the "name" member, or `fallback` + index. */
static ss_status item_name(ss_scene_reader *r, const cJSON *obj, int required, const char *fallback,
                           int index, char name[SS_NAME_SIZE]) {
  snprintf(name, SS_NAME_SIZE, "%s%d", fallback, index);
  if (required) {
    ss_status st = ss_json_require(&r->json, obj, "name");
    if (st != SS_OK) {
      return st;
    }
  }
  ss_status st = ss_json_string(&r->json, obj, "name", name, SS_NAME_SIZE);
  if (st == SS_OK && !name[0]) {
    return ss_json_fail_key(&r->json, "name", "must not be empty");
  }
  return st;
}

/* ---- camera */

static ss_status read_filter(ss_scene_reader *r, const cJSON *cam, ss_filter *f) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(cam, "filter");
  if (!v) {
    return SS_OK;
  }
  ss_json_ctx *c = &r->json;
  char type[32] = "box";
  ss_status st = SS_OK;
  ss_json_push_key(c, "filter");
  if (cJSON_IsString(v)) {
    snprintf(type, sizeof type, "%s", v->valuestring);
  } else if (cJSON_IsObject(v)) {
    static const char *const keys[] = {"type", "radius", "sigma", NULL};
    st = ss_json_check_keys(c, v, keys);
    if (st == SS_OK) {
      st = ss_json_string(c, v, "type", type, sizeof type);
    }
  } else {
    st = ss_json_fail(c, SS_ERR_PARSE, "expected \"box\", \"gaussian\" or an object");
  }
  ss_filter_type ft;
  if (st == SS_OK && !ss_filter_type_from_name(type, &ft)) {
    st = cJSON_IsObject(v)
             ? ss_json_fail_key(c, "type", "unknown filter '%s' (box, gaussian)", type)
             : ss_json_fail(c, SS_ERR_PARSE, "unknown filter '%s' (box, gaussian)", type);
  }
  if (st == SS_OK) {
    *f = ss_filter_default(ft);
    if (cJSON_IsObject(v)) {
      st = ss_json_number(c, v, "radius", 1e-3, 16.0, &f->radius);
      if (st == SS_OK) {
        st = ss_json_number(c, v, "sigma", 1e-3, 16.0, &f->sigma);
      }
    }
  }
  ss_json_pop(c);
  return st;
}

static ss_status read_camera(ss_scene_reader *r, const cJSON *cam) {
  static const char *const keys[] = {"position",   "target", "up", "fov",
                                     "resolution", "filter", NULL};
  ss_json_ctx *c = &r->json;
  ss_camera *k = &r->scene->camera;
  ss_status st = ss_json_expect_object(c, cam);
  if (st == SS_OK)
    st = ss_json_check_keys(c, cam, keys);
  if (st == SS_OK)
    st = ss_json_vec3(c, cam, "position", &k->position);
  if (st == SS_OK)
    st = ss_json_vec3(c, cam, "target", &k->target);
  if (st == SS_OK)
    st = ss_json_vec3(c, cam, "up", &k->up);
  if (st == SS_OK)
    st = ss_json_number(c, cam, "fov", 1e-3, 179.0, &k->fov_deg);
  if (st == SS_OK)
    st = read_filter(r, cam, &k->filter);
  const cJSON *res = cJSON_GetObjectItemCaseSensitive(cam, "resolution");
  if (st == SS_OK && res) {
    if (!cJSON_IsArray(res) || cJSON_GetArraySize(res) != 2) {
      return ss_json_fail_key(c, "resolution", "expected [width, height]");
    }
    for (int i = 0; i < 2; ++i) {
      const cJSON *e = cJSON_GetArrayItem(res, i);
      double v = cJSON_IsNumber(e) ? e->valuedouble : -1.0;
      if (!(v >= 1.0 && v <= 65536.0) || v != floor(v)) { /* range first: (long)1e300 is UB */
        return ss_json_fail_key(c, "resolution", "width and height must be integers in [1, 65536]");
      }
      *(i ? &k->height : &k->width) = (int)v;
    }
  }
  if (st == SS_OK && ss_camera_init(k, c->err) != SS_OK) {
    return ss_json_wrap(c, SS_ERR_PARSE);
  }
  return st;
}

/* ---- integrator and render settings */

/* "cache": the file of the integrator's precomputation, relative to the
 * scene file (integrators that list "cache" among their options). */
static ss_status read_integrator_cache(ss_scene_reader *r, const cJSON *v) {
  ss_integrator_settings *in = &r->scene->integrator;
  if (!cJSON_IsString(v) || !v->valuestring[0]) {
    return ss_json_fail_key(&r->json, "cache", "expected a file name, not empty");
  }
  const char *s = v->valuestring;
  int n = s[0] == '/' ? snprintf(in->cache, sizeof in->cache, "%s", s)
                      : snprintf(in->cache, sizeof in->cache, "%s/%s", r->base_dir, s);
  if (n < 0 || (size_t)n >= sizeof in->cache) {
    return ss_json_fail_key(&r->json, "cache", "file name too long");
  }
  return SS_OK;
}

static ss_status read_integrator(ss_scene_reader *r, const cJSON *obj) {
  ss_json_ctx *c = &r->json;
  ss_integrator_settings *in = &r->scene->integrator;
  ss_status st = ss_json_expect_object(c, obj);
  if (st == SS_OK)
    st = ss_json_string(c, obj, "type", in->name, sizeof in->name);
  if (st != SS_OK) {
    return st;
  }
  const ss_integrator_ops *ops = ss_integrator_find(in->name);
  if (!ops) {
    char names[256];
    ss_integrator_names(names, sizeof names);
    return ss_json_fail_key(c, "type", "unknown integrator '%s' (known: %s)", in->name, names);
  }
  const cJSON *m;
  cJSON_ArrayForEach(m, obj) {
    if (!strcmp(m->string, "type")) {
      continue;
    }
    if (!ss_integrator_accepts_option(ops, m->string)) {
      return ss_json_fail_key(c, m->string, "unknown option of integrator '%s'", ops->name);
    }
    long v = 0;
    if (!strcmp(m->string, "cache")) {
      st = read_integrator_cache(r, m);
    } else if (!strcmp(m->string, "max_depth") || !strcmp(m->string, "rr_depth")) {
      st = ss_json_int(c, obj, m->string, 0, 100000000, &v);
      *(!strcmp(m->string, "max_depth") ? &in->max_depth : &in->rr_depth) = (int)v;
    } else {
      double d = 0.0;
      st = ss_json_number(c, obj, m->string, -HUGE_VAL, HUGE_VAL, &d);
      if (st == SS_OK && ss_scene_set_integrator_option(r->scene, m->string, d, c->err) != SS_OK) {
        st = ss_json_wrap(c, SS_ERR_PARSE);
      }
    }
    if (st != SS_OK) {
      return st;
    }
  }
  return SS_OK;
}

/* "table_cache": true (the default directory), false (none) or a directory
 * relative to the scene file. */
static ss_status read_table_cache(ss_scene_reader *r, const cJSON *obj) {
  ss_render_settings *rs = &r->scene->render;
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "table_cache");
  if (!v) {
    return SS_OK;
  }
  if (cJSON_IsBool(v)) {
    rs->table_cache = cJSON_IsTrue(v);
    return SS_OK;
  }
  if (!cJSON_IsString(v) || !v->valuestring[0]) {
    return ss_json_fail_key(&r->json, "table_cache",
                            "expected true, false or a directory name, not empty");
  }
  const char *s = v->valuestring;
  int n = s[0] == '/'
              ? snprintf(rs->table_cache_dir, sizeof rs->table_cache_dir, "%s", s)
              : snprintf(rs->table_cache_dir, sizeof rs->table_cache_dir, "%s/%s", r->base_dir, s);
  if (n < 0 || (size_t)n >= sizeof rs->table_cache_dir) {
    return ss_json_fail_key(&r->json, "table_cache", "directory name too long");
  }
  rs->table_cache = 1;
  return SS_OK;
}

static ss_status read_render(ss_scene_reader *r, const cJSON *obj) {
  static const char *const keys[] = {"spp",      "seed",     "time_limit",  "output", "png",
                                     "variance", "exposure", "table_cache", NULL};
  ss_json_ctx *c = &r->json;
  ss_render_settings *rs = &r->scene->render;
  long spp = rs->spp, seed = (long)rs->seed;
  ss_status st = ss_json_expect_object(c, obj);
  if (st == SS_OK)
    st = ss_json_check_keys(c, obj, keys);
  if (st == SS_OK)
    st = ss_json_int(c, obj, "spp", 1, 1L << 30, &spp);
  if (st == SS_OK)
    st = ss_json_int(c, obj, "seed", 0, 1L << 52, &seed);
  if (st == SS_OK)
    st = ss_json_number(c, obj, "time_limit", 0.0, 1e9, &rs->time_limit);
  if (st == SS_OK)
    st = ss_json_string(c, obj, "output", rs->output, sizeof rs->output);
  if (st == SS_OK)
    st = ss_json_bool(c, obj, "png", &rs->png);
  if (st == SS_OK)
    st = ss_json_bool(c, obj, "variance", &rs->variance);
  if (st == SS_OK)
    st = ss_json_number(c, obj, "exposure", -64.0, 64.0, &rs->exposure);
  if (st == SS_OK)
    st = read_table_cache(r, obj);
  rs->spp = (int)spp;
  rs->seed = (uint64_t)seed;
  return st;
}

/* ---- media */

static ss_status read_phase(ss_scene_reader *r, const cJSON *obj, ss_phase *phase) {
  ss_json_ctx *c = &r->json;
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "phase");
  char type[32] = "iso";
  double g = 0.0;
  ss_status st = SS_OK;
  if (v) {
    ss_json_push_key(c, "phase");
    if (cJSON_IsString(v)) {
      snprintf(type, sizeof type, "%s", v->valuestring);
    } else if (cJSON_IsObject(v)) {
      static const char *const keys[] = {"type", "g", NULL};
      st = ss_json_check_keys(c, v, keys);
      if (st == SS_OK)
        st = ss_json_string(c, v, "type", type, sizeof type);
      if (st == SS_OK)
        st = ss_json_number(c, v, "g", -0.999999, 0.999999, &g);
    } else {
      st = ss_json_fail(c, SS_ERR_PARSE, "expected a phase function name or object");
    }
  }
  ss_phase_type pt = SS_PHASE_ISOTROPIC;
  if (st == SS_OK && !ss_phase_type_from_name(type, &pt)) {
    st = ss_json_fail(c, SS_ERR_PARSE, "unknown phase function '%s' (iso, hg, gauss)", type);
  }
  if (st == SS_OK && ss_phase_init(phase, pt, g, c->err) != SS_OK) {
    st = ss_json_wrap(c, SS_ERR_PARSE);
  }
  if (v) {
    ss_json_pop(c);
  }
  return st;
}

static ss_status read_medium_object(ss_scene_reader *r, const cJSON *obj, ss_medium *m) {
  static const char *const keys[] = {"name",  "sigma_s", "sigma_a", "preset", "scale",
                                     "phase", "flakes",  "grid",    NULL};
  ss_json_ctx *c = &r->json;
  char preset[SS_NAME_SIZE] = "";
  double scale = 1.0;
  ss_status st = ss_json_check_keys(c, obj, keys);
  if (st == SS_OK)
    st = read_phase(r, obj, &m->phase);
  m->optics.phase = m->phase.type;
  m->optics.g = ss_rgb_gray(m->phase.g);
  if (st == SS_OK)
    st = ss_json_string(c, obj, "preset", preset, sizeof preset);
  if (st == SS_OK)
    st = ss_json_number(c, obj, "scale", 1e-12, 1e12, &scale);
  if (st != SS_OK) {
    return st;
  }
  int has_s = cJSON_HasObjectItem(obj, "sigma_s"), has_a = cJSON_HasObjectItem(obj, "sigma_a");
  if (preset[0]) {
    if (has_s || has_a) {
      return ss_json_fail_key(c, has_s ? "sigma_s" : "sigma_a",
                              "give either a preset or sigma_s and sigma_a, not both");
    }
    if (ss_medium_from_preset(m, preset, scale, c->err) != SS_OK) {
      ss_json_push_key(c, "preset");
      st = ss_json_wrap(c, SS_ERR_PARSE);
      ss_json_pop(c);
      return st;
    }
  } else {
    if ((st = ss_json_require(c, obj, "sigma_s")) != SS_OK ||
        (st = ss_json_require(c, obj, "sigma_a")) != SS_OK) {
      return st;
    }
    if ((st = ss_json_rgb(c, obj, "sigma_s", 0.0, &m->optics.sigma_s)) != SS_OK ||
        (st = ss_json_rgb(c, obj, "sigma_a", 0.0, &m->optics.sigma_a)) != SS_OK) {
      return st;
    }
    m->optics.sigma_s = ss_rgb_scale(m->optics.sigma_s, scale);
    m->optics.sigma_a = ss_rgb_scale(m->optics.sigma_a, scale);
  }
  if ((st = ss_scene_json_flakes(r, obj, m)) != SS_OK) {
    return st;
  }
  if (ss_medium_init(m, c->err) != SS_OK) {
    return ss_json_wrap(c, SS_ERR_PARSE);
  }
  return ss_scene_json_grid(r, obj, m);
}

static ss_status read_medium(ss_scene_reader *r, const cJSON *obj, int index) {
  ss_medium m;
  memset(&m, 0, sizeof m);
  ss_status st = item_name(r, obj, 1, "medium", index, m.name);
  if (st == SS_OK)
    st = read_medium_object(r, obj, &m);
  if (st == SS_OK && ss_scene_add_medium(r->scene, &m, NULL, r->json.err) != SS_OK) {
    st = ss_json_wrap(&r->json, SS_ERR_PARSE);
  }
  return st;
}

/* ---- materials */

static ss_status read_material_medium(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "medium");
  if (!v) {
    return SS_OK;
  }
  if (cJSON_IsString(v)) {
    return ss_scene_json_reference(r, obj, "medium", "medium", ss_scene_find_medium, &m->medium);
  }
  if (!cJSON_IsObject(v)) {
    return ss_json_fail_key(&r->json, "medium", "expected a medium name or a medium object");
  }
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "%.40s.medium", m->name);
  ss_json_push_key(&r->json, "medium");
  ss_status st = ss_json_string(&r->json, v, "name", med.name, sizeof med.name);
  if (st == SS_OK)
    st = read_medium_object(r, v, &med);
  if (st == SS_OK && ss_scene_add_medium(r->scene, &med, &m->medium, r->json.err) != SS_OK) {
    st = ss_json_wrap(&r->json, SS_ERR_PARSE);
  }
  ss_json_pop(&r->json);
  return st;
}

static ss_status read_microfacet(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  char dist[32] = "beckmann";
  m->mf.type = SS_MICROFACET_BECKMANN;
  m->mf.alpha = 0.1;
  ss_status st = ss_json_string(&r->json, obj, "distribution", dist, sizeof dist);
  if (st == SS_OK && !ss_microfacet_type_from_name(dist, &m->mf.type)) {
    st = ss_json_fail_key(&r->json, "distribution", "unknown distribution '%s' (beckmann, ggx)",
                          dist);
  }
  if (st == SS_OK)
    st = ss_scene_json_texture(r, obj, m, SS_PARAM_ALPHA);
  if (st == SS_OK && !m->textures[SS_PARAM_ALPHA]) {
    st = ss_json_number(&r->json, obj, "alpha", 1e-4, 4.0, &m->mf.alpha);
  }
  return st;
}

/* "energy_compensation": true/false, only on rough boundaries. */
static ss_status read_energy_compensation(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  if (!cJSON_HasObjectItem(obj, "energy_compensation")) {
    return SS_OK;
  }
  if (m->boundary != SS_BOUNDARY_ROUGH) {
    return ss_json_fail_key(&r->json, "energy_compensation",
                            "energy compensation applies to rough boundaries only");
  }
  return ss_json_bool(&r->json, obj, "energy_compensation", &m->energy_compensation);
}

static ss_status read_material(ss_scene_reader *r, const cJSON *obj, int index) {
  static const char *const diffuse_keys[] = {"name", "type", "albedo", NULL};
  static const char *const dielectric_keys[] = {"name", "type", "eta", "priority", NULL};
  static const char *const rough_keys[] = {
      "name", "type", "eta", "distribution", "alpha", "energy_compensation", "priority", NULL};
  static const char *const translucent_keys[] = {"name",
                                                 "type",
                                                 "boundary",
                                                 "eta",
                                                 "distribution",
                                                 "alpha",
                                                 "medium",
                                                 "bssrdf",
                                                 "single_scattering",
                                                 "lod",
                                                 "energy_compensation",
                                                 "albedo",
                                                 "mfp",
                                                 "g",
                                                 "albedo_inversion",
                                                 "priority",
                                                 NULL};
  ss_json_ctx *c = &r->json;
  ss_material m;
  memset(&m, 0, sizeof m);
  m.medium = -1;
  char type[32] = "";
  ss_status st = item_name(r, obj, 1, "material", index, m.name);
  if (st == SS_OK)
    st = ss_json_require(c, obj, "type");
  if (st == SS_OK)
    st = ss_json_string(c, obj, "type", type, sizeof type);
  if (st != SS_OK) {
    return st;
  }
  m.kind = SS_MATERIAL_INTERFACE;
  if (!strcmp(type, "diffuse")) {
    m.kind = SS_MATERIAL_DIFFUSE;
    m.albedo = ss_rgb_gray(0.5);
    st = ss_json_check_keys(c, obj, diffuse_keys);
    if (st == SS_OK)
      st = ss_scene_json_texture(r, obj, &m, SS_PARAM_ALBEDO);
    if (st == SS_OK && !m.textures[SS_PARAM_ALBEDO]) {
      st = ss_json_rgb(c, obj, "albedo", 0.0, &m.albedo);
    }
  } else if (!strcmp(type, "dielectric")) {
    m.boundary = SS_BOUNDARY_SMOOTH;
    m.eta = 1.5;
    st = ss_json_check_keys(c, obj, dielectric_keys);
  } else if (!strcmp(type, "roughdielectric")) {
    m.boundary = SS_BOUNDARY_ROUGH;
    m.eta = 1.5;
    st = ss_json_check_keys(c, obj, rough_keys);
    if (st == SS_OK)
      st = read_microfacet(r, obj, &m);
    if (st == SS_OK)
      st = read_energy_compensation(r, obj, &m);
  } else if (!strcmp(type, "translucent")) {
    char boundary[32] = "smooth";
    m.eta = 1.3;
    st = ss_json_check_keys(c, obj, translucent_keys);
    if (st == SS_OK)
      st = ss_json_string(c, obj, "boundary", boundary, sizeof boundary);
    if (st == SS_OK && !ss_boundary_type_from_name(boundary, &m.boundary)) {
      st = ss_json_fail_key(c, "boundary", "unknown boundary '%s' (index-matched, smooth, rough)",
                            boundary);
    }
    if (st == SS_OK && m.boundary == SS_BOUNDARY_INDEX_MATCHED && cJSON_HasObjectItem(obj, "eta")) {
      st = ss_json_fail_key(c, "eta", "an index-matched boundary has eta 1; remove eta");
    }
    if (st == SS_OK)
      st = read_microfacet(r, obj, &m);
    m.energy_compensation = 1;
    if (st == SS_OK)
      st = read_energy_compensation(r, obj, &m);
    if (st == SS_OK && !ss_scene_json_has_albedo(obj))
      st = ss_json_require(c, obj, "medium");
    if (st == SS_OK)
      st = read_material_medium(r, obj, &m);
    if (st == SS_OK)
      st = ss_scene_json_bssrdf(r, obj, &m);
  } else if (ss_scene_json_is_surface(type)) {
    st = ss_scene_json_surface(r, obj, type, &m);
  } else {
    return ss_json_fail_key(c, "type",
                            "unknown material type '%s' (diffuse, dielectric, roughdielectric, "
                            "translucent, conductor, roughconductor, mirror, thindielectric, "
                            "diffusetransmission, plastic, twosided, mix)",
                            type);
  }
  long priority = 0;
  if (st == SS_OK && m.kind == SS_MATERIAL_INTERFACE) {
    st = ss_json_number(c, obj, "eta", 1e-3, 10.0, &m.eta);
  }
  if (st == SS_OK && m.kind == SS_MATERIAL_INTERFACE) {
    st = ss_json_int(c, obj, "priority", 0, SS_PRIORITY_MAX, &priority);
    m.priority = (int)priority;
  }
  if (st == SS_OK && !strcmp(type, "translucent"))
    st = ss_scene_json_albedo(r, obj, &m);
  if (st == SS_OK && ss_material_check(&m, c->err) != SS_OK) {
    st = ss_json_wrap(c, SS_ERR_PARSE);
  }
  if (st == SS_OK && ss_scene_add_material(r->scene, &m, NULL, c->err) != SS_OK) {
    st = ss_json_wrap(c, SS_ERR_PARSE);
  }
  return st;
}

/* ---- the document */

static ss_status read_section(ss_scene_reader *r, const cJSON *root, const char *key,
                              ss_status (*fn)(ss_scene_reader *r, const cJSON *v)) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, key);
  if (!v) {
    return SS_OK;
  }
  ss_json_push_key(&r->json, key);
  ss_status st = fn(r, v);
  ss_json_pop(&r->json);
  return st;
}

static ss_status read_media(ss_scene_reader *r, const cJSON *v) {
  return ss_scene_json_each(r, v, read_medium);
}
static ss_status read_materials(ss_scene_reader *r, const cJSON *v) {
  return ss_scene_json_each(r, v, read_material);
}

static ss_status read_document(ss_scene_reader *r, const cJSON *root) {
  static const char *const keys[] = {"description", "camera",     "media",  "materials", "shapes",
                                     "lights",      "integrator", "render", NULL};
  ss_status st = ss_json_expect_object(&r->json, root);
  if (st == SS_OK)
    st = ss_json_check_keys(&r->json, root, keys);
  const cJSON *d = cJSON_GetObjectItemCaseSensitive(root, "description");
  if (st == SS_OK && d && !cJSON_IsString(d)) {
    st = ss_json_fail_key(&r->json, "description", "expected a string");
  }
  if (st == SS_OK)
    st = ss_json_require(&r->json, root, "shapes");
  if (st == SS_OK)
    st = read_section(r, root, "camera", read_camera);
  if (st == SS_OK)
    st = read_section(r, root, "integrator", read_integrator);
  if (st == SS_OK)
    st = read_section(r, root, "render", read_render);
  if (st == SS_OK)
    st = read_section(r, root, "media", read_media);
  if (st == SS_OK)
    st = read_section(r, root, "materials", read_materials);
  if (st == SS_OK)
    st = read_section(r, root, "shapes", ss_scene_json_shapes);
  if (st == SS_OK)
    st = read_section(r, root, "lights", ss_scene_json_lights);
  return st;
}

ss_status ss_scene_parse_json(const char *text, const char *file, const char *base_dir,
                              ss_scene **out, ss_error *err) {
  *out = NULL;
  ss_status strict = ss_json_check_strict(text, file, err);
  if (strict != SS_OK) {
    return strict;
  }
  const char *end = NULL;
  cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
  if (!root) {
    long off = end ? (long)(end - text) : 0;
    char near[24];
    snprintf(near, sizeof near, "%.20s", text + off);
    for (char *p = near; *p; ++p) {
      if (*p == '\n' || *p == '\r') {
        *p = '\0';
        break;
      }
    }
    return ss_error_set(err, SS_ERR_PARSE, "%s:%d: invalid JSON near '%s'", file,
                        ss_json_line(text, off), near);
  }
  ss_scene_reader r;
  memset(&r, 0, sizeof r);
  r.json.text = text;
  r.json.file = file;
  r.json.err = err;
  r.base_dir = base_dir ? base_dir : ".";
  ss_status st = ss_json_check_unique_keys(&r.json, root);
  if (st == SS_OK)
    st = ss_scene_create(&r.scene, err);
  if (st == SS_OK)
    st = read_document(&r, root);
  if (st == SS_OK && ss_scene_commit(r.scene, err) != SS_OK) {
    ss_error_prefix(err, "%s: ", file);
    st = SS_ERR_PARSE;
  }
  cJSON_Delete(root);
  if (st != SS_OK) {
    ss_scene_destroy(r.scene);
    return st;
  }
  *out = r.scene;
  return SS_OK;
}

ss_status ss_scene_read_json(const char *path, ss_scene **out, ss_error *err) {
  *out = NULL;
  char *text = NULL, dir[SS_PATH_SIZE];
  ss_status st = ss_scene_file_read(path, "a JSON text file", &text, dir, err);
  if (st != SS_OK) {
    return st;
  }
  st = ss_scene_parse_json(text, path, dir, out, err);
  free(text);
  return st;
}
