/* Specular manifolds through one or two smooth refracting interfaces: the
 * refraction points of a path from a vertex x0 inside a smooth dielectric
 * to a target outside it, found by Newton's method on the triangle meshes
 * with interpolated (shading) normals, and the derivatives of the first
 * direction with respect to the target (Hanika, Droske & Fascione 2015,
 * "Manifold Next Event Estimation"; Jakob & Marschner 2012, "Manifold
 * Exploration", sec. 4).
 *
 * The constraint at a refraction vertex x_i is v_i = w_o - w_t = 0, w_o the
 * direction toward the next vertex (or the target) and w_t the direction
 * from the previous vertex (x0 for the first) refracted at the shading
 * normal n(x_i) (Zeltner, Georgiev & Jakob 2020, "Specular
 * Manifold Sampling", sec. 5.2: unlike the half-vector constraint of Hanika
 * et al., it has no spurious solutions with the target below the surface).
 * Each vertex is parameterised by its triangle's barycentrics (b1, b2) and v_i
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

/* A chain of k refraction vertices x_1 .. x_k (k <= SS_MANIFOLD_MAX_CHAIN)
 * from the fixed vertex x0 to the target, on one shape each (two vertices
 * may lie on one mesh). At x_i the path passes from a side of index n_(i-1)
 * to one of index n_i: eta[i] = n_(i-1) / n_i. A vertex where the path
 * enters its shape (against the mesh's outward normal) has its normals
 * negated (`enters`), so that at every vertex they point to the side the
 * path leaves toward. Hanika et al. 2015, sec. 4; Jakob & Marschner 2012,
 * sec. 4: the constraints of all vertices are solved together. */
#define SS_MANIFOLD_MAX_CHAIN 2
typedef struct {
  int k;
  ss_manifold_vertex x[SS_MANIFOLD_MAX_CHAIN];
  double eta[SS_MANIFOLD_MAX_CHAIN];
  int enters[SS_MANIFOLD_MAX_CHAIN];
  /* Projection rays pass surfaces of other shapes (nested media, where
   * they may be false interfaces: the caller checks each segment after the
   * solve); otherwise the projection ray's first hit must be the vertex's
   * shape. */
  int pass_others;
} ss_manifold_chain;

/* Sets vertex i of the chain (its normals turned as c->enters[i] says);
 * 0 as ss_manifold_vertex_at. */
int ss_manifold_chain_vertex(const ss_scene *scene, ss_manifold_chain *c, int i, unsigned geom,
                             unsigned prim, double b1, double b2);

/* Newton's method from the seed vertices in c (the straight line's
 * crossings): each step solves the linearised constraint of all vertices
 * (a 2k x 2k system, block tridiagonal: v_i depends on x_(i-1), x_i and
 * x_(i+1)), moves every vertex in the plane of its triangle by its part of
 * the solution scaled by beta (halved when the step fails or |v| grows,
 * doubled up to 1 after a success) and projects it back onto its shape by a
 * ray from its (already projected) predecessor (Hanika et al. 2015, sec.
 * 4.2). Stops when |v| < tolerance with every vertex a refraction (returns
 * 1, c holds the solution) or after max_iterations steps (returns 0). *rays
 * counts the projection rays. */
int ss_manifold_chain_solve(const ss_scene *scene, ss_vec3 x0, ss_manifold_chain *c,
                            const ss_manifold_target *y, int max_iterations, double tolerance,
                            uint64_t *rays);

/* The generalised geometry term's Jacobian (Jakob & Marschner 2012, eq. 10
 * for the chain x0 - x_1 .. x_k - y, by the implicit function theorem on
 * the stacked constraint): |det d omega_0 / d y| where omega_0 is the unit
 * direction from x0 to x_1 and y moves along the orthonormal pair (t1, t2):
 * for a point target, d omega_0 / dA over the plane spanned by t1, t2; for
 * a target at infinity, t1, t2 perpendicular to w are rotations of w and
 * the result is d omega_0 / d omega_o. Returns 0 when the constraint's
 * derivative is singular (a caustic) or a vertex is totally reflecting. */
double ss_manifold_chain_jacobian(ss_vec3 x0, const ss_manifold_chain *c,
                                  const ss_manifold_target *y, ss_vec3 t1, ss_vec3 t2);

#endif
