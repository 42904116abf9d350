#include "mesh_io_internal.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

int ss_index_buffer_reserve(ss_index_buffer *b, size_t capacity) {
  if (capacity <= b->capacity) {
    return 0;
  }
  uint32_t *grown = realloc(b->data, capacity * sizeof *grown);
  if (!grown) {
    return -1;
  }
  b->data = grown;
  b->capacity = capacity;
  return 0;
}

int ss_index_buffer_push(ss_index_buffer *b, const uint32_t *v, size_t n) {
  if (b->size + n > b->capacity && ss_index_buffer_reserve(b, 2 * (b->size + n) + 16) != 0) {
    return -1;
  }
  memcpy(b->data + b->size, v, n * sizeof *v);
  b->size += n;
  return 0;
}

void ss_index_buffer_free(ss_index_buffer *b) {
  free(b->data);
  b->data = NULL;
  b->size = b->capacity = 0;
}

ss_status ss_mesh_io_finish(const char *path, size_t nv, float **pos, float **nrm, float **uv,
                            ss_index_buffer *tris, size_t npolys, ss_mesh **out,
                            ss_mesh_read_info *info, ss_error *err) {
  *out = NULL;
  if (tris->size == 0) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: the file has no faces (expected a triangle mesh)",
                        path);
  }
  ss_mesh *m;
  ss_status st = ss_mesh_create(0, 0, 0, &m, err);
  if (st != SS_OK) {
    return st;
  }
  free(m->positions);
  free(m->indices);
  m->num_vertices = nv;
  m->num_triangles = tris->size / 3;
  m->positions = *pos;
  m->normals = *nrm;
  m->uvs = *uv;
  m->indices = tris->data;
  *pos = *nrm = *uv = NULL;
  tris->data = NULL;
  tris->size = tris->capacity = 0;
  size_t degenerate = 0;
  st = ss_mesh_validate(m, &degenerate, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    ss_mesh_destroy(m);
    return st;
  }
  if (info) {
    info->num_polygons = npolys;
    info->num_degenerate = degenerate;
  }
  *out = m;
  return SS_OK;
}

static int has_extension(const char *path, const char *ext) {
  size_t n = strlen(path), e = strlen(ext);
  return n > e && strcasecmp(path + n - e, ext) == 0;
}

ss_status ss_mesh_read(const char *path, ss_mesh **out, ss_mesh_read_info *info, ss_error *err) {
  if (has_extension(path, ".ply")) {
    return ss_mesh_read_ply(path, out, info, err);
  }
  if (has_extension(path, ".obj")) {
    return ss_mesh_read_obj(path, out, info, err);
  }
  *out = NULL;
  return ss_error_set(err, SS_ERR_UNSUPPORTED,
                      "%s: unknown mesh format (expected a .ply or .obj file)", path);
}
