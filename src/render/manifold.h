/* One-interface specular manifolds: the refraction point of a path from a
 * vertex x0 inside a smooth dielectric to a target outside it, found by
 * Newton's method on the triangle mesh with interpolated (shading) normals,
 * and the derivatives of that point with respect to the target (Hanika,
 * Droske & Fascione 2015, "Manifold Next Event Estimation"; Jakob &
 * Marschner 2012, "Manifold Exploration", sec. 4).
 *
 * The constraint at the refraction vertex x1 is v = w_o - w_t = 0, w_o the
 * direction toward the target and w_t the direction x1 -> x0 refracted at
 * the shading normal n(x1) (Zeltner, Georgiev & Jakob 2020, "Specular
 * Manifold Sampling", sec. 5.2: unlike the half-vector constraint of Hanika
 * et al., it has no spurious solutions with the target below the surface).
 * The vertex is parameterised by its triangle's barycentrics (b1, b2) and v
 * is measured in a frame normal to w_t (the frame's own derivative drops
 * out at a solution, where v = 0). */
#ifndef SUBSURF_RENDER_MANIFOLD_H
#define SUBSURF_RENDER_MANIFOLD_H

#include "subsurf/scene.h"

/* A point of a mesh with the derivatives the constraint needs. */
typedef struct {
  unsigned geom_id, prim_id;
  double b1, b2;        /* barycentrics: p = (1 - b1 - b2) p0 + b1 p1 + b2 p2 */
  ss_vec3 p, ng, n;     /* position, unit geometric and shading normals */
  ss_vec3 dp[2], dn[2]; /* d p / d b_k and d n / d b_k */
} ss_manifold_vertex;

/* Fills v at barycentrics (b1, b2) of triangle prim of shape geom. Returns 0
 * for a degenerate triangle or a shading normal that is zero or faces away
 * from the geometric one. */
int ss_manifold_vertex_at(const ss_scene *scene, unsigned geom, unsigned prim, double b1, double b2,
                          ss_manifold_vertex *v);

/* The far end of the chain: a point, or (at_infinity) the direction w
 * toward a light at infinity. */
typedef struct {
  ss_vec3 p, w;
  int at_infinity;
} ss_manifold_target;

/* The direction from x1 toward the target. */
ss_vec3 ss_manifold_target_dir(const ss_manifold_target *y, ss_vec3 x1, double *dist);

/* |v| = |w_o - w_t| at x1 (the convergence measure); -1 when x0 is not
 * behind the shading normal or its direction is totally reflected. */
double ss_manifold_constraint(ss_vec3 x0, const ss_manifold_vertex *x1, const ss_manifold_target *y,
                              double eta);

/* Newton's method from the seed hit (on the interface, reached from x0):
 * each step moves x1 in the plane of its triangle by the solution of the
 * linearised constraint, scaled by beta (halved when the step fails or the
 * constraint grows, doubled up to 1 after a success), and projects it back
 * onto the mesh by a ray from x0 (Hanika et al. 2015, sec. 4.2), which must
 * hit the same shape from the inside. Stops when |v| < tolerance (returns
 * 1 and the vertex) or after max_iterations steps (returns 0). *rays
 * counts the projection rays. */
int ss_manifold_solve(const ss_scene *scene, ss_vec3 x0, const ss_hit *seed,
                      const ss_manifold_target *y, double eta, int max_iterations, double tolerance,
                      ss_manifold_vertex *x1, uint64_t *rays);

/* The generalised geometry term's Jacobian (Jakob & Marschner 2012, eq. 10
 * applied to the chain x0 - x1 - y): |det d omega_0 / d y| where omega_0 is
 * the unit direction from x0 to x1 and y moves along the orthonormal pair
 * (t1, t2): for a point target, d omega_0 / dA over the plane spanned by
 * t1, t2; for a target at infinity, t1, t2 perpendicular to w are
 * rotations of w and the result is d omega_0 / d omega_o. Returns 0 when the
 * constraint's derivative is singular (a caustic). */
double ss_manifold_jacobian(ss_vec3 x0, const ss_manifold_vertex *x1, const ss_manifold_target *y,
                            double eta, ss_vec3 t1, ss_vec3 t2);

#endif
