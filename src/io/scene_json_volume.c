/* A scene medium's micro-flakes and density grid (volume.h):
 *   "flakes": {"type": "fiber", "p": 20, "axis": [1, 0, 0],
 *              "albedo_falloff": 0, "albedo_exponent": 1}
 *   "grid": {"file": "yarn.ssgrid" | "yarn.vdb", "offset": [0, 0, 0]}
 *   "grid": {"procedural": "yarn", "resolution": 64, "radius": 1, "plies": 3,
 *            "twist": 0.2, "fiber_twist": 0.6, "offset": [0, 0, 0]}
 *   "grid": {"procedural": "wood", "resolution": 64, "size": [4, 2, 1],
 *            "ring": 0.3, "latewood": 2.5, "wobble": 0.4, "offset": [0, 0, 0]} */
#include "io/scene_json.h"
#include "subsurf/grid_io.h"
#include "subsurf/volume.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

ss_status ss_scene_json_flakes(ss_scene_reader *r, const cJSON *obj, ss_medium *m) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "flakes");
  if (!v) {
    return SS_OK;
  }
  static const char *const keys[] = {"type", "p", "axis", "albedo_falloff", "albedo_exponent",
                                     NULL};
  ss_json_ctx *c = &r->json;
  ss_medium_flakes *f = &m->optics.flakes;
  *f = (ss_medium_flakes){SS_FLAKE_NONE, 20.0, ss_vec3_make(0.0, 0.0, 1.0), 0.0, 1.0};
  char type[32] = "";
  ss_json_push_key(c, "flakes");
  ss_status st = ss_json_expect_object(c, v);
  if (st == SS_OK)
    st = ss_json_check_keys(c, v, keys);
  if (st == SS_OK)
    st = ss_json_require(c, v, "type");
  if (st == SS_OK)
    st = ss_json_string(c, v, "type", type, sizeof type);
  if (st == SS_OK && (!ss_flake_type_from_name(type, &f->type) || f->type == SS_FLAKE_NONE)) {
    st = ss_json_fail_key(c, "type", "unknown flake distribution '%s' (uniform, surface, fiber)",
                          type);
  }
  if (st == SS_OK)
    st = ss_json_number(c, v, "p", 0.0, 1000.0, &f->p);
  if (st == SS_OK)
    st = ss_json_number(c, v, "albedo_falloff", 0.0, 1.0, &f->albedo_falloff);
  if (st == SS_OK)
    st = ss_json_number(c, v, "albedo_exponent", 0.0, 100.0, &f->albedo_exponent);
  if (st == SS_OK)
    st = ss_json_vec3(c, v, "axis", &f->axis);
  if (st == SS_OK && !(ss_vec3_length(f->axis) > 0.0 && isfinite(ss_vec3_length(f->axis)))) {
    st = ss_json_fail_key(c, "axis", "must be a non-zero vector");
  }
  ss_json_pop(c);
  return st;
}

static ss_status read_yarn(ss_json_ctx *c, const cJSON *v, int res, ss_grid **g) {
  static const char *const keys[] = {"procedural", "resolution", "offset",      "radius",
                                     "plies",      "twist",      "fiber_twist", NULL};
  ss_yarn_params p = {res, 1.0, 3, 0.2, 0.6};
  long plies = p.plies;
  ss_status st = ss_json_check_keys(c, v, keys);
  if (st == SS_OK)
    st = ss_json_number(c, v, "radius", 1e-6, 1e6, &p.radius);
  if (st == SS_OK)
    st = ss_json_int(c, v, "plies", 1, 16, &plies);
  if (st == SS_OK)
    st = ss_json_number(c, v, "twist", -1e6, 1e6, &p.twist);
  if (st == SS_OK)
    st = ss_json_number(c, v, "fiber_twist", -1e6, 1e6, &p.fiber_twist);
  p.plies = (int)plies;
  if (st == SS_OK && ss_grid_yarn(&p, g, c->err) != SS_OK) {
    st = ss_json_wrap(c, SS_ERR_PARSE);
  }
  return st;
}

