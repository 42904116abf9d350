/* The medium of `subsurf fem` as a scene medium (material.h, volume.h):
 * isotropic or micro-flakes, homogeneous or scaled by a density grid file
 * (raw or OpenVDB, the scene format's "grid": {"file"}) whose voxels may
 * carry the flakes' axis, sampled per tetrahedron by the `fem` integrator's
 * ss_fem_scene_medium (Jakob2010 eq. 28 and 34). */
#ifndef SUBSURF_CLI_FEM_VOLUME_H
#define SUBSURF_CLI_FEM_VOLUME_H

#include "render/integrators/fem_medium.h"
#include "subsurf/material.h"

typedef struct {
  double sigma_s_prime, sigma_a; /* reduced scattering (g = 0 for flakes) and absorption */
  ss_medium_flakes flakes;       /* type SS_FLAKE_NONE: isotropic */
  const char *grid_path;         /* or NULL: homogeneous */
  double grid_offset[3], min_density;
} ss_cli_fem_medium_args;

typedef struct {
  ss_medium med;
  ss_fem_scene_medium coeffs; /* the ss_fem_medium_fn's context */
} ss_cli_fem_medium;

/* Builds the medium (the grid read and offset); on bad input prints one
 * line naming the option or the file and returns 2; 1 when out of memory. */
int ss_cli_fem_medium_init(ss_cli_fem_medium *m, const ss_cli_fem_medium_args *a);
void ss_cli_fem_medium_release(ss_cli_fem_medium *m);

/* The largest density (1 without a grid). */
double ss_cli_fem_medium_max_density(const ss_cli_fem_medium *m);

#endif
