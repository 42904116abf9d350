/* Indexed triangle meshes and procedural shapes.
 *
 * A mesh is plain data that readers and generators fill and the accelerator
 * (accel.h) shares with Embree: float positions (Embree's vertex format),
 * optional per-vertex normals and texture coordinates, uint32 indices.
 * Orientation: a triangle (i0, i1, i2) has the geometric normal
 * (p1 - p0) x (p2 - p0) (counter-clockwise seen from the front); every
 * procedural closed shape is wound so that this normal points OUTWARD. */
#ifndef SUBSURF_MESH_H
#define SUBSURF_MESH_H

#include "subsurf/status.h"
#include "subsurf/transform.h"
#include "subsurf/vec3.h"

#include <stddef.h>
#include <stdint.h>

enum {
  SS_MESH_NORMALS = 1u << 0, /* allocate per-vertex normals */
  SS_MESH_UVS = 1u << 1,     /* allocate per-vertex texture coordinates */
};

typedef struct {
  size_t num_vertices;
  size_t num_triangles;
  float *positions;  /* 3 * num_vertices, and one float of padding that Embree
                      * reads past the last vertex (ss_mesh_create allocates it) */
  float *normals;    /* 3 * num_vertices, or NULL */
  float *uvs;        /* 2 * num_vertices, or NULL */
  uint32_t *indices; /* 3 * num_triangles */
  /* Nonzero: closed and wound outward by construction (set by the sphere
   * and cube generators, whose tests prove it with ss_mesh_check_closed;
   * kept by ss_mesh_clone and ss_mesh_transform). The scene then skips the
   * closedness check; clear it after editing the indices. */
  int closed;
} ss_mesh;

/* Allocates a mesh with uninitialised arrays (normals/uvs per `flags`),
 * each with one element of padding, and large ones huge-page backed.
 * num_vertices must be < 2^32. */
ss_status ss_mesh_create(size_t num_vertices, size_t num_triangles, unsigned flags, ss_mesh **out,
                         ss_error *err);
void ss_mesh_destroy(ss_mesh *mesh);
ss_status ss_mesh_clone(const ss_mesh *mesh, ss_mesh **out, ss_error *err);

static inline ss_vec3 ss_mesh_position(const ss_mesh *m, uint32_t v) {
  const float *p = m->positions + 3 * (size_t)v;
  return ss_vec3_make(p[0], p[1], p[2]);
}
/* The three corners of triangle `tri`. */
void ss_mesh_triangle(const ss_mesh *m, size_t tri, ss_vec3 p[3]);
/* Unnormalised geometric normal (p1 - p0) x (p2 - p0); its length is twice
 * the area. */
ss_vec3 ss_mesh_triangle_normal(const ss_mesh *m, size_t tri);
double ss_mesh_triangle_area(const ss_mesh *m, size_t tri);
double ss_mesh_area(const ss_mesh *m);
/* Volume enclosed by a closed mesh (divergence theorem); positive when the
 * winding is outward. */
double ss_mesh_signed_volume(const ss_mesh *m);
/* Axis-aligned bounds of the vertices; lo > hi for an empty mesh. */
void ss_mesh_bounds(const ss_mesh *m, ss_vec3 *lo, ss_vec3 *hi);

/* Applies an affine transform to positions, normals (by the inverse
 * transpose, renormalised) and, when the transform mirrors (det < 0),
 * swaps two indices of every triangle so that outward winding stays outward.
 * Fails on a singular or non-finite matrix. */
ss_status ss_mesh_transform(ss_mesh *m, ss_mat4 xf, ss_error *err);
/* Reverses every triangle's winding (normals are left untouched). */
void ss_mesh_flip_winding(ss_mesh *m);

/* Checks the data: finite positions/normals/uvs, non-zero normals, indices
 * in range. Degenerate (zero-area) triangles are not an error: their count
 * is stored in *num_degenerate (may be NULL). The message names the vertex
 * or triangle index; the caller prefixes the file name. */
ss_status ss_mesh_validate(const ss_mesh *m, size_t *num_degenerate, ss_error *err);
/* Checks that the surface is closed and consistently oriented: after
 * welding vertices with bit-identical positions, every directed edge (a, b)
 * is matched by exactly one (b, a). The message names an offending edge. */
ss_status ss_mesh_check_closed(const ss_mesh *m, ss_error *err);

/* ---- Procedural shapes (src/render/shapes.c), all centred at the origin. */

/* UV sphere: n_theta >= 2 rings from pole to pole, n_phi >= 3 segments;
 * smooth normals, uvs (u = phi / 2pi, v = theta / pi). The pole rows are
 * triangles (no degenerate ones); pole and seam vertices are duplicated for
 * the uvs with bit-identical positions, so the surface is closed. */
ss_status ss_shape_sphere_uv(double radius, unsigned n_theta, unsigned n_phi, ss_mesh **out,
                             ss_error *err);
/* Icosphere: the icosahedron subdivided `subdivisions` times (0..10), giving
 * 20 * 4^subdivisions nearly equal triangles; smooth normals and spherical
 * uvs (ss_mesh_add_spherical_uvs). */
ss_status ss_shape_icosphere(double radius, unsigned subdivisions, ss_mesh **out, ss_error *err);
/* A copy of `m` (positions around the origin, with normals) with spherical
 * texture coordinates u = phi / 2pi, v = theta / pi (theta from +z), as
 * ss_shape_sphere_uv. Vertices on the seam are duplicated with u + 1 for
 * the triangles across it and pole vertices once per triangle (with the
 * mean u of its other corners), at bit-identical positions, so every
 * triangle's uvs are continuous and the surface stays closed. */
ss_status ss_mesh_add_spherical_uvs(const ss_mesh *m, ss_mesh **out, ss_error *err);
/* Box of side lengths `size`, each face an n x n grid of quads (n >= 1),
 * per-face normals and uvs; closed (shared edges are bit-identical). */
ss_status ss_shape_cube(ss_vec3 size, unsigned n, ss_mesh **out, ss_error *err);
/* Rectangle in the z = 0 plane, x in [-width/2, width/2], y in
 * [-height/2, height/2], normal +z, an nx x ny grid of quads; uvs in [0,1]. */
ss_status ss_shape_quad(double width, double height, unsigned nx, unsigned ny, ss_mesh **out,
                        ss_error *err);

#endif
