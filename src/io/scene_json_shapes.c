/* The scene reader: shapes (procedural and mesh files, with transforms)
 * and lights. */
#include "io/scene_json.h"

#include "subsurf/mesh_io.h"
#include "subsurf/transform.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* "transform": {"scale": s | [sx, sy, sz], "rotate": [ax, ay, az, degrees],
 * "translate": [x, y, z]} applied in that order, or {"matrix": [16 numbers,
 * row-major]}. */
static ss_status read_transform(ss_scene_reader *r, const cJSON *obj, ss_mat4 *xf) {
  static const char *const keys[] = {"scale", "rotate", "translate", "matrix", NULL};
  ss_json_ctx *c = &r->json;
  *xf = ss_mat4_identity();
  const cJSON *t = cJSON_GetObjectItemCaseSensitive(obj, "transform");
  if (!t) {
    return SS_OK;
  }
  ss_json_push_key(c, "transform");
  ss_status st = ss_json_expect_object(c, t);
  if (st == SS_OK)
    st = ss_json_check_keys(c, t, keys);
  const cJSON *mat = cJSON_GetObjectItemCaseSensitive(t, "matrix");
  if (st == SS_OK && mat) {
    if (cJSON_HasObjectItem(t, "scale") || cJSON_HasObjectItem(t, "rotate") ||
        cJSON_HasObjectItem(t, "translate")) {
      st = ss_json_fail_key(c, "matrix", "give either a matrix or scale/rotate/translate");
    } else if (!cJSON_IsArray(mat) || cJSON_GetArraySize(mat) != 16) {
      st = ss_json_fail_key(c, "matrix", "expected an array of 16 numbers (row-major)");
    } else {
      for (int i = 0; i < 16 && st == SS_OK; ++i) {
        const cJSON *e = cJSON_GetArrayItem(mat, i);
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) {
          st = ss_json_fail_key(c, "matrix", "element %d is not a finite number", i);
        } else {
          xf->m[i / 4][i % 4] = e->valuedouble;
        }
      }
    }
  } else if (st == SS_OK) {
    ss_rgb scale = ss_rgb_gray(1.0);
    ss_vec3 translate = ss_vec3_make(0, 0, 0);
    st = ss_json_rgb(c, t, "scale", -HUGE_VAL, &scale);
    if (st == SS_OK)
      st = ss_json_vec3(c, t, "translate", &translate);
    const cJSON *rot = cJSON_GetObjectItemCaseSensitive(t, "rotate");
    ss_mat4 rm = ss_mat4_identity();
    if (st == SS_OK && rot) {
      double a[4];
      int ok = cJSON_IsArray(rot) && cJSON_GetArraySize(rot) == 4;
      for (int i = 0; ok && i < 4; ++i) {
        const cJSON *e = cJSON_GetArrayItem(rot, i);
        ok = cJSON_IsNumber(e) && isfinite(e->valuedouble);
        a[i] = ok ? e->valuedouble : 0.0;
      }
      if (!ok || !(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] > 0.0)) {
        st = ss_json_fail_key(c, "rotate",
                              "expected [axis x, axis y, axis z, degrees] with a non-zero axis");
      } else {
        rm = ss_mat4_rotate(a[3], ss_vec3_make(a[0], a[1], a[2]));
      }
    }
    if (st == SS_OK && scale.c[0] * scale.c[1] * scale.c[2] == 0.0) {
      st = ss_json_fail_key(c, "scale", "a zero scale flattens the shape");
    }
    if (st == SS_OK) {
      ss_mat4 sm = ss_mat4_scale(ss_vec3_make(scale.c[0], scale.c[1], scale.c[2]));
      *xf = ss_mat4_mul(ss_mat4_translate(translate), ss_mat4_mul(rm, sm));
    }
  }
  ss_json_pop(c);
  return st;
}

static ss_status positive_int(ss_json_ctx *c, const cJSON *obj, const char *key, long hi,
                              unsigned *out) {
  long v = (long)*out;
  ss_status st = ss_json_int(c, obj, key, 1, hi, &v);
  *out = (unsigned)v;
  return st;
}

