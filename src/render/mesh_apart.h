/* How two closed meshes lie relative to each other (private to src/render):
 * the scene finds the media that touch or nest (media_nesting.h), whose
 * paths then carry a stack of media. */
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
/* 1 when p lies inside the closed mesh m (ray parity, majority of three). */
int ss_mesh_contains(const ss_mesh *m, ss_vec3 p);

#endif
