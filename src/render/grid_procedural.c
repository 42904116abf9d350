/* Procedural oriented volumes (grid.h): a twisted-ply yarn and a block of
 * wood, the kinds of material Jakob2010 (sec. 7) renders
 * with fibre-like micro-flakes. */
#include "subsurf/grid.h"
#include "subsurf/sampling.h"
#include "subsurf/texture.h"

#include <math.h>

/* A soft edge: 1 well inside (d >= w), 0 outside (d <= 0). */
static double soft(double d, double w) {
  double x = fmin(1.0, fmax(0.0, d / w));
  return x * x * (3.0 - 2.0 * x);
}

/* Voxel counts for a box of extent `size` with `res` voxels on its longest
 * side (at least one per side), and the box itself centred at the origin
 * (cubic voxels, so that the grid also fits OpenVDB's uniform transform). */
static ss_status make_box(int res, ss_vec3 size, int with_axis, ss_grid **out, ss_error *err) {
  if (res < 1 || res > 4096) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "resolution must lie in [1, 4096], got %d",
                        res);
  }
  double h = ss_vec3_max_component(size) / res;
  int n[3];
  for (int a = 0; a < 3; ++a) {
    n[a] = (int)fmax(1.0, ceil(ss_vec3_component(size, a) / h - 1e-9));
  }
  ss_vec3 half = ss_vec3_scale(ss_vec3_make(n[0], n[1], n[2]), 0.5 * h);
  return ss_grid_create(n, ss_vec3_neg(half), half, with_axis, out, err);
}

static ss_vec3 voxel_centre(const ss_grid *g, int i, int j, int k) {
  ss_vec3 h = ss_vec3_sub(g->hi, g->lo);
  return ss_vec3_make(g->lo.x + (i + 0.5) * h.x / g->n[0], g->lo.y + (j + 0.5) * h.y / g->n[1],
                      g->lo.z + (k + 0.5) * h.z / g->n[2]);
}

ss_status ss_grid_yarn(const ss_yarn_params *p, ss_grid **out, ss_error *err) {
  *out = NULL;
  if (!(p->radius > 0.0 && isfinite(p->radius)) || p->plies < 1 || p->plies > 16 ||
      !isfinite(p->twist) || !isfinite(p->fiber_twist)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "yarn: radius must be > 0, plies in [1, 16], twists finite");
  }
  double R = p->radius, rp = p->plies == 1 ? R : 0.45 * R, rc = R - rp;
  ss_grid *g;
  ss_status st = make_box(p->res, ss_vec3_make(4.0 * R, 2.0 * R, 2.0 * R), 1, &g, err);
  if (st != SS_OK) {
    return st;
  }
  double wt = 2.0 * SS_PI * p->twist, wf = 2.0 * SS_PI * p->fiber_twist;
  for (int k = 0; k < g->n[2]; ++k) {
    for (int j = 0; j < g->n[1]; ++j) {
      for (int i = 0; i < g->n[0]; ++i) {
        ss_vec3 x = voxel_centre(g, i, j, k);
        int64_t v = ss_grid_index(g, i, j, k);
        for (int ply = 0; ply < p->plies; ++ply) {
          /* The ply's centre line: a helix of radius rc about x. */
          double th = 2.0 * SS_PI * ply / p->plies + wt * x.x;
          double qy = x.y - rc * cos(th), qz = x.z - rc * sin(th);
          double r = sqrt(qy * qy + qz * qz);
          double d = soft(rp - r, 0.15 * rp);
          if (d > g->density[v]) {
            g->density[v] = (float)d;
            /* The fibre's tangent: the ply's (d/dx of the helix) plus the
             * fibres' own winding about the ply's centre, the other way. */
            ss_vec3 tangent = ss_vec3_make(1.0, -rc * wt * sin(th), rc * wt * cos(th));
            ss_vec3 wind = ss_vec3_make(0.0, qz * wf, -qy * wf);
            ss_grid_set_axis(g, v, ss_vec3_add(tangent, wind));
          }
        }
      }
    }
  }
  if ((st = ss_grid_finish(g, err)) != SS_OK) {
    ss_grid_destroy(g);
    return st;
  }
  *out = g;
  return SS_OK;
}

ss_status ss_grid_wood(const ss_wood_params *p, ss_grid **out, ss_error *err) {
  *out = NULL;
  for (int a = 0; a < 3; ++a) {
    if (!(ss_vec3_component(p->size, a) > 0.0 && isfinite(ss_vec3_component(p->size, a)))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "wood: size must be > 0");
    }
  }
  if (!(p->ring > 0.0 && isfinite(p->ring)) || !(p->latewood >= 0.0 && isfinite(p->latewood)) ||
      !(p->wobble >= 0.0 && isfinite(p->wobble))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "wood: ring must be > 0, latewood and wobble >= 0");
  }
  ss_grid *g;
  ss_status st = make_box(p->res, p->size, 1, &g, err);
  if (st != SS_OK) {
    return st;
  }
  /* The tree's axis runs along x, off the block's corner. */
  double py = -1.3 * p->size.y, pz = -0.7 * p->size.z, f = 1.0 / (4.0 * p->ring);
  for (int k = 0; k < g->n[2]; ++k) {
    for (int j = 0; j < g->n[1]; ++j) {
      for (int i = 0; i < g->n[0]; ++i) {
        ss_vec3 x = voxel_centre(g, i, j, k);
        ss_vec3 s = ss_vec3_make(0.3 * f * x.x, f * x.y, f * x.z);
        double n0 = ss_gradient_noise(s, 1), n1 = ss_gradient_noise(s, 2);
        double n2 = ss_gradient_noise(s, 3);
        double r = hypot(x.y - py, x.z - pz) + p->wobble * p->ring * n0;
        double phase = r / p->ring - floor(r / p->ring);
        /* Latewood: the last quarter of each ring, with soft edges. */
        double late = soft(phase - 0.7, 0.05) * soft(1.0 - phase, 0.05);
        int64_t v = ss_grid_index(g, i, j, k);
        g->density[v] = (float)(1.0 + (p->latewood - 1.0) * late);
        ss_grid_set_axis(g, v, ss_vec3_make(1.0, 0.25 * n1, 0.25 * n2));
      }
    }
  }
  if ((st = ss_grid_finish(g, err)) != SS_OK) {
    ss_grid_destroy(g);
    return st;
  }
  *out = g;
  return SS_OK;
}
