/* Writing a finite-element solution (fem.h) as a PLY file (src/io). */
#ifndef SUBSURF_FEM_IO_H
#define SUBSURF_FEM_IO_H

#include "subsurf/fem.h"
#include "subsurf/status.h"

/* ASCII PLY 1.0: element vertex (every vertex of the mesh) with float x y z
 * and the per-vertex values fluence and exitance (0 inside), element face
 * (the boundary triangles, wound outward) with list uchar uint
 * vertex_indices. Written atomically (the file appears complete or not at
 * all); SS_ERR_IO naming the path. */
ss_status ss_fem_write_ply(const char *path, const ss_fem_mesh *mesh, const ss_fem_solution *sol,
                           ss_error *err);

#endif
