/* pbrt-v3's shapes ("sphere", "trianglemesh", "plymesh") as scene meshes,
 * with their area lights (AreaLightSource "diffuse") and object instances
 * (ObjectBegin/ObjectEnd/ObjectInstance) (pbrt.h, docs/pbrt-import.md). */
#include "io/pbrt.h"

#include "subsurf/mesh_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ss_pbrt_area_light(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  if (strcmp(type, "diffuse")) {
    ss_pbrt_warn(P, ps->file, ps->line, "AreaLightSource \"%s\" is not supported (ignored)", type);
    return;
  }
  ss_rgb l = ss_rgb_gray(1.0), scale = ss_rgb_gray(1.0);
  ss_pbrt_rgb(P, ps, "L", &l);
  ss_pbrt_rgb(P, ps, "scale", &scale);
  int two_sided = 0;
  if (ss_pbrt_bool(P, ps, "twosided", &two_sided) && two_sided) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "AreaLightSource: twosided is not supported; the shapes emit on their front "
                 "(normal) side only");
  }
  long samples;
  ss_pbrt_int(P, ps, "nsamples", 1, 1L << 20, &samples); /* noise only */
  ss_pbrt_int(P, ps, "samples", 1, 1L << 20, &samples);
  P->gs.area = 1;
  P->gs.area_l = ss_rgb_make(l.c[0] * scale.c[0], l.c[1] * scale.c[1], l.c[2] * scale.c[2]);
}

/* pbrt-v3 orients a triangle by its shading normals when the mesh has them
 * (Faceforward in Triangle::Intersect): wind each triangle so that its
 * geometric normal agrees with the mean of its vertex normals. */
static void orient_by_normals(ss_mesh *m) {
  if (!m->normals) {
    return;
  }
  for (size_t t = 0; t < m->num_triangles; ++t) {
    uint32_t *idx = m->indices + 3 * t;
    ss_vec3 n = ss_vec3_make(0, 0, 0);
    for (int k = 0; k < 3; ++k) {
      const float *v = m->normals + 3 * (size_t)idx[k];
      n = ss_vec3_add(n, ss_vec3_make(v[0], v[1], v[2]));
    }
    if (ss_vec3_dot(ss_mesh_triangle_normal(m, t), n) < 0.0) {
      uint32_t tmp = idx[1];
      idx[1] = idx[2];
      idx[2] = tmp;
    }
  }
}

static ss_mesh *triangle_mesh(ss_pbrt *P, ss_pbrt_params *ps) {
  static const char *const ints[] = {"integer", NULL};
  static const char *const points[] = {"point3", "point", NULL};
  static const char *const normals[] = {"normal", "normal3", NULL};
  static const char *const uvs[] = {"float", "point2", NULL};
  const ss_pbrt_param *p = ss_pbrt_array(P, ps, "P", points);
  const ss_pbrt_param *ind = ss_pbrt_array(P, ps, "indices", ints);
  const ss_pbrt_param *n = ss_pbrt_array(P, ps, "N", normals);
  const ss_pbrt_param *uv = ss_pbrt_array(P, ps, "uv", uvs);
  if (!uv) {
    uv = ss_pbrt_array(P, ps, "st", uvs);
  }
  if (P->st != SS_OK) {
    return NULL;
  }
  if (!p || p->num_nums % 3 || p->num_nums == 0) {
    ss_pbrt_fail(P, ps->file, ps->line,
                 "Shape \"trianglemesh\": needs \"point3 P\" with a multiple of 3 numbers");
    return NULL;
  }
  size_t nv = p->num_nums / 3;
  size_t ni = ind ? ind->num_nums : (nv == 3 ? 3 : 0);
  if (ni == 0 || ni % 3 || nv >= UINT32_MAX) {
    ss_pbrt_fail(P, ps->file, ps->line,
                 "Shape \"trianglemesh\": needs \"integer indices\" with a multiple of 3 values "
                 "(only a single triangle may leave them out)");
    return NULL;
  }
  if ((n && n->num_nums != 3 * nv) || (uv && uv->num_nums != 2 * nv)) {
    ss_pbrt_fail(P, ps->file, ps->line,
                 "Shape \"trianglemesh\": \"%s\" needs %zu values (one per vertex of P), got %zu",
                 n && n->num_nums != 3 * nv ? "normal N" : "uv",
                 (n && n->num_nums != 3 * nv ? 3 : 2) * nv,
                 n && n->num_nums != 3 * nv ? n->num_nums : uv->num_nums);
    return NULL;
  }
  ss_mesh *m = NULL;
  ss_error e;
  if (ss_mesh_create(nv, ni / 3, (n ? SS_MESH_NORMALS : 0u) | (uv ? SS_MESH_UVS : 0u), &m, &e) !=
      SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "Shape \"trianglemesh\": %s", e.message);
    return NULL;
  }
  for (size_t i = 0; i < 3 * nv; ++i) {
    m->positions[i] = (float)p->nums[i];
    if (n) {
      m->normals[i] = (float)n->nums[i];
    }
  }
  for (size_t i = 0; uv && i < 2 * nv; ++i) {
    m->uvs[i] = (float)uv->nums[i];
  }
  for (size_t i = 0; i < ni; ++i) {
    double v = ind ? ind->nums[i] : (double)i;
    if (!(v >= 0.0 && v < (double)nv) || v != floor(v)) {
      ss_pbrt_fail(P, ps->file, ind ? ind->line : ps->line,
                   "Shape \"trianglemesh\": index %zu is %g, not a vertex of P (0..%zu)", i, v,
                   nv - 1);
      ss_mesh_destroy(m);
      return NULL;
    }
    m->indices[i] = (uint32_t)v;
  }
  if (ss_mesh_validate(m, NULL, &e) != SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "Shape \"trianglemesh\": %s", e.message);
    ss_mesh_destroy(m);
    return NULL;
  }
  return m;
}

