/* Specular manifolds (manifold.h): Newton's method for the refraction
 * points of a chain and the Jacobian of the generalised geometry term. */
#include "render/manifold.h"

#include "subsurf/sampling.h"

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

/* The directions at one vertex x1 between its predecessor x0 and its
 * successor y: w_t is w_i refracted at the shading normal, and the
 * constraint is v = w_o - w_t, measured in a frame normal to w_t (Zeltner
 * et al. 2020's direction constraint, sec. 5.2, as a difference of
 * vectors). */
typedef struct {
  ss_vec3 wi, wo, wt, v;
  double d0, d2, cos_i, cos_t;
  int tir;    /* total internal reflection: w_t is continued below the surface */
  double tau; /* then sin_i, the length of -w_i's tangential part */
  double sin_t;
  ss_frame f; /* f.n = w_t */
} link;

/* 0 when x0 is not behind the shading normal. Beyond the critical angle
 * (eta sin_i = s > 1) w_t is continued past the grazing direction, in the
 * plane of incidence, to theta_t = pi/2 + (pi/2)(1 - 1/s) from the normal
 * (below the surface, short of -n for any eta), so that the constraint stays
 * continuous and keeps a derivative along the plane of incidence: Newton's
 * method then leaves the region of total internal reflection, where a seed
 * lies whenever the straight line to the light meets the surface beyond the
 * critical angle. (The grazing direction alone, constant along the plane of
 * incidence on a flat face, left the constraint's derivative singular there
 * and the solve without a step.) */
