/* Shared inside the fem module: point location and element geometry. */
#ifndef SUBSURF_FEM_INTERNAL_H
#define SUBSURF_FEM_INTERNAL_H

#include "subsurf/fem.h"

/* The tetrahedron containing x (on its faces within a relative 1e-9) and x's
 * barycentric coordinates in it; 0 when none does. Linear in the number of
 * tetrahedra. */
int ss_fem_locate(const ss_fem_mesh *mesh, ss_vec3 x, size_t *tet, double lambda[4]);
/* x's barycentric coordinates in tetrahedron t; 1 when x is in it (within a
 * relative 1e-9). */
int ss_fem_tet_barycentric(const ss_fem_mesh *mesh, size_t t, ss_vec3 x, double lambda[4]);

/* Uniform cells listing the tetrahedra whose bounding boxes overlap them. */
typedef struct {
  ss_vec3 lo;
  double cell;
  size_t dims[3];
  size_t *start; /* dims[0] dims[1] dims[2] + 1 offsets into tet */
  uint32_t *tet;
} ss_fem_cells;

/* For locating many points: cells over the mesh, and in the cells that list
 * many tetrahedra (graded meshes) finer cells over that cell (fem_grid.c). */
typedef struct {
  ss_fem_cells top;
  int64_t *child; /* per top cell: its finer cells in fine[], or -1 */
  ss_fem_cells *fine;
  size_t num_fine;
} ss_fem_grid;
ss_status ss_fem_grid_build(const ss_fem_mesh *mesh, ss_fem_grid *g, ss_error *err);
int ss_fem_grid_locate(const ss_fem_grid *g, const ss_fem_mesh *mesh, ss_vec3 x, size_t *tet,
                       double lambda[4]);
void ss_fem_grid_free(ss_fem_grid *g);

/* Deposits the problem's rays into the right-hand side b (q_i, eq. 39);
 * returns the power placed inside the mesh in *injected. */
ss_status ss_fem_deposit_rays(const ss_fem_mesh *mesh, const ss_fem_problem *pb, double *b,
                              double *injected, ss_error *err);

/* The assembled system K a = b of Jakob2010 eq. 39-42, in CHOLMOD's form
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