static ss_status make_mesh(ss_scene_reader *r, const cJSON *obj, const char *type, ss_mesh **mesh) {
  static const char *const sphere_keys[] = {"name",   "type",   "material",     "transform",
                                            "radius", "center", "subdivisions", NULL};
  static const char *const cube_keys[] = {"name", "type",         "material", "transform",
                                          "size", "tessellation", NULL};
  static const char *const quad_keys[] = {"name",  "type",   "material",     "transform",
                                          "width", "height", "tessellation", NULL};
  static const char *const mesh_keys[] = {"name", "type", "material", "transform", "file", NULL};
  ss_json_ctx *c = &r->json;
  ss_status st;
  *mesh = NULL;
  if (!strcmp(type, "sphere")) {
    double radius = 1.0;
    ss_vec3 center = ss_vec3_make(0, 0, 0);
    unsigned subdiv = 5;
    long sd = subdiv;
    st = ss_json_check_keys(c, obj, sphere_keys);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "radius", 1e-9, 1e9, &radius);
    if (st == SS_OK)
      st = ss_json_vec3(c, obj, "center", &center);
    if (st == SS_OK)
      st = ss_json_int(c, obj, "subdivisions", 0, 8, &sd);
    subdiv = (unsigned)sd;
    if (st == SS_OK && ss_shape_icosphere(radius, subdiv, mesh, c->err) != SS_OK) {
      return ss_json_wrap(c, SS_ERR_PARSE);
    }
    if (st == SS_OK && (center.x != 0.0 || center.y != 0.0 || center.z != 0.0) &&
        ss_mesh_transform(*mesh, ss_mat4_translate(center), c->err) != SS_OK) {
      return ss_json_wrap(c, SS_ERR_PARSE);
    }
    return st;
  }
  if (!strcmp(type, "cube")) {
    ss_rgb size = ss_rgb_gray(1.0);
    unsigned n = 1;
    st = ss_json_check_keys(c, obj, cube_keys);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "size", 1e-9, &size);
    if (st == SS_OK)
      st = positive_int(c, obj, "tessellation", 4096, &n);
    if (st == SS_OK &&
        ss_shape_cube(ss_vec3_make(size.c[0], size.c[1], size.c[2]), n, mesh, c->err) != SS_OK) {
      return ss_json_wrap(c, SS_ERR_PARSE);
    }
    return st;
  }
  if (!strcmp(type, "quad") || !strcmp(type, "plane")) {
    double width = 1.0, height = 1.0;
    unsigned nx = 1, ny = 1;
    st = ss_json_check_keys(c, obj, quad_keys);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "width", 1e-9, 1e9, &width);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "height", 1e-9, 1e9, &height);
    const cJSON *tess = cJSON_GetObjectItemCaseSensitive(obj, "tessellation");
    if (st == SS_OK && tess) {
      if (cJSON_IsNumber(tess)) {
        st = positive_int(c, obj, "tessellation", 4096, &nx);
        ny = nx;
      } else if (cJSON_IsArray(tess) && cJSON_GetArraySize(tess) == 2 &&
                 cJSON_IsNumber(cJSON_GetArrayItem(tess, 0)) &&
                 cJSON_IsNumber(cJSON_GetArrayItem(tess, 1))) {
        double a = cJSON_GetArrayItem(tess, 0)->valuedouble;
        double b = cJSON_GetArrayItem(tess, 1)->valuedouble;
        if (a != floor(a) || b != floor(b) || a < 1 || b < 1 || a > 4096 || b > 4096) {
          st = ss_json_fail_key(c, "tessellation", "counts must be integers in [1, 4096]");
        } else {
          nx = (unsigned)a;
          ny = (unsigned)b;
        }
      } else {
        st = ss_json_fail_key(c, "tessellation", "expected an integer or [nx, ny]");
      }
    }
    if (st == SS_OK && ss_shape_quad(width, height, nx, ny, mesh, c->err) != SS_OK) {
      return ss_json_wrap(c, SS_ERR_PARSE);
    }
    return st;
  }
  if (!strcmp(type, "mesh")) {
    char file[SS_PATH_SIZE] = "", path[2 * SS_PATH_SIZE];
    st = ss_json_check_keys(c, obj, mesh_keys);
    if (st == SS_OK)
      st = ss_json_require(c, obj, "file");
    if (st == SS_OK)
      st = ss_json_string(c, obj, "file", file, sizeof file);
    if (st != SS_OK) {
      return st;
    }
    if (file[0] == '/') {
      snprintf(path, sizeof path, "%s", file);
    } else {
      snprintf(path, sizeof path, "%s/%s", r->base_dir, file);
    }
    if (ss_mesh_read(path, mesh, NULL, c->err) != SS_OK) {
      ss_json_push_key(c, "file");
      st = ss_json_wrap(c, c->err->status == SS_ERR_IO ? SS_ERR_IO : SS_ERR_PARSE);
      ss_json_pop(c);
      return st;
    }
    return SS_OK;
  }
  return ss_json_fail_key(c, "type", "unknown shape type '%s' (sphere, cube, quad, plane, mesh)",
                          type);
}