static ss_mesh *make_mesh(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  ss_mesh *m = NULL;
  ss_error e;
  if (!strcmp(type, "sphere")) {
    double radius = 1.0, zmin = -1.0, zmax = 1.0, phimax = 360.0;
    long subdivisions = 5;
    ss_pbrt_float(P, ps, "radius", &radius);
    int partial = ss_pbrt_float(P, ps, "zmin", &zmin) + ss_pbrt_float(P, ps, "zmax", &zmax) +
                  ss_pbrt_float(P, ps, "phimax", &phimax);
    ss_pbrt_int(P, ps, "subdivisions", 0, 8, &subdivisions); /* subsurf's own */
    long cap = P->limits.max_subdivisions;
    subdivisions = cap > 0 && subdivisions > cap ? cap : subdivisions;
    if (partial && (zmin > -radius || zmax < radius || phimax < 360.0)) {
      ss_pbrt_warn(P, ps->file, ps->line,
                   "Shape \"sphere\": zmin, zmax and phimax are not supported; the whole sphere "
                   "is used");
    }
    if (P->st == SS_OK && !(radius > 0.0 && radius < 1e12)) {
      ss_pbrt_fail(P, ps->file, ps->line, "Shape \"sphere\": radius must be > 0, got %g", radius);
    }
    if (P->st == SS_OK && ss_shape_icosphere(radius, (unsigned)subdivisions, &m, &e) != SS_OK) {
      ss_pbrt_fail(P, ps->file, ps->line, "Shape \"sphere\": %s", e.message);
    }
    return m;
  }
  if (!strcmp(type, "trianglemesh")) {
    m = triangle_mesh(P, ps);
  } else if (!strcmp(type, "plymesh")) {
    char name[SS_PATH_SIZE], path[SS_PATH_SIZE];
    if (!ss_pbrt_string(P, ps, "filename", name, sizeof name)) {
      ss_pbrt_fail(P, ps->file, ps->line, "Shape \"plymesh\": needs \"string filename\"");
      return NULL;
    }
    ss_pbrt_resolve(P, name, path);
    if (ss_mesh_read_ply(path, &m, NULL, &e) != SS_OK) {
      ss_pbrt_fail(P, ps->file, ps->line, "Shape \"plymesh\": %s", e.message);
      P->st = P->err->status = e.status == SS_ERR_IO ? SS_ERR_IO : SS_ERR_PARSE;
      return NULL;
    }
  } else {
    ss_pbrt_warn(P, ps->file, ps->line, "Shape \"%s\" is not supported (left out)", type);
    return NULL;
  }
  if (m && P->limits.max_triangles > 0 && m->num_triangles > P->limits.max_triangles) {
    ss_pbrt_fail(P, ps->file, ps->line, "Shape \"%s\": %zu triangles, more than the limit %zu",
                 type, m->num_triangles, P->limits.max_triangles);
    ss_mesh_destroy(m);
    return NULL;
  }
  if (m) {
    orient_by_normals(m);
  }
  return m;
}