static int link_at(ss_vec3 x0, const ss_manifold_vertex *x1, const ss_manifold_target *y,
                   double eta, link *c) {
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
    double theta_t = 0.5 * SS_PI * (2.0 - 1.0 / (eta * c->tau));
    c->sin_t = sin(theta_t);
    c->cos_t = cos(theta_t);
    c->wt = ss_vec3_madd(ss_vec3_scale(tau, c->sin_t / c->tau), x1->n, c->cos_t);
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
static void dv(const link *c, const ss_manifold_vertex *x1, double eta, ss_vec3 dwi, ss_vec3 dwo,
               ss_vec3 dn, double out[2]) {
  double dcos_i = -(ss_vec3_dot(dwi, x1->n) + ss_vec3_dot(c->wi, dn));
  ss_vec3 dwt;
  if (c->tir) {
    /* w_t = sin_t T + cos_t n, T the unit tangential direction, and
     * d theta_t = (pi/2) d s / s^2 with s = eta tau. */
    ss_vec3 T = ss_vec3_scale(ss_vec3_madd(c->wt, x1->n, -c->cos_t), 1.0 / c->sin_t);
    ss_vec3 dtau_v = ss_vec3_madd(ss_vec3_madd(ss_vec3_neg(dwi), x1->n, -dcos_i), dn, -c->cos_i);
    double dtau = ss_vec3_dot(T, dtau_v), s = eta * c->tau;
    double dtheta = 0.5 * SS_PI * eta * dtau / (s * s);
    ss_vec3 dT = ss_vec3_scale(ss_vec3_madd(dtau_v, T, -dtau), 1.0 / c->tau);
    dwt = ss_vec3_scale(ss_vec3_madd(ss_vec3_scale(T, c->cos_t), x1->n, -c->sin_t), dtheta);
    dwt = ss_vec3_madd(ss_vec3_madd(dwt, dT, c->sin_t), dn, c->cos_t);
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

/* x = A^-1 b for the 2k x 2k system of a chain (n = 2k <= 4): the closed
 * form for one vertex, Gaussian elimination with partial pivoting for two;
 * 0 when A is singular. */
static int solve_n(int n, double A[4][4], const double b[4], double x[4]) {
  if (n == 2) {
    double A2[2][2] = {{A[0][0], A[0][1]}, {A[1][0], A[1][1]}};
    return solve2(A2, b, x);
  }
  double M[4][5], scale = 0.0;
  for (int r = 0; r < n; ++r) {
    for (int j = 0; j < n; ++j) {
      M[r][j] = A[r][j];
      scale = fmax(scale, fabs(A[r][j]));
    }
    M[r][n] = b[r];
  }
  for (int j = 0; j < n; ++j) {
    int piv = j;
    for (int r = j + 1; r < n; ++r) {
      piv = fabs(M[r][j]) > fabs(M[piv][j]) ? r : piv;
    }
    if (!(fabs(M[piv][j]) > 1e-12 * scale)) {
      return 0;
    }
    for (int q = 0; q <= n; ++q) {
      double t = M[j][q];
      M[j][q] = M[piv][q];
      M[piv][q] = t;
    }
    for (int r = j + 1; r < n; ++r) {
      double f = M[r][j] / M[j][j];
      for (int q = j; q <= n; ++q) {
        M[r][q] -= f * M[j][q];
      }
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    double t = M[r][n];
    for (int q = r + 1; q < n; ++q) {
      t -= M[r][q] * x[q];
    }
    x[r] = t / M[r][r];
    if (!isfinite(x[r])) {
      return 0;
    }
  }
  return 1;
}

/* A vertex of the chain, its normals negated where the path enters its shape. */
static int vertex_at(const ss_scene *scene, int enters, unsigned geom, unsigned prim, double b1,
                     double b2, ss_manifold_vertex *v) {
  if (!ss_manifold_vertex_at(scene, geom, prim, b1, b2, v)) {
    return 0;
  }
  if (enters) {
    v->ng = ss_vec3_neg(v->ng);
    v->n = ss_vec3_neg(v->n);
    v->dn[0] = ss_vec3_neg(v->dn[0]);
    v->dn[1] = ss_vec3_neg(v->dn[1]);
  }
  return 1;
}

int ss_manifold_chain_vertex(const ss_scene *scene, ss_manifold_chain *c, int i, unsigned geom,
                             unsigned prim, double b1, double b2) {
  return vertex_at(scene, c->enters[i], geom, prim, b1, b2, &c->x[i]);
}

/* The links of all vertices and |v| of the stacked constraint; 0 when some
 * vertex's predecessor is not behind its shading normal. */
static int links_at(ss_vec3 x0, const ss_manifold_chain *c, const ss_manifold_target *y,
                    link l[SS_MANIFOLD_MAX_CHAIN], double *err) {
  double e2 = 0.0;
  for (int i = 0; i < c->k; ++i) {
    ss_manifold_target next = *y;
    if (i + 1 < c->k) {
      next.p = c->x[i + 1].p;
      next.at_infinity = 0;
    }
    if (!link_at(i ? c->x[i - 1].p : x0, &c->x[i], &next, c->eta[i], &l[i])) {
      return 0;
    }
    e2 += ss_vec3_dot(l[i].v, l[i].v);
  }
  *err = sqrt(e2);
  return 1;
}

/* A = d C / d b, C the stacked constraint (v_i's two components in rows 2i,
 * 2i + 1) and b the vertices' barycentrics (x_j's in columns 2j, 2j + 1):
 * v_i depends on x_i (its directions and shading normal), on x_(i-1)
 * through w_i and on x_(i+1) through w_o (block tridiagonal). */
static void constraint_jacobian(const ss_manifold_chain *c, const link l[SS_MANIFOLD_MAX_CHAIN],
                                int at_infinity, double A[4][4]) {
  const ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
  for (int r = 0; r < 4; ++r) {
    for (int j = 0; j < 4; ++j) {
      A[r][j] = 0.0;
    }
  }
  for (int i = 0; i < c->k; ++i) {
    const link *li = &l[i];
    const ss_manifold_vertex *xi = &c->x[i];
    int last = i + 1 == c->k;
    for (int k = 0; k < 2; ++k) {
      double d[2];
      ss_vec3 dwo = last && at_infinity ? zero : d_unit(li->wo, li->d2, xi->dp[k]);
      dv(li, xi, c->eta[i], d_unit(li->wi, li->d0, xi->dp[k]), dwo, xi->dn[k], d);
      A[2 * i][2 * i + k] = d[0];
      A[2 * i + 1][2 * i + k] = d[1];
      /* The far end of a unit vector moved: the opposite of d_unit. */
      if (i > 0) {
        ss_vec3 dwi = ss_vec3_neg(d_unit(li->wi, li->d0, c->x[i - 1].dp[k]));
        dv(li, xi, c->eta[i], dwi, zero, zero, d);
        A[2 * i][2 * (i - 1) + k] = d[0];
        A[2 * i + 1][2 * (i - 1) + k] = d[1];
      }
      if (!last) {
        dv(li, xi, c->eta[i], zero, ss_vec3_neg(d_unit(li->wo, li->d2, c->x[i + 1].dp[k])), zero,
           d);
        A[2 * i][2 * (i + 1) + k] = d[0];
        A[2 * i + 1][2 * (i + 1) + k] = d[1];
      }
    }
  }
}

/* A refraction (not a grazing limit), the predecessor behind and the
 * successor in front of the geometric surface too. */
static int refracts(const link *c, const ss_manifold_vertex *x1) {
  return !c->tir && ss_vec3_dot(c->wi, x1->ng) < 0.0 && ss_vec3_dot(c->wo, x1->ng) > 0.0;
}

/* Surfaces of other shapes a projection ray passes (pass_others) at most. */
#define MAX_PASSED 64

/* Projects p onto the shape of vertex i of c by a ray from its predecessor
 * (x0, or the surface point `prev` left on the side toward p), which must
 * meet that shape on the side the vertex's normals point away from. */
static int project(const ss_scene *scene, const ss_manifold_chain *c, int i, ss_vec3 x0,
                   const ss_manifold_vertex *prev, ss_vec3 p, ss_manifold_vertex *out,
                   uint64_t *rays) {
  ss_ray ray = {x0, ss_vec3_sub(p, x0), 0.0, INFINITY};
  if (prev) {
    /* Aimed from the offset origin, so that the ray passes p itself. */
    ray.o = ss_offset_ray_origin(prev->p, prev->ng, ss_vec3_sub(p, prev->p));
    ray.d = ss_vec3_sub(p, ray.o);
  }
  const unsigned geom = c->x[i].geom_id;
  ss_hit hit;
  for (int passed = 0;; ++passed) {
    ++*rays;
    if (!ss_accel_intersect(scene->accel, &ray, &hit)) {
      return 0;
    }
    if (hit.geom_id == geom) {
      break;
    }
    if (!c->pass_others || passed == MAX_PASSED) {
      return 0;
    }
    /* On from the passed surface, aimed at p again (float offsets of the
     * origin would shift the line off p and stall Newton's method). */
    ray.o = ss_offset_ray_origin(hit.p, hit.ng, ray.d);
    ray.d = ss_vec3_sub(p, ray.o);
  }
  double side = ss_vec3_dot(ray.d, hit.ng);
  if (c->enters[i] ? !(side < 0.0) : !(side > 0.0)) {
    return 0;
  }
  /* Barycentrics again in double (Moller & Trumbore 1997): Embree's float
   * ones would stall Newton's method near 1e-7. */
  ss_vec3 q[3];
  ss_mesh_triangle(scene->shapes[geom].mesh, hit.prim_id, q);
  ss_vec3 e1 = ss_vec3_sub(q[1], q[0]), e2 = ss_vec3_sub(q[2], q[0]);
  ss_vec3 pv = ss_vec3_cross(ray.d, e2), tv = ss_vec3_sub(ray.o, q[0]);
  double det = ss_vec3_dot(e1, pv);
  if (!(fabs(det) > 0.0)) {
    return 0;
  }
  ss_vec3 qv = ss_vec3_cross(tv, e1);
  double b1 = ss_vec3_dot(tv, pv) / det, b2 = ss_vec3_dot(ray.d, qv) / det;
  return vertex_at(scene, c->enters[i], geom, hit.prim_id, b1, b2, out);
}

int ss_manifold_chain_solve(const ss_scene *scene, ss_vec3 x0, ss_manifold_chain *c,
                            const ss_manifold_target *y, int max_iterations, double tolerance,
                            uint64_t *rays) {
  link l[SS_MANIFOLD_MAX_CHAIN];
  double err, beta = 1.0;
  if (!(c->k >= 1 && c->k <= SS_MANIFOLD_MAX_CHAIN) || !links_at(x0, c, y, l, &err)) {
    return 0;
  }
  for (int it = 0;; ++it) {
    if (err < tolerance) {
      for (int i = 0; i < c->k; ++i) {
        if (!refracts(&l[i], &c->x[i])) {
          return 0;
        }
      }
      return 1;
    }
    if (it == max_iterations) {
      return 0;
    }
    double A[4][4], C[4], db[4];
    for (int i = 0; i < c->k; ++i) {
      C[2 * i] = ss_vec3_dot(l[i].v, l[i].f.s);
      C[2 * i + 1] = ss_vec3_dot(l[i].v, l[i].f.t);
    }
    constraint_jacobian(c, l, y->at_infinity, A);
    if (!solve_n(2 * c->k, A, C, db)) {
      return 0;
    }
    /* Newton step of every vertex in its triangle's plane, then back onto
     * the meshes in order along the chain. */
    ss_manifold_chain next = *c;
    int projected = 1;
    for (int i = 0; i < c->k && projected; ++i) {
      const ss_manifold_vertex *xi = &c->x[i];
      ss_vec3 p = ss_vec3_madd(ss_vec3_madd(xi->p, xi->dp[0], -beta * db[2 * i]), xi->dp[1],
                               -beta * db[2 * i + 1]);
      projected = project(scene, &next, i, x0, i ? &next.x[i - 1] : NULL, p, &next.x[i], rays);
    }
    link ln[SS_MANIFOLD_MAX_CHAIN];
    double err_next;
    if (projected && links_at(x0, &next, y, ln, &err_next) && err_next < err) {
      *c = next;
      for (int i = 0; i < c->k; ++i) {
        l[i] = ln[i];
      }
      err = err_next;
      beta = fmin(1.0, 2.0 * beta);
    } else {
      beta *= 0.5;
    }
  }
}

double ss_manifold_chain_jacobian(ss_vec3 x0, const ss_manifold_chain *c,
                                  const ss_manifold_target *y, ss_vec3 t1, ss_vec3 t2) {
  link l[SS_MANIFOLD_MAX_CHAIN];
  double err;
  if (!(c->k >= 1 && c->k <= SS_MANIFOLD_MAX_CHAIN) || !links_at(x0, c, y, l, &err)) {
    return 0.0;
  }
  for (int i = 0; i < c->k; ++i) {
    if (l[i].tir) {
      return 0.0;
    }
  }
  double A[4][4];
  constraint_jacobian(c, l, y->at_infinity, A);
  /* d b / d y_j = -A^-1 (d C / d y_j) (implicit function theorem; only the
   * last vertex's w_o depends on y), then d omega_0 = (I - omega_0
   * omega_0^T) dx_1 / d0 with omega_0 = -w_i of the first vertex. */
  const int last = c->k - 1;
  const link *ll = &l[last];
  const ss_manifold_vertex *x1 = &c->x[0];
  ss_vec3 t[2] = {t1, t2};
  ss_frame g = ss_frame_from_normal(ss_vec3_neg(l[0].wi));
  double K[2][2];
  for (int j = 0; j < 2; ++j) {
    ss_vec3 dwo = y->at_infinity ? ss_vec3_madd(t[j], ll->wo, -ss_vec3_dot(ll->wo, t[j]))
                                 : d_unit(ll->wo, ll->d2, ss_vec3_neg(t[j]));
    ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
    double B[4] = {0.0, 0.0, 0.0, 0.0}, db[4];
    dv(ll, &c->x[last], c->eta[last], zero, dwo, zero, &B[2 * last]);
    if (!solve_n(2 * c->k, A, B, db)) {
      return 0.0;
    }
    ss_vec3 dx1 =
        ss_vec3_scale(ss_vec3_madd(ss_vec3_scale(x1->dp[0], db[0]), x1->dp[1], db[1]), -1.0);
    ss_vec3 dw = d_unit(ss_vec3_neg(l[0].wi), l[0].d0, ss_vec3_neg(dx1));
    K[0][j] = ss_vec3_dot(dw, g.s);
    K[1][j] = ss_vec3_dot(dw, g.t);
  }
  return fabs(K[0][0] * K[1][1] - K[0][1] * K[1][0]);
}
