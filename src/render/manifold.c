/* One-interface specular manifolds (manifold.h): Newton's method for the
 * refraction point and the Jacobian of the generalised geometry term. */
#include "render/manifold.h"

#include <math.h>

int ss_manifold_vertex_at(const ss_scene *scene, unsigned geom, unsigned prim, double b1, double b2,
                          ss_manifold_vertex *v) {
  const ss_mesh *m = scene->shapes[geom].mesh;
  const uint32_t *idx = m->indices + 3 * (size_t)prim;
  ss_vec3 q[3];
  ss_mesh_triangle(m, prim, q);
  v->geom_id = geom;
  v->prim_id = prim;
  v->b1 = b1;
  v->b2 = b2;
  v->dp[0] = ss_vec3_sub(q[1], q[0]);
  v->dp[1] = ss_vec3_sub(q[2], q[0]);
  v->p = ss_vec3_madd(ss_vec3_madd(q[0], v->dp[0], b1), v->dp[1], b2);
  ss_vec3 ng = ss_vec3_cross(v->dp[0], v->dp[1]);
  double len = ss_vec3_length(ng);
  if (!(len > 0.0)) {
    return 0;
  }
  v->ng = ss_vec3_scale(ng, 1.0 / len);
  v->n = v->ng;
  v->dn[0] = v->dn[1] = ss_vec3_make(0.0, 0.0, 0.0);
  if (!m->normals) {
    return 1;
  }
  ss_vec3 nk[3];
  for (int k = 0; k < 3; ++k) {
    const float *f = m->normals + 3 * (size_t)idx[k];
    nk[k] = ss_vec3_make(f[0], f[1], f[2]);
  }
  /* n = N / |N|, N = (1 - b1 - b2) n0 + b1 n1 + b2 n2 (Phong interpolation);
   * dn = (dN - n (n.dN)) / |N|. */
  ss_vec3 N = ss_vec3_madd(ss_vec3_madd(ss_vec3_scale(nk[0], 1.0 - b1 - b2), nk[1], b1), nk[2], b2);
  double nl = ss_vec3_length(N);
  if (!(nl > 0.0)) {
    return 0;
  }
  v->n = ss_vec3_scale(N, 1.0 / nl);
  if (!(ss_vec3_dot(v->n, v->ng) > 0.0)) {
    return 0;
  }
  for (int k = 0; k < 2; ++k) {
    ss_vec3 dN = ss_vec3_sub(nk[k + 1], nk[0]);
    v->dn[k] = ss_vec3_scale(ss_vec3_madd(dN, v->n, -ss_vec3_dot(v->n, dN)), 1.0 / nl);
  }
  return 1;
}

ss_vec3 ss_manifold_target_dir(const ss_manifold_target *y, ss_vec3 x1, double *dist) {
  if (y->at_infinity) {
    *dist = INFINITY;
    return y->w;
  }
  ss_vec3 d = ss_vec3_sub(y->p, x1);
  *dist = ss_vec3_length(d);
  return ss_vec3_scale(d, 1.0 / *dist);
}

/* The chain's directions at x1: w_t is w_i refracted at the shading
 * normal, and the constraint is v = w_o - w_t, measured in a frame normal
 * to w_t (Zeltner et al. 2020's direction constraint, sec. 5.2, as a
 * difference of vectors). */
typedef struct {
  ss_vec3 wi, wo, wt, v;
  double d0, d2, cos_i, cos_t;
  int tir;    /* total internal reflection: w_t is continued as the grazing direction */
  double tau; /* then the length of -w_i's tangential part */
  ss_frame f; /* f.n = w_t */
} chain;

/* 0 when x0 is not behind the shading normal. Beyond the critical angle w_t
 * is continued by the grazing direction in the plane of incidence, so that
 * the constraint stays continuous and Newton's method can leave the region
 * of total internal reflection (a seed lies there whenever the straight
 * line to the light meets the surface beyond the critical angle). */