static void add_to_object(ss_pbrt *P, ss_pbrt_params *ps, ss_mesh *mesh, int material) {
  ss_pbrt_object *o = &P->objects[P->object];
  void *grown = realloc(o->shapes, (o->n + 1) * sizeof *o->shapes);
  if (!grown) {
    ss_mesh_destroy(mesh);
    ss_pbrt_fail(P, ps->file, ps->line, "out of memory");
    return;
  }
  o->shapes = grown;
  o->shapes[o->n].mesh = mesh;
  o->shapes[o->n++].material = material;
}

/* Adds a world-space mesh (taking it) with its material and the current
 * area light, if any. */
static void add_shape(ss_pbrt *P, const char *file, int line, ss_mesh *mesh, int material,
                      int area) {
  char name[SS_NAME_SIZE];
  snprintf(name, sizeof name, "shape%d", P->num_shapes++);
  int index = -1;
  ss_error e;
  if (ss_scene_add_shape(P->scene, name, mesh, material, &index, &e) != SS_OK) {
    ss_pbrt_fail(P, file, line, "%s", e.message);
    return;
  }
  if (!area) {
    return;
  }
  ss_light l;
  memset(&l, 0, sizeof l);
  l.type = SS_LIGHT_AREA;
  l.shape = index;
  l.value = P->gs.area_l;
  snprintf(l.name, sizeof l.name, "%s", name);
  if (ss_scene_add_light(P->scene, &l, NULL, &e) != SS_OK) {
    ss_pbrt_fail(P, file, line, "AreaLightSource: %s", e.message);
  }
}

void ss_pbrt_shape(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  ss_mesh *mesh = make_mesh(P, type, ps);
  if (!mesh || P->st != SS_OK) {
    ss_mesh_destroy(mesh);
    return;
  }
  if (P->gs.reverse && !mesh->normals) {
    ss_mesh_flip_winding(mesh);
  }
  int skip = 0;
  int material = ss_pbrt_scene_material(P, ps->file, ps->line, &skip);
  int area = P->gs.area;
  if (area && P->object >= 0) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "area lights inside ObjectBegin are not supported (as in pbrt-v3); the shape "
                 "does not emit");
    area = 0;
  }
  if (skip && !area) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "Shape \"%s\" with Material \"none\" and no inside medium is invisible (left "
                 "out)",
                 type);
    ss_mesh_destroy(mesh);
    return;
  }
  if (skip) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "an emitting Shape with Material \"none\" is a black emitter in subsurf (pbrt-v3 "
                 "lets light through it)");
  }
  ss_error e;
  ss_mat4 xf = P->object >= 0 ? P->gs.ctm : ss_pbrt_to_world(P, P->gs.ctm);
  if (P->st != SS_OK || ss_mesh_transform(mesh, xf, &e) != SS_OK) {
    if (P->st == SS_OK) {
      ss_pbrt_fail(P, ps->file, ps->line, "Shape \"%s\": %s", type, e.message);
    }
    ss_mesh_destroy(mesh);
    return;
  }
  if (P->object >= 0) {
    add_to_object(P, ps, mesh, material);
  } else {
    add_shape(P, ps->file, ps->line, mesh, material, area);
  }
}

void ss_pbrt_object_instance(ss_pbrt *P, const char *name, const char *file, int line) {
  if (P->object >= 0) {
    ss_pbrt_fail(P, file, line, "ObjectInstance inside ObjectBegin \"%s\"",
                 P->objects[P->object].name);
    return;
  }
  for (size_t i = P->num_objects; i-- > 0;) {
    const ss_pbrt_object *o = &P->objects[i];
    if (strcmp(o->name, name)) {
      continue;
    }
    ss_mat4 xf = ss_pbrt_to_world(P, P->gs.ctm);
    for (size_t k = 0; k < o->n && P->st == SS_OK; ++k) {
      ss_mesh *mesh = NULL;
      ss_error e;
      if (ss_mesh_clone(o->shapes[k].mesh, &mesh, &e) != SS_OK ||
          ss_mesh_transform(mesh, xf, &e) != SS_OK) {
        ss_mesh_destroy(mesh);
        ss_pbrt_fail(P, file, line, "ObjectInstance \"%s\": %s", name, e.message);
        return;
      }
      add_shape(P, file, line, mesh, o->shapes[k].material, 0);
    }
    return;
  }
  ss_pbrt_fail(P, file, line, "ObjectInstance: no object named \"%s\"", name);
}