static ss_status read_shape(ss_scene_reader *r, const cJSON *obj, int index) {
  ss_json_ctx *c = &r->json;
  char name[SS_NAME_SIZE], type[32] = "";
  snprintf(name, sizeof name, "shape%d", index);
  ss_status st = ss_json_string(c, obj, "name", name, sizeof name);
  if (st == SS_OK)
    st = ss_json_require(c, obj, "type");
  if (st == SS_OK)
    st = ss_json_string(c, obj, "type", type, sizeof type);
  int material = -1;
  if (st == SS_OK && cJSON_HasObjectItem(obj, "material")) {
    st = ss_scene_json_reference(r, obj, "material", "material", ss_scene_find_material, &material);
  }
  ss_mat4 xf;
  ss_mesh *mesh = NULL;
  if (st == SS_OK)
    st = read_transform(r, obj, &xf);
  if (st == SS_OK)
    st = make_mesh(r, obj, type, &mesh);
  if (st == SS_OK && ss_mesh_transform(mesh, xf, c->err) != SS_OK) {
    ss_json_push_key(c, "transform");
    st = ss_json_wrap(c, SS_ERR_PARSE);
    ss_json_pop(c);
  }
  if (st != SS_OK) {
    ss_mesh_destroy(mesh);
    return st;
  }
  if (ss_scene_add_shape(r->scene, name, mesh, material, NULL, c->err) != SS_OK) {
    return ss_json_wrap(c, SS_ERR_PARSE);
  }
  return SS_OK;
}

ss_status ss_scene_json_shapes(ss_scene_reader *r, const cJSON *array) {
  return ss_scene_json_each(r, array, read_shape);
}

/* ---- lights */

