/* The octree of pass 2 of the hierarchical BSSRDF evaluation
 * (JensenBuhler2002 sec. 3): the irradiance points of one object in an
 * octree whose every node stores the total power sum E_j A_j of its points,
 * their irradiance-weighted centroid (and mean normal) and their total
 * area. The diffusion term at a point x is
 *     M(x) = sum_j K(x_j, n_j; x) E_j A_j,
 * evaluated by descending the tree until a node's solid angle seen from x,
 * A_node / |x - centroid|^2, is below epsilon (and x is outside the node's
 * bounds): such a node enters as one point at its centroid carrying its
 * power; leaves enter point by point.
 *
 * Building reorders the points so that every node covers a contiguous range
 * [begin, end) of them, children in octant order; node aggregates are summed
 * over that range in order, so that they equal the sum over their points
 * exactly, and a descent that never aggregates adds the points in the order
 * of the array: it equals ss_irradiance_direct_sum bit for bit. */
#ifndef SUBSURF_IRRADIANCE_OCTREE_H
#define SUBSURF_IRRADIANCE_OCTREE_H

#include "subsurf/irradiance_points.h"

#define SS_OCTREE_LEAF_POINTS 8
#define SS_OCTREE_MAX_DEPTH 32

typedef struct {
  ss_vec3 lo, hi;   /* bounds of its points */
  ss_vec3 centroid; /* sum w_j x_j / sum w_j, w_j the luminance of E_j A_j (area when all 0) */
  ss_vec3 normal;   /* the same average of the normals, normalised */
  ss_rgb power;     /* sum E_j A_j */
  double area;      /* sum A_j */
  uint32_t begin, end;
  int32_t child[8]; /* -1: none; all -1 for a leaf */
} ss_octree_node;

typedef struct {
  ss_octree_node *nodes; /* nodes[0] is the root */
  size_t num_nodes;
  const ss_irradiance_point *points; /* borrowed: the array built on */
  size_t num_points;
} ss_irradiance_octree;

/* The kernel K per channel for a point (or aggregate) at x_i with normal n_i. */
typedef void (*ss_octree_kernel_fn)(const void *ctx, ss_vec3 x_i, ss_vec3 n_i, double k[3]);

/* Builds the tree over points[0, n) (n >= 1), reordering them in place. */
ss_status ss_irradiance_octree_build(ss_irradiance_point *points, size_t n,
                                     ss_irradiance_octree *out, ss_error *err);
void ss_irradiance_octree_destroy(ss_irradiance_octree *t);

/* M(x) by the descent above (epsilon > 0); *evals (may be NULL) counts the
 * kernel evaluations. */
ss_rgb ss_irradiance_octree_sum(const ss_irradiance_octree *t, ss_vec3 x, double epsilon,
                                ss_octree_kernel_fn kernel, const void *ctx, uint64_t *evals);

/* The near field of a lookup: the points within sqrt(r2) of x, which the
 * descent below never aggregates and sums apart, so that the caller can
 * correct their quadrature (hierarchical.c). */
typedef struct {
  double r2;        /* in: the squared radius */
  ss_vec3 n;        /* in: the normal at x */
  ss_rgb sum;       /* out: sum K_j E_j A_j over the near points */
  double weight[3]; /* out: sum K_j A_j, the kernel mass the points stand for */
  size_t count;     /* out: the near points */
  int flat;         /* out: 1 when every near point lies on x's tangent plane
                       (normal within acos SS_OCTREE_NEAR_COS of n, off the
                       plane by at most SS_OCTREE_NEAR_OFFSET of the radius) */
} ss_octree_near;

#define SS_OCTREE_NEAR_COS 0.985
#define SS_OCTREE_NEAR_OFFSET 0.1

/* The descent of ss_irradiance_octree_sum with the near field apart: returns
 * the sum over the points and nodes outside it (a node that reaches into it
 * is opened whatever its solid angle) and fills *near's outputs. Their
 * sum equals ss_irradiance_octree_sum up to the nodes opened for the near
 * field (exactly when epsilon -> 0). */
ss_rgb ss_irradiance_octree_sum_near(const ss_irradiance_octree *t, ss_vec3 x, double epsilon,
                                     ss_octree_kernel_fn kernel, const void *ctx,
                                     ss_octree_near *near, uint64_t *evals);

/* M(x) summed over every point in array order (the reference of the descent). */
ss_rgb ss_irradiance_direct_sum(const ss_irradiance_point *points, size_t n, ss_vec3 x,
                                ss_octree_kernel_fn kernel, const void *ctx);

/* Bytes held by the tree's nodes. */
size_t ss_irradiance_octree_bytes(const ss_irradiance_octree *t);

#endif
