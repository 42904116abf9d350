/* Spherical texture coordinates added to a mesh in place (private to
 * src/render): the icosphere generator uses it on its own mesh, and
 * ss_mesh_add_spherical_uvs on a copy. */
#ifndef SUBSURF_RENDER_SPHERE_UV_H
#define SUBSURF_RENDER_SPHERE_UV_H

#include "subsurf/mesh.h"

/* Vertex room for a mesh of num_vertices vertices and its seam and pole
 * copies, so that the arrays rarely have to grow. */
size_t ss_spherical_uvs_room(size_t num_vertices);

/* Gives m (positions around the origin, with normals) the texture
 * coordinates of ss_mesh_add_spherical_uvs: appends the seam and pole
 * copies to the vertex arrays and points the triangles at them. With room
 * 0 the uvs are allocated here and the arrays grown and trimmed as needed;
 * otherwise the caller allocated positions, normals and uvs for `room`
 * (ss_spherical_uvs_room) vertices, which stay allocated. On failure m is
 * left consistent but partly converted: the caller destroys it. */
ss_status ss_mesh_spherical_uvs_in_place(ss_mesh *m, size_t room, ss_error *err);

#endif
