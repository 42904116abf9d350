/* The medium of `subsurf fem` (fem_volume.h). */
#include "cli/fem_volume.h"

#include "subsurf/grid.h"
#include "subsurf/grid_io.h"
#include "subsurf/volume.h"

#include <stdio.h>
#include <string.h>

#define CMD "fem"

int ss_cli_fem_medium_init(ss_cli_fem_medium *m, const ss_cli_fem_medium_args *a) {
  memset(m, 0, sizeof *m);
  snprintf(m->med.name, sizeof m->med.name, "fem");
  m->med.optics = ss_medium_optics_gray(a->sigma_s_prime, a->sigma_a, 0.0, SS_PHASE_ISOTROPIC);
  m->med.optics.flakes = a->flakes;
  ss_error err = {0};
  if (a->grid_path) {
    if (ss_grid_read(a->grid_path, &m->med.grid, &err) != SS_OK) {
      /* the reader's message names the file */
      fprintf(stderr, "subsurf " CMD ": --grid: %s\n", err.message);
      return err.status == SS_ERR_NO_MEMORY ? 1 : 2;
    }
    ss_vec3 off = ss_vec3_make(a->grid_offset[0], a->grid_offset[1], a->grid_offset[2]);
    m->med.grid->lo = ss_vec3_add(m->med.grid->lo, off);
    m->med.grid->hi = ss_vec3_add(m->med.grid->hi, off);
    if (!(m->med.grid->max_density > 0.0)) {
      fprintf(stderr, "subsurf " CMD ": --grid: %s: every density is 0 (nothing scatters)\n",
              a->grid_path);
      ss_cli_fem_medium_release(m);
      return 2;
    }
  }
  ss_status st = ss_medium_init(&m->med, &err);
  if (st == SS_OK) {
    st = ss_medium_prepare_volume(&m->med, &err);
  }
  if (st == SS_OK) {
    st = ss_fem_scene_medium_init(&m->coeffs, &m->med, 0, a->min_density, &err);
  }
  if (st != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    ss_cli_fem_medium_release(m);
    return st == SS_ERR_NO_MEMORY ? 1 : 2;
  }
  return 0;
}

void ss_cli_fem_medium_release(ss_cli_fem_medium *m) {
  ss_fem_scene_medium_release(&m->coeffs);
  ss_medium_release_volume(&m->med);
}

double ss_cli_fem_medium_max_density(const ss_cli_fem_medium *m) {
  return m->med.grid ? m->med.grid->max_density : 1.0;
}
