/* Spherical texture coordinates added to a mesh in place (private to
 * src/render): the icosphere generator uses it on its own mesh, and
 * ss_mesh_add_spherical_uvs on a copy. */
#ifndef SUBSURF_RENDER_SPHERE_UV_H
#define SUBSURF_RENDER_SPHERE_UV_H

#include "subsurf/mesh.h"

/* Gives m (positions around the origin, with normals) the texture
 * coordinates of ss_mesh_add_spherical_uvs: allocates m->uvs, appends the
 * seam and pole copies to the vertex arrays and points the triangles at
 * them. On failure m is left consistent but partly converted: the caller
 * destroys it. */
ss_status ss_mesh_spherical_uvs_in_place(ss_mesh *m, ss_error *err);

#endif
