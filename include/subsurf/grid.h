/* Heterogeneous oriented volumes (Jakob2010 sec. 7): a regular grid of
 * voxels over an axis-aligned box, each with a
 * density (scaling the medium's sigma_s and sigma_a) and optionally the axis
 * of its micro-flakes (a fibre's tangent, a layer's normal). Voxel (i, j, k)
 * covers [lo + (i, j, k) h, lo + (i + 1, j + 1, k + 1) h], h = (hi - lo) / n,
 * and its value sits at the voxel's centre; the density between centres is
 * trilinear (constant beyond the outer centres, zero outside the box), the
 * axis that of the nearest voxel (axes have no sign, so they are not
 * interpolated).
 *
 * Axes are stored as two 16-bit octahedral coordinates (Cigolle et al. 2014,
 * "A Survey of Efficient Representations for Independent Unit Vectors"):
 * 4 bytes per voxel beside the 4-byte float density, an angular error below
 * 1e-4 rad. */
#ifndef SUBSURF_GRID_H
#define SUBSURF_GRID_H

#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <stddef.h>
#include <stdint.h>

/* At most this many voxels (2^31: the index arithmetic stays in int64 and a
 * grid's arrays fit in memory of a large machine). */
#define SS_GRID_MAX_VOXELS ((int64_t)1 << 31)

typedef struct ss_grid {
  int n[3];
  ss_vec3 lo, hi;
  float *density;     /* n[0] n[1] n[2] values, x fastest */
  uint16_t *axis;     /* 2 per voxel (octahedral), or NULL: the medium's axis */
  double max_density; /* the largest voxel density (the majorant's scale) */
} ss_grid;

/* Allocates a grid of n[0] x n[1] x n[2] voxels over [lo, hi] with zero
 * densities, and axes when with_axis is set (all along +z). Checks the
 * dimensions (each >= 1, product <= SS_GRID_MAX_VOXELS) and the box (finite,
 * lo < hi in each coordinate). */
ss_status ss_grid_create(const int n[3], ss_vec3 lo, ss_vec3 hi, int with_axis, ss_grid **out,
                         ss_error *err);
void ss_grid_destroy(ss_grid *g);

static inline int64_t ss_grid_voxels(const ss_grid *g) {
  return (int64_t)g->n[0] * g->n[1] * g->n[2];
}
static inline int64_t ss_grid_index(const ss_grid *g, int i, int j, int k) {
  return ((int64_t)k * g->n[1] + j) * g->n[0] + i;
}

/* Bytes of voxel data per voxel (4 for densities, 8 with axes). */
size_t ss_grid_bytes_per_voxel(const ss_grid *g);

/* Sets voxel v's axis (any non-zero length; stored normalised). */
void ss_grid_set_axis(ss_grid *g, int64_t v, ss_vec3 axis);
/* The unit axis of voxel v (+z when the grid has none). */
ss_vec3 ss_grid_axis_of(const ss_grid *g, int64_t v);

/* Checks every density (finite, >= 0) and computes max_density; the
 * message names the first bad voxel. Call after filling the grid. */
ss_status ss_grid_finish(ss_grid *g, ss_error *err);

/* The trilinear density at world point p (0 outside the box). */
double ss_grid_density(const ss_grid *g, ss_vec3 p);
/* The axis of the voxel containing p (p inside the box). */
ss_vec3 ss_grid_axis(const ss_grid *g, ss_vec3 p);

/* The part [*t0, *t1] of the ray o + t d (t in [tmin, tmax]) inside the box;
 * returns 0 when the ray misses it. */
int ss_grid_clip(const ss_grid *g, ss_vec3 o, ss_vec3 d, double tmin, double tmax, double *t0,
                 double *t1);

/* Procedural grids (grid_procedural.c), in a box of the given size centred
 * at the origin, at `res` voxels along the longest side. */
typedef struct {
  int res;            /* voxels along the longest side */
  double radius;      /* yarn: the yarn's radius (mm); its length is 4 radius along x */
  int plies;          /* yarn: number of plies twisted about x */
  double twist;       /* yarn: turns of the plies per unit length */
  double fiber_twist; /* yarn: turns of the fibres about their ply per unit length */
} ss_yarn_params;

/* A twisted-ply yarn along x: `plies` plies of radius 0.45 radius wound
 * about the yarn's axis, each a bundle of fibres wound about the ply's
 * centre line; density 1 inside a ply with a soft edge, the axis the local
 * fibre tangent. */
ss_status ss_grid_yarn(const ss_yarn_params *p, ss_grid **out, ss_error *err);

typedef struct {
  int res;         /* voxels along the longest side */
  ss_vec3 size;    /* the block's extent */
  double ring;     /* spacing of the growth rings */
  double latewood; /* density of the latewood band (earlywood: 1) */
  double wobble;   /* amplitude of the rings' distortion, in ring widths */
} ss_wood_params;

/* A block of wood: fibres along x (the tree's axis), growth rings about an
 * axis outside the block, distorted by smooth noise; dense latewood bands at
 * the rings' ends, the axis the grain direction bent by the distortion. */
ss_status ss_grid_wood(const ss_wood_params *p, ss_grid **out, ss_error *err);

#endif