static int chain_at(ss_vec3 x0, const ss_manifold_vertex *x1, const ss_manifold_target *y,
                    double eta, chain *c) {
  ss_vec3 d = ss_vec3_sub(x0, x1->p);
  c->d0 = ss_vec3_length(d);
  c->wo = ss_manifold_target_dir(y, x1->p, &c->d2);
  if (!(c->d0 > 0.0) || !(c->d2 > 0.0)) {
    return 0;
  }
  c->wi = ss_vec3_scale(d, 1.0 / c->d0);
  c->cos_i = -ss_vec3_dot(c->wi, x1->n);
  double cos_t2 = 1.0 - eta * eta * (1.0 - c->cos_i * c->cos_i);
  if (!(c->cos_i > 0.0)) {
    return 0;
  }
  c->tir = !(cos_t2 > 0.0);
  if (c->tir) {
    ss_vec3 tau = ss_vec3_madd(ss_vec3_neg(c->wi), x1->n, -c->cos_i);
    c->tau = ss_vec3_length(tau);
    if (!(c->tau > 0.0)) {
      return 0;
    }
    c->cos_t = 0.0;
    c->wt = ss_vec3_scale(tau, 1.0 / c->tau);
  } else {
    /* Snell's law in vector form: w_t = -eta w_i - (eta cos_i - cos_t) n. */
    c->cos_t = sqrt(cos_t2);
    c->wt = ss_vec3_madd(ss_vec3_scale(c->wi, -eta), x1->n, -(eta * c->cos_i - c->cos_t));
  }
  c->v = ss_vec3_sub(c->wo, c->wt);
  c->f = ss_frame_from_normal(ss_vec3_normalize(c->wt));
  return 1;
}

/* The constraint's change, as (s, t) components, for changes dwi, dwo, dn
 * of w_i, w_o and the shading normal. */
static void dv(const chain *c, const ss_manifold_vertex *x1, double eta, ss_vec3 dwi, ss_vec3 dwo,
               ss_vec3 dn, double out[2]) {
  double dcos_i = -(ss_vec3_dot(dwi, x1->n) + ss_vec3_dot(c->wi, dn));
  ss_vec3 dwt;
  if (c->tir) {
    ss_vec3 dtau = ss_vec3_madd(ss_vec3_madd(ss_vec3_neg(dwi), x1->n, -dcos_i), dn, -c->cos_i);
    dwt = ss_vec3_scale(ss_vec3_madd(dtau, c->wt, -ss_vec3_dot(c->wt, dtau)), 1.0 / c->tau);
  } else {
    double dcos_t = eta * eta * c->cos_i * dcos_i / c->cos_t;
    dwt = ss_vec3_madd(ss_vec3_scale(dwi, -eta), x1->n, -(eta * dcos_i - dcos_t));
    dwt = ss_vec3_madd(dwt, dn, -(eta * c->cos_i - c->cos_t));
  }
  ss_vec3 d = ss_vec3_sub(dwo, dwt);
  out[0] = ss_vec3_dot(d, c->f.s);
  out[1] = ss_vec3_dot(d, c->f.t);
}

/* d w / d x for a unit vector w = (a - x) / |a - x| moved by e at x. */
static ss_vec3 d_unit(ss_vec3 w, double dist, ss_vec3 e) {
  return ss_vec3_scale(ss_vec3_madd(e, w, -ss_vec3_dot(w, e)), -1.0 / dist);
}

/* A[.][k] = d C / d b_k. */
static void constraint_jacobian(const chain *c, const ss_manifold_vertex *x1, double eta,
                                int at_infinity, double A[2][2]) {
  ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
  for (int k = 0; k < 2; ++k) {
    ss_vec3 dwo = at_infinity ? zero : d_unit(c->wo, c->d2, x1->dp[k]);
    double d[2];
    dv(c, x1, eta, d_unit(c->wi, c->d0, x1->dp[k]), dwo, x1->dn[k], d);
    A[0][k] = d[0];
    A[1][k] = d[1];
  }
}

/* x = A^-1 b; 0 when A is singular. */
static int solve2(double A[2][2], const double b[2], double x[2]) {
  double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
  double scale = fabs(A[0][0] * A[1][1]) + fabs(A[0][1] * A[1][0]);
  if (!(fabs(det) > 1e-12 * scale) || !isfinite(det)) {
    return 0;
  }
  x[0] = (A[1][1] * b[0] - A[0][1] * b[1]) / det;
  x[1] = (A[0][0] * b[1] - A[1][0] * b[0]) / det;
  return 1;
}

double ss_manifold_constraint(ss_vec3 x0, const ss_manifold_vertex *x1, const ss_manifold_target *y,
                              double eta) {
  chain c;
  return chain_at(x0, x1, y, eta, &c) ? ss_vec3_length(c.v) : -1.0;
}

/* A refraction (not a grazing limit), x0 inside and the target outside of
 * the geometric surface too. */
static int refracts(const chain *c, const ss_manifold_vertex *x1) {
  return !c->tir && ss_vec3_dot(c->wi, x1->ng) < 0.0 && ss_vec3_dot(c->wo, x1->ng) > 0.0;
}

