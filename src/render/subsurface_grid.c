/* The BSSRDF of a gridded medium at an exit point (subsurface.h). */
#include "subsurf/grid.h"
#include "subsurf/subsurface.h"
#include "subsurf/volume.h"

#include <math.h>

int ss_subsurface_grid_params(const ss_medium *med, ss_vec3 x_o, ss_vec3 n, ss_bssrdf_params *p) {
  const ss_grid *g = med->grid;
  ss_vec3 d = ss_vec3_neg(n);
  double t0, t1;
  if (!g || !(g->max_density > 0.0) || !ss_grid_clip(g, x_o, d, 0.0, INFINITY, &t0, &t1)) {
    return 0;
  }
  ss_vec3 size = ss_vec3_sub(g->hi, g->lo);
  double h = 0.5 * fmin(size.x / g->n[0], fmin(size.y / g->n[1], size.z / g->n[2]));
  double threshold = SS_GRID_EXIT_DENSITY * g->max_density;
  long steps = (long)ceil((t1 - t0) / h);
  for (long k = 0; k <= steps; ++k) {
    ss_volume_point q = ss_volume_at(med, ss_vec3_madd(x_o, d, fmin(t0 + k * h, t1)));
    if (q.density >= threshold) {
      p->medium.sigma_s = ss_rgb_scale(p->medium.sigma_s, q.density);
      p->medium.sigma_a = ss_rgb_scale(p->medium.sigma_a, q.density);
      p->medium.flakes.axis = q.axis.n;
      return 1;
    }
  }
  return 0;
}
