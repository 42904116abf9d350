/* The state of the `hierarchical` integrator (Jensen & Buhler 2002): the
 * irradiance points of pass 1 and one octree per translucent shape, built by
 * ss_hierarchical_build (hierarchical_build.c) and read by pass 2
 * (hierarchical.c). Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_HIERARCHICAL_H
#define SUBSURF_RENDER_INTEGRATORS_HIERARCHICAL_H

#include "subsurf/bssrdf.h"
#include "subsurf/irradiance_octree.h"

/* Option defaults. The solid-angle threshold: pbrt-v2's
 * DipoleSubsurfaceIntegrator uses 0.05 for the same criterion. */
#define SS_HIER_DEFAULT_EPSILON 0.05
#define SS_HIER_DEFAULT_IRRADIANCE_SAMPLES 64
/* The automatic density: one point per l^2 of area, l = 1 / max_c sigma_t'
 * the shortest transport mean free path of the material, at most this many
 * points in all (the `points` option sets any count up to SS_HIER_MAX_POINTS). */
#define SS_HIER_AUTO_MAX_POINTS 2000000
#define SS_HIER_MAX_POINTS 20000000

typedef struct {
  size_t points;          /* total requested; 0: automatic */
  double epsilon;         /* solid-angle threshold */
  int irradiance_samples; /* per point */
  uint64_t seed;
} ss_hier_options;

typedef struct {
  ss_hier_options opt;
  ss_irradiance_point *points; /* grouped by shape, each group in its octree's order */
  size_t num_points;
  size_t num_shapes;
  ss_irradiance_octree *trees; /* per shape; num_nodes 0 for a shape without one */
  const ss_bssrdf **kernel;    /* per shape: the material's model, or NULL */
  double *eta;                 /* per shape: the kernel's boundary eta */
  ss_path_stats pass1;         /* rays of the irradiance pass */
  int from_cache;              /* the points were read from the cache file */
  double pass1_seconds, octree_seconds;
} ss_hier_state;

/* Reads and checks the options (names in the message). */
ss_status ss_hier_options_read(const ss_scene *scene, ss_hier_options *o, ss_error *err);
/* 1 when a model can be the kernel: radially symmetric and with a pointwise
 * value (not a BRDF or a singular model). */
int ss_hier_kernel_ok(const ss_bssrdf *b);
/* Pass 1 and the octrees, on `threads` threads (0: OpenMP's default). With
 * a `cache` path (NULL or "": none) the points are read from it when it is
 * valid for this scene and options, else computed and written to it. */
ss_status ss_hier_build(const ss_scene *scene, const ss_hier_options *o, int threads,
                        const char *cache, ss_hier_state **out, ss_error *err);
void ss_hier_destroy(ss_hier_state *s);

/* The kernel at exit point x_o (normal n_o, toward w_o) for a point (x_i,
 * n_i): S(x_i, n_i, w_i = n_i; x_o, n_o, w_o) / Ft(1), the model's value
 * for light entering along the normal per unit of Fresnel-transmitted
 * irradiance; exact for models whose S depends on w_i only through Ft. */
typedef struct {
  const ss_bssrdf *b;
  ss_vec3 x_o, n_o, w_o;
  double inv_ft_normal;
} ss_hier_kernel_ctx;

void ss_hier_kernel(const void *ctx, ss_vec3 x_i, ss_vec3 n_i, double k[3]);

#endif