static ss_status read_wood(ss_json_ctx *c, const cJSON *v, int res, ss_grid **g) {
  static const char *const keys[] = {"procedural", "resolution", "offset", "size",
                                     "ring",       "latewood",   "wobble", NULL};
  ss_wood_params p = {res, ss_vec3_make(4.0, 2.0, 1.0), 0.3, 2.5, 0.4};
  ss_status st = ss_json_check_keys(c, v, keys);
  if (st == SS_OK)
    st = ss_json_vec3(c, v, "size", &p.size);
  for (int a = 0; st == SS_OK && a < 3; ++a) {
    double s = ss_vec3_component(p.size, a);
    if (!(s >= 1e-6 && s <= 1e6)) {
      st = ss_json_fail_key(c, "size", "each extent must lie in [1e-06, 1e+06], got %g", s);
    }
  }
  if (st == SS_OK)
    st = ss_json_number(c, v, "ring", 1e-6, 1e6, &p.ring);
  if (st == SS_OK)
    st = ss_json_number(c, v, "latewood", 0.0, 1e6, &p.latewood);
  if (st == SS_OK)
    st = ss_json_number(c, v, "wobble", 0.0, 100.0, &p.wobble);
  if (st == SS_OK && ss_grid_wood(&p, g, c->err) != SS_OK) {
    st = ss_json_wrap(c, SS_ERR_PARSE);
  }
  return st;
}

static ss_status read_file(ss_scene_reader *r, const cJSON *v, ss_grid **g) {
  static const char *const keys[] = {"file", "offset", NULL};
  ss_json_ctx *c = &r->json;
  char file[SS_PATH_SIZE] = "", path[2 * SS_PATH_SIZE];
  ss_status st = ss_json_check_keys(c, v, keys);
  if (st == SS_OK)
    st = ss_json_string(c, v, "file", file, sizeof file);
  if (st != SS_OK) {
    return st;
  }
  snprintf(path, sizeof path, file[0] == '/' ? "%.0s%s" : "%s/%s", r->base_dir, file);
  if (ss_grid_read(path, g, c->err) != SS_OK) {
    ss_json_push_key(c, "file");
    st = ss_json_wrap(c, c->err->status == SS_ERR_IO ? SS_ERR_IO : SS_ERR_PARSE);
    ss_json_pop(c);
  }
  return st;
}

static ss_status read_grid(ss_scene_reader *r, const cJSON *v, ss_grid **g) {
  ss_json_ctx *c = &r->json;
  ss_status st = ss_json_expect_object(c, v);
  if (st != SS_OK) {
    return st;
  }
  int has_file = cJSON_HasObjectItem(v, "file"), has_proc = cJSON_HasObjectItem(v, "procedural");
  if (has_file == has_proc) {
    return ss_json_fail(c, SS_ERR_PARSE, "give either \"file\" or \"procedural\"");
  }
  if (has_file) {
    return read_file(r, v, g);
  }
  char kind[32] = "";
  long res = 64;
  st = ss_json_string(c, v, "procedural", kind, sizeof kind);
  if (st == SS_OK)
    st = ss_json_int(c, v, "resolution", 1, 512, &res);
  if (st != SS_OK) {
    return st;
  }
  if (!strcmp(kind, "yarn")) {
    return read_yarn(c, v, (int)res, g);
  }
  if (!strcmp(kind, "wood")) {
    return read_wood(c, v, (int)res, g);
  }
  return ss_json_fail_key(c, "procedural", "unknown procedural grid '%s' (yarn, wood)", kind);
}

ss_status ss_scene_json_grid(ss_scene_reader *r, const cJSON *obj, ss_medium *m) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "grid");
  m->grid = NULL;
  if (!v) {
    return SS_OK;
  }
  ss_json_ctx *c = &r->json;
  ss_json_push_key(c, "grid");
  ss_vec3 offset = ss_vec3_make(0.0, 0.0, 0.0);
  ss_status st = read_grid(r, v, &m->grid);
  if (st == SS_OK)
    st = ss_json_vec3(c, v, "offset", &offset);
  if (st == SS_OK) {
    m->grid->lo = ss_vec3_add(m->grid->lo, offset);
    m->grid->hi = ss_vec3_add(m->grid->hi, offset);
  } else {
    ss_grid_destroy(m->grid);
    m->grid = NULL;
  }
  ss_json_pop(c);
  return st;
}