static ss_status read_light(ss_scene_reader *r, const cJSON *obj, int index) {
  static const char *const point_keys[] = {"name", "type", "position", "intensity", NULL};
  static const char *const spot_keys[] = {"name",    "type",      "position",   "direction",
                                          "target",  "intensity", "cone_angle", "falloff_angle",
                                          "falloff", NULL};
  static const char *const dir_keys[] = {"name", "type", "direction", "irradiance", NULL};
  static const char *const area_keys[] = {"name", "type", "shape", "radiance", NULL};
  static const char *const env_keys[] = {"name", "type",  "radiance", "scale", "map",
                                         "up",   "front", "rotation", NULL};
  static const char *const beam_keys[] = {"name",   "type",  "position", "direction",
                                          "radius", "power", NULL};
  ss_json_ctx *c = &r->json;
  ss_light l;
  memset(&l, 0, sizeof l);
  l.shape = -1;
  l.value = ss_rgb_gray(1.0);
  l.direction = ss_vec3_make(0, 0, -1);
  snprintf(l.name, sizeof l.name, "light%d", index);
  char type[32] = "";
  ss_status st = ss_json_string(c, obj, "name", l.name, sizeof l.name);
  if (st == SS_OK)
    st = ss_json_require(c, obj, "type");
  if (st == SS_OK)
    st = ss_json_string(c, obj, "type", type, sizeof type);
  if (st != SS_OK) {
    return st;
  }
  if (!ss_light_type_from_name(type, &l.type)) {
    return ss_json_fail_key(c, "type",
                            "unknown light type '%s' (point, spot, directional, area, "
                            "environment, beam)",
                            type);
  }
  switch (l.type) {
  case SS_LIGHT_POINT:
    st = ss_json_check_keys(c, obj, point_keys);
    if (st == SS_OK)
      st = ss_json_vec3(c, obj, "position", &l.position);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "intensity", 0.0, &l.value);
    break;
  case SS_LIGHT_SPOT: {
    l.cone_angle = 30.0;
    st = ss_json_check_keys(c, obj, spot_keys);
    if (st == SS_OK)
      st = ss_json_vec3(c, obj, "position", &l.position);
    if (st == SS_OK && cJSON_HasObjectItem(obj, "target")) {
      if (cJSON_HasObjectItem(obj, "direction")) {
        st = ss_json_fail_key(c, "target", "give either a direction or a target");
      } else {
        ss_vec3 target = l.position;
        st = ss_json_vec3(c, obj, "target", &target);
        l.direction = ss_vec3_sub(target, l.position);
      }
    }
    if (st == SS_OK)
      st = ss_json_vec3(c, obj, "direction", &l.direction);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "intensity", 0.0, &l.value);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "cone_angle", 1e-3, 180.0, &l.cone_angle);
    l.falloff_angle = fmax(0.0, l.cone_angle - 5.0);
    if (st == SS_OK) {
      st = ss_json_number(c, obj, "falloff_angle", 0.0, l.cone_angle, &l.falloff_angle);
    }
    char falloff[16] = "quartic";
    if (st == SS_OK)
      st = ss_json_string(c, obj, "falloff", falloff, sizeof falloff);
    if (st == SS_OK && strcmp(falloff, "quartic") && strcmp(falloff, "smoothstep")) {
      st = ss_json_fail_key(c, "falloff", "unknown falloff '%s' (quartic, smoothstep)", falloff);
    }
    l.spot_smoothstep = !strcmp(falloff, "smoothstep");
    break;
  }
  case SS_LIGHT_DIRECTIONAL:
    st = ss_json_check_keys(c, obj, dir_keys);
    if (st == SS_OK)
      st = ss_json_vec3(c, obj, "direction", &l.direction);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "irradiance", 0.0, &l.value);
    break;
  case SS_LIGHT_AREA:
    st = ss_json_check_keys(c, obj, area_keys);
    if (st == SS_OK) {
      st = ss_scene_json_reference(r, obj, "shape", "shape", ss_scene_find_shape, &l.shape);
    }
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "radiance", 0.0, &l.value);
    break;
  case SS_LIGHT_ENVIRONMENT:
    st = ss_json_check_keys(c, obj, env_keys);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "radiance", 0.0, &l.value);
    if (st == SS_OK)
      st = ss_scene_json_envmap(r, obj, &l);
    break;
  case SS_LIGHT_BEAM:
    l.radius = 0.01;
    st = ss_json_check_keys(c, obj, beam_keys);
    if (st == SS_OK)
      st = ss_json_vec3(c, obj, "position", &l.position);
    if (st == SS_OK)
      st = ss_json_vec3(c, obj, "direction", &l.direction);
    if (st == SS_OK)
      st = ss_json_number(c, obj, "radius", 1e-9, 1e9, &l.radius);
    if (st == SS_OK)
      st = ss_json_rgb(c, obj, "power", 0.0, &l.value);
    break;
  }
  if (st != SS_OK) {
    return st;
  }
  if (l.type != SS_LIGHT_AREA && l.type != SS_LIGHT_ENVIRONMENT &&
      ss_vec3_length2(l.direction) == 0.0 && l.type != SS_LIGHT_POINT) {
    return ss_json_fail_key(c, "direction", "must not be zero");
  }
  if (ss_scene_add_light(r->scene, &l, NULL, c->err) != SS_OK) {
    ss_envmap_destroy(l.map);
    return ss_json_wrap(c, SS_ERR_PARSE);
  }
  return SS_OK;
}

ss_status ss_scene_json_lights(ss_scene_reader *r, const cJSON *array) {
  return ss_scene_json_each(r, array, read_light);
}
