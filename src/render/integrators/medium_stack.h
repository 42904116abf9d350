/* The stack of media a path is inside, for nested and touching media with
 * priorities (Schmidt & Budge 2002, "Simple Nested Dielectrics in Ray
 * Traced Images"; private to src/render/integrators). Every interface
 * material bounds a region (its medium, or a clear interior) of absolute
 * refractive index eta (1 when index matched; vacuum has 1). Where regions
 * overlap, the one of highest priority owns the point: the medium of a
 * segment is the top of the stack. A surface whose crossing leaves the
 * owner unchanged is a false interface (no event); otherwise the interface
 * is between the old and the new owner, with both their indices. */
#ifndef SUBSURF_RENDER_INTEGRATORS_MEDIUM_STACK_H
#define SUBSURF_RENDER_INTEGRATORS_MEDIUM_STACK_H

#include "render/integrators/common.h"

/* The material owning the points of the stack: the highest priority, the
 * latest entered among equals; -1 for an empty stack (vacuum). */
int ss_medium_stack_top(const ss_scene *s, const ss_medium_stack *st);
/* The absolute refractive index of the region of material `mat` (-1: vacuum). */
double ss_region_index(const ss_scene *s, int mat);
/* The medium of the top region, or -1 (vacuum or a clear interior). */
int ss_medium_stack_medium(const ss_scene *s, const ss_medium_stack *st);

typedef enum {
  SS_CROSSING_FALSE,   /* the owner is unchanged: no event */
  SS_CROSSING_MATCHED, /* a new owner of the same index: no event */
  SS_CROSSING_TRUE,    /* a refracting interface between the two owners */
  SS_CROSSING_LOST,    /* leaving a region the path is not in, or more than
                          SS_MEDIUM_STACK_SIZE regions: the path ends */
} ss_crossing;

/* Updates the stack for a ray crossing the surface of interface material
 * `mat`, entering its region when `entering`. For a true interface, *eta
 * receives n_inside / n_outside across the surface (inside: the side its
 * normal points away from), else 1. */
ss_crossing ss_medium_stack_cross(const ss_scene *s, ss_medium_stack *st, int mat, int entering,
                                  double *eta);

/* The BSDF of material m's surface as an interface of relative index eta:
 * the material's own (ss_material_bsdf_at) when eta is its eta, else
 * rebuilt in *scratch with eta (a rough boundary then without energy
 * compensation, whose tables hold for the material's eta only). */
const ss_bsdf *ss_interface_bsdf(const ss_material *m, ss_texcoord tc, double eta,
                                 ss_bsdf *scratch);

/* The shadow ray from p (geometric normal n, zero off surfaces) toward a
 * light sample, starting inside the regions of *st: false and
 * index-matching interfaces are crossed, switching to the new owner's
 * medium; refracting ones and other surfaces block. The media crossed
 * attenuate (Beer-Lambert; their coefficients are constant,
 * media_nesting.h). Returns the transmittance; *st holds the regions
 * where the ray stopped (at the sample when it is not black). */
ss_rgb ss_medium_stack_shadow(const ss_scene *scene, ss_vec3 p, ss_vec3 n, ss_medium_stack *st,
                              const ss_light_sample *ls, ss_path_stats *stats);

#endif
