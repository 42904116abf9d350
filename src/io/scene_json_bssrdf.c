/* A translucent material's BSSRDF in a scene file:
 *     "bssrdf": "pbd"
 *     "bssrdf": {"model": "pbd", "beam_samples": 50}
 * and "lod" (material.h, subsurface.h). Every key but "model" is an option of that model, set by
 * name (ss_bssrdf_params_set_option), so that the loader knows no model. String options that
 * name files (table files, meta "FILE") are relative to the scene file's directory. */
#include "io/scene_json.h"

#include <stdio.h>
#include <string.h>

static ss_status read_model(ss_scene_reader *r, const cJSON *v, ss_material *m,
                            const ss_bssrdf_ops **ops) {
  ss_json_ctx *c = &r->json;
  if (!cJSON_IsString(v)) {
    return ss_json_fail(c, SS_ERR_PARSE, "expected a BSSRDF model name");
  }
  *ops = ss_bssrdf_model_find(v->valuestring);
  if (!*ops) {
    char names[512];
    ss_bssrdf_model_names(names, sizeof names);
    return ss_json_fail(c, SS_ERR_PARSE, "unknown BSSRDF model '%s' (known: %s)", v->valuestring,
                        names);
  }
  snprintf(m->bssrdf, sizeof m->bssrdf, "%s", v->valuestring);
  return SS_OK;
}

/* The option's value as the text set_option parses. */
static ss_status option_text(ss_scene_reader *r, const cJSON *item, const ss_bssrdf_ops *ops,
                             char *text, size_t size) {
  const ss_option *o = ss_bssrdf_option_find(ops, item->string);
  if (cJSON_IsBool(item)) {
    snprintf(text, size, "%s", cJSON_IsTrue(item) ? "true" : "false");
  } else if (cJSON_IsNumber(item)) {
    snprintf(text, size, "%.17g", item->valuedouble);
  } else if (cJSON_IsString(item)) {
    const char *s = item->valuestring;
    /* Files (meta "FILE") are relative to the scene; other text (an axis, a
     * layer stack) is taken as written. */
    int relative = o && o->type == SS_OPTION_STRING && o->meta && !strcmp(o->meta, "FILE") &&
                   s[0] && s[0] != '/';
    int n =
        relative ? snprintf(text, size, "%s/%s", r->base_dir, s) : snprintf(text, size, "%s", s);
    if (n < 0 || (size_t)n >= size) {
      return ss_json_fail(&r->json, SS_ERR_PARSE, "value too long");
    }
  } else {
    return ss_json_fail(&r->json, SS_ERR_PARSE, "expected a number, a boolean or a string");
  }
  return SS_OK;
}

static ss_status read_options(ss_scene_reader *r, const cJSON *obj, ss_material *m,
                              const ss_bssrdf_ops *ops) {
  ss_json_ctx *c = &r->json;
  for (const cJSON *item = obj->child; item; item = item->next) {
    if (!strcmp(item->string, "model")) {
      continue;
    }
    char text[SS_OPTION_TEXT];
    ss_json_push_key(c, item->string);
    ss_status st = option_text(r, item, ops, text, sizeof text);
    if (st == SS_OK &&
        ss_bssrdf_params_set_option(&m->bssrdf_options, ops, item->string, text, c->err) != SS_OK) {
      st = ss_json_wrap(c, SS_ERR_PARSE);
    }
    ss_json_pop(c);
    if (st != SS_OK) {
      return st;
    }
  }
  return SS_OK;
}

/* "lod": explicit, else the named model, else automatic. */
static ss_status read_lod(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  char name[32] = "";
  m->lod = cJSON_HasObjectItem(obj, "bssrdf") ? SS_LOD_BSSRDF : SS_LOD_AUTO;
  ss_status st = ss_json_string(&r->json, obj, "lod", name, sizeof name);
  if (st == SS_OK && name[0] && !ss_lod_from_name(name, &m->lod)) {
    st = ss_json_fail_key(&r->json, "lod",
                          "unknown level of detail '%s' (auto, bssrdf, brdf, "
                          "volpath)",
                          name);
  }
  return st;
}

ss_status ss_scene_json_bssrdf(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  ss_json_ctx *c = &r->json;
  ss_status st = ss_json_bool(c, obj, "single_scattering", &m->bssrdf_single);
  if (st == SS_OK)
    st = read_lod(r, obj, m);
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "bssrdf");
  if (st != SS_OK || !v) {
    return st;
  }
  const ss_bssrdf_ops *ops;
  ss_json_push_key(c, "bssrdf");
  if (cJSON_IsObject(v)) {
    const cJSON *model = cJSON_GetObjectItemCaseSensitive(v, "model");
    if (!model) {
      st = ss_json_fail(c, SS_ERR_PARSE, "a BSSRDF object needs \"model\"");
    } else {
      ss_json_push_key(c, "model");
      st = read_model(r, model, m, &ops);
      ss_json_pop(c);
    }
    if (st == SS_OK)
      st = read_options(r, v, m, ops);
  } else {
    st = read_model(r, v, m, &ops);
  }
  ss_json_pop(c);
  return st;
}
