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
/* The largest near field, in point spacings sqrt(A_j). */
#define SS_HIER_MAX_NEAR_FIELD 16

typedef struct {
  size_t points;          /* total requested; 0: automatic */
  double epsilon;         /* solid-angle threshold */
  int irradiance_samples; /* per point */
  int kernel_table;       /* 1: the tabulated kernel where it checks out; 0: the model's */
  double near_field;      /* radius of the normalised near field in point spacings; 0: none */
  uint64_t seed;
} ss_hier_options;

typedef struct ss_hier_state ss_hier_state;

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

/* The same kernel tabulated (hierarchical_table.c): K(r, w_o) = A(w_o)
 * T(r), T per channel on SS_HIER_TABLE_PER_OCTAVE nodes per octave of r^2
 * from r_min = 1e-3 mean free paths to where T < SS_HIER_TABLE_FLOOR of its
 * largest value, A from one evaluation of the model at r_ref per lookup. */
#define SS_HIER_TABLE_PER_OCTAVE 64
#define SS_HIER_TABLE_FLOOR 1e-9
/* The largest difference ss_hier_table_check may report for the table to
 * be used (else the model is evaluated at every point). */
#define SS_HIER_TABLE_TOLERANCE 5e-3

typedef struct {
  float (*value)[3]; /* T at the nodes */
  int n;
  double inv_s_min; /* 1 / r_min^2 */
  double r_ref;     /* where A is measured: one mean free path */
  double ref[3];    /* T(r_ref) */
} ss_hier_table;

typedef struct {
  const ss_hier_table *table;
  ss_vec3 x_o;
  double a[3]; /* A(w_o) */
} ss_hier_table_ctx;

ss_status ss_hier_table_build(const ss_bssrdf *b, double eta, ss_hier_table *t, ss_error *err);
void ss_hier_table_destroy(ss_hier_table *t);
/* T at squared distance r2. */
void ss_hier_table_lookup(const ss_hier_table *t, double r2, double k[3]);
/* A(w_o) for the exit point and direction of `analytic`. */
void ss_hier_table_angular(const ss_hier_table *t, const ss_hier_kernel_ctx *analytic, double a[3]);
/* The integral of T over a disk of radius r on a plane:
 * 2 pi int_0^r T(r') r' dr' = pi int_0^{r^2} T(s) ds, exact for the table's
 * interpolant. */
void ss_hier_table_disk(const ss_hier_table *t, double r, double out[3]);
/* The kernel callback (ctx: ss_hier_table_ctx). */
void ss_hier_kernel_tabulated(const void *ctx, ss_vec3 x_i, ss_vec3 n_i, double k[3]);
/* The largest difference between the table and the model over sample
 * geometries, relative to the model's value (or, where that is below 1e-6
 * of the channel's largest, to 1e-6 of the largest). */
double ss_hier_table_check(const ss_hier_table *t, const ss_bssrdf *b, double eta);

/* The octree's sum at tk->x_o (normal n_o) with the near field, the points
 * within r of x_o, normalised: there the point sum sum_j K_j E_j A_j is a
 * quadrature of int K E dA whose weights A_j K(r_j) miss the kernel's peak
 * (points sqrt(A_j) apart against a peak about z_r wide), so where the
 * near points lie on x_o's tangent plane (ss_octree_near's flat) it is
 * replaced by the kernel-weighted mean irradiance times the kernel's exact
 * mass on the disk,
 *     (sum_j K_j E_j A_j / sum_j K_j A_j) A(w_o) int_{|x| < r} T dA,
 * (disk = ss_hier_table_disk(r)), exact for a constant E; elsewhere (edges,
 * corners) the plain sum stays. Not in Jensen & Buhler 2002: the option
 * near_field. */
ss_rgb ss_hier_sum_near(const ss_irradiance_octree *t, ss_vec3 n_o, double epsilon, double r,
                        const double disk[3], const ss_hier_table_ctx *tk, uint64_t *evals);

struct ss_hier_state {
  ss_hier_options opt;
  ss_irradiance_point *points; /* grouped by shape, each group in its octree's order */
  size_t num_points;
  size_t num_shapes;
  ss_irradiance_octree *trees; /* per shape; num_nodes 0 for a shape without one */
  const ss_bssrdf **kernel;    /* per shape: the material's model, or NULL */
  double *eta;                 /* per shape: the kernel's boundary eta */
  ss_hier_table *table;        /* per shape: the tabulated kernel; n 0: none (the model's) */
  double *near_radius;         /* per shape: the near field's radius; 0: none */
  double (*near_disk)[3];      /* per shape: T's integral over that disk (ss_hier_table_disk) */
  ss_path_stats pass1;         /* rays of the irradiance pass */
  int from_cache;              /* the points were read from the cache file */
  double pass1_seconds, octree_seconds;
};

#endif