/* Projects p onto the shape of x1 by a ray from x0 (hitting it from inside). */
static int project(const ss_scene *scene, ss_vec3 x0, ss_vec3 p, unsigned geom,
                   ss_manifold_vertex *out, uint64_t *rays) {
  ss_ray ray = {x0, ss_vec3_sub(p, x0), 0.0, INFINITY};
  ss_hit hit;
  ++*rays;
  if (!ss_accel_intersect(scene->accel, &ray, &hit) || hit.geom_id != geom ||
      !(ss_vec3_dot(ray.d, hit.ng) > 0.0)) {
    return 0;
  }
  /* Barycentrics again in double (Moller & Trumbore 1997): Embree's float
   * ones would stall Newton's method near 1e-7. */
  ss_vec3 q[3];
  ss_mesh_triangle(scene->shapes[geom].mesh, hit.prim_id, q);
  ss_vec3 e1 = ss_vec3_sub(q[1], q[0]), e2 = ss_vec3_sub(q[2], q[0]);
  ss_vec3 pv = ss_vec3_cross(ray.d, e2), tv = ss_vec3_sub(x0, q[0]);
  double det = ss_vec3_dot(e1, pv);
  if (!(fabs(det) > 0.0)) {
    return 0;
  }
  ss_vec3 qv = ss_vec3_cross(tv, e1);
  double b1 = ss_vec3_dot(tv, pv) / det, b2 = ss_vec3_dot(ray.d, qv) / det;
  return ss_manifold_vertex_at(scene, hit.geom_id, hit.prim_id, b1, b2, out);
}

int ss_manifold_solve(const ss_scene *scene, ss_vec3 x0, const ss_hit *seed,
                      const ss_manifold_target *y, double eta, int max_iterations, double tolerance,
                      ss_manifold_vertex *x1, uint64_t *rays) {
  if (!ss_manifold_vertex_at(scene, seed->geom_id, seed->prim_id, seed->b1, seed->b2, x1)) {
    return 0;
  }
  chain c;
  if (!chain_at(x0, x1, y, eta, &c)) {
    return 0;
  }
  double err = ss_vec3_length(c.v), beta = 1.0;
  for (int it = 0;; ++it) {
    if (err < tolerance) {
      return refracts(&c, x1);
    }
    if (it == max_iterations) {
      return 0;
    }
    double A[2][2], C[2] = {ss_vec3_dot(c.v, c.f.s), ss_vec3_dot(c.v, c.f.t)}, db[2];
    constraint_jacobian(&c, x1, eta, y->at_infinity, A);
    if (!solve2(A, C, db)) {
      return 0;
    }
    /* Newton step in the triangle's plane, then back onto the mesh. */
    ss_vec3 p =
        ss_vec3_madd(ss_vec3_madd(x1->p, x1->dp[0], -beta * db[0]), x1->dp[1], -beta * db[1]);
    ss_manifold_vertex next;
    chain cn;
    if (project(scene, x0, p, x1->geom_id, &next, rays) && chain_at(x0, &next, y, eta, &cn) &&
        ss_vec3_length(cn.v) < err) {
      *x1 = next;
      c = cn;
      err = ss_vec3_length(c.v);
      beta = fmin(1.0, 2.0 * beta);
    } else {
      beta *= 0.5;
    }
  }
}

double ss_manifold_jacobian(ss_vec3 x0, const ss_manifold_vertex *x1, const ss_manifold_target *y,
                            double eta, ss_vec3 t1, ss_vec3 t2) {
  chain c;
  if (!chain_at(x0, x1, y, eta, &c) || c.tir) {
    return 0.0;
  }
  double A[2][2];
  constraint_jacobian(&c, x1, eta, y->at_infinity, A);
  /* d b / d y_j = -A^-1 (d C / d y_j) (implicit function theorem), then
   * d omega_0 = (I - omega_0 omega_0^T) dx1 / d0 with omega_0 = -w_i. */
  ss_vec3 t[2] = {t1, t2};
  ss_frame g = ss_frame_from_normal(ss_vec3_neg(c.wi));
  double K[2][2];
  for (int j = 0; j < 2; ++j) {
    ss_vec3 dwo = y->at_infinity ? ss_vec3_madd(t[j], c.wo, -ss_vec3_dot(c.wo, t[j]))
                                 : d_unit(c.wo, c.d2, ss_vec3_neg(t[j]));
    ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
    double B[2], db[2];
    dv(&c, x1, eta, zero, dwo, zero, B);
    if (!solve2(A, B, db)) {
      return 0.0;
    }
    ss_vec3 dx1 =
        ss_vec3_scale(ss_vec3_madd(ss_vec3_scale(x1->dp[0], db[0]), x1->dp[1], db[1]), -1.0);
    ss_vec3 dw = d_unit(ss_vec3_neg(c.wi), c.d0, ss_vec3_neg(dx1));
    K[0][j] = ss_vec3_dot(dw, g.s);
    K[1][j] = ss_vec3_dot(dw, g.t);
  }
  return fabs(K[0][0] * K[1][1] - K[0][1] * K[1][0]);
}
