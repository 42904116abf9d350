/* Shared inside the fem module: point location and element geometry. */
#ifndef SUBSURF_FEM_INTERNAL_H
#define SUBSURF_FEM_INTERNAL_H

#include "subsurf/fem.h"

/* The tetrahedron containing x (on its faces within a relative 1e-9) and x's
 * barycentric coordinates in it; 0 when none does. Linear in the number of
 * tetrahedra. */
int ss_fem_locate(const ss_fem_mesh *mesh, ss_vec3 x, size_t *tet, double lambda[4]);

/* The assembled system K a = b of seed 003, eq. 39-42, in CHOLMOD's form
 * (upper triangle, duplicates summed), and what the energy balance and the
 * exitance need. */
typedef struct {
  size_t n;
  void *K;               /* cholmod_sparse *, stype = 1 */
  double *b;             /* right-hand side q + g */
  double *gamma_vertex;  /* Gamma_s at each vertex (spot density), for M_o */
  double *absorb_weight; /* int mu0/(4 pi) beta_i: absorbed = sum w_i a_i */
  double *face_weight;   /* int beta_i ds over the boundary */
  double A, spot_injected, volume_injected;
} ss_fem_system;

/* Assembles with CHOLMOD's workspace `common` (a cholmod_common *). */
ss_status ss_fem_assemble(const ss_fem_mesh *mesh, ss_fem_medium_fn medium, void *ctx,
                          const ss_fem_problem *problem, void *common, ss_fem_system *sys,
                          ss_error *err);
void ss_fem_system_free(ss_fem_system *sys, void *common);

#endif
