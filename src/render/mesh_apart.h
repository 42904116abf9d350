/* How two closed meshes lie relative to each other (private to src/render):
 * the scene requires the boundaries of media to be apart, since the volume
 * path tracer tells the medium of a segment from the surface it ends on,
 * which is only right when no medium touches or contains another. */
#ifndef SUBSURF_RENDER_MESH_APART_H
#define SUBSURF_RENDER_MESH_APART_H

#include "subsurf/mesh.h"

typedef enum {
  SS_MESHES_APART,   /* disjoint, closer than eps nowhere */
  SS_MESHES_TOUCH,   /* surfaces cross or come within eps */
  SS_MESHES_A_IN_B,  /* a lies inside b */
  SS_MESHES_B_IN_A,  /* b lies inside a */
  SS_MESHES_UNKNOWN, /* out of memory */
} ss_mesh_relation;

/* For closed meshes (ss_mesh_check_closed); eps >= 0 in world units. */
ss_mesh_relation ss_mesh_relation_of(const ss_mesh *a, const ss_mesh *b, double eps);

#endif
