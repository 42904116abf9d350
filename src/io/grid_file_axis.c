/* A voxel's axis from a grid file (grid_file_axis.h). */
#include "io/grid_file_axis.h"

#include <math.h>

ss_status ss_grid_set_file_axis(ss_grid *g, int64_t v, ss_vec3 a, const char *name, ss_error *err) {
  double l = ss_vec3_length(a);
  if (!isfinite(l) || (l == 0.0 && g->density[v] > 0.0)) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "%s: voxel %lld: the axis (%g, %g, %g) must be "
                        "finite and non-zero where the density is positive",
                        name, (long long)v, a.x, a.y, a.z);
  }
  ss_grid_set_axis(g, v, l > 0.0 ? a : ss_vec3_make(0.0, 0.0, 1.0));
  return SS_OK;
}
