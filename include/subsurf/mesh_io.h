/* Strict readers of triangle meshes from PLY and OBJ files (src/io).
 *
 * Polygons of any size are triangulated as fans (v0, vk, vk+1). Vertex
 * normals and texture coordinates are kept when the file has them for every
 * vertex. Errors are SS_ERR_IO (cannot open/read) or SS_ERR_PARSE, with a
 * message that starts with the path and names the line (ASCII) or element
 * index (binary) and what was expected. The result has passed
 * ss_mesh_validate (degenerate triangles are kept and counted). */
#ifndef SUBSURF_MESH_IO_H
#define SUBSURF_MESH_IO_H

#include "subsurf/mesh.h"
#include "subsurf/status.h"

#include <stddef.h>

typedef struct {
  size_t num_polygons;   /* faces in the file */
  size_t num_degenerate; /* zero-area triangles after triangulation */
} ss_mesh_read_info;

/* PLY: format ascii 1.0, binary_little_endian 1.0 or binary_big_endian 1.0.
 * Element "vertex" with float/double/int properties x y z, optional nx ny nz
 * and u v (or s t, texture_u texture_v); element "face" with a list property
 * vertex_indices (or vertex_index) of any integer types. Other elements and
 * properties are skipped; comments and obj_info are ignored. */
ss_status ss_mesh_read_ply(const char *path, ss_mesh **out, ss_mesh_read_info *info, ss_error *err);

/* OBJ: v x y z [w] (or x y z r g b), vt u [v [w]], vn x y z, f with v, v/vt, v//vn or v/vt/vn
 * references (1-based, negative = relative to the end). Other statements (o,
 * g, s, usemtl, mtllib, l, p, ...) are ignored. Vertices are split per
 * distinct (v, vt, vn) combination so that normals and uvs stay per-vertex;
 * normals (uvs) are kept only when every face reference carries one. */
ss_status ss_mesh_read_obj(const char *path, ss_mesh **out, ss_mesh_read_info *info, ss_error *err);

/* Dispatches on the extension (.ply or .obj, case-insensitive). */
ss_status ss_mesh_read(const char *path, ss_mesh **out, ss_mesh_read_info *info, ss_error *err);

#endif
