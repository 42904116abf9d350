/* Assembly of the finite-element system of the anisotropic diffusion
 * equation with linear tetrahedra (Jakob2010 eq. 39-42;
 * the isotropic derivation of Arbree2011):
 *   R_ij = int grad beta_i . M^-1 grad beta_j dx        (eq. 40)
 *   T_ij = int mu0/(4 pi) beta_i beta_j dx              (eq. 41)
 *   S_ij = 1/(2A) int_boundary beta_i beta_j ds         (eq. 42)
 *   q_i = int Q0 beta_i dx,  g_i = 2/(A Fdt) int Gamma_s beta_i ds  (eq. 39)
 * Q0 from a point source, a uniform volume source and refracted rays
 * (fem_rays.c). The element matrices are exact for linear elements and constant
 * coefficients per tetrahedron. */
#include "fem/fem_internal.h"
#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"

#include <cholmod.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static ss_vec3 vtx(const ss_fem_mesh *m, uint32_t v) {
  const double *p = m->positions + 3 * (size_t)v;
  return ss_vec3_make(p[0], p[1], p[2]);
}

/* Inverse of a symmetric positive definite 3x3 matrix; 0 when it is not
 * (a leading minor <= 0) or not symmetric to 1e-9. */
static int spd_inverse(const double M[9], double inv[9]) {
  double scale = fabs(M[0]) + fabs(M[4]) + fabs(M[8]);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < i; ++j) {
      if (!(fabs(M[3 * i + j] - M[3 * j + i]) <= 1e-9 * scale)) {
        return 0;
      }
    }
  }
  double m1 = M[0], m2 = M[0] * M[4] - M[1] * M[3];
  double c00 = M[4] * M[8] - M[5] * M[7], c01 = M[2] * M[7] - M[1] * M[8],
         c02 = M[1] * M[5] - M[2] * M[4];
  double det = M[0] * c00 + M[3] * c01 + M[6] * c02;
  if (!(m1 > 0.0) || !(m2 > 0.0) || !(det > 0.0) || !isfinite(det)) {
    return 0;
  }
  inv[0] = c00 / det;
  inv[1] = c01 / det;
  inv[2] = c02 / det;
  inv[4] = (M[0] * M[8] - M[2] * M[6]) / det;
  inv[5] = (M[2] * M[3] - M[0] * M[5]) / det;
  inv[8] = (M[0] * M[4] - M[1] * M[3]) / det;
  inv[3] = inv[1];
  inv[6] = inv[2];
  inv[7] = inv[5];
  return 1;
}

static void add_entry(cholmod_triplet *T, uint32_t i, uint32_t j, double v) {
  int *ri = T->i, *rj = T->j;
  double *x = T->x;
  size_t k = T->nnz++;
  ri[k] = (int)(i < j ? i : j);
  rj[k] = (int)(i < j ? j : i);
  x[k] = v;
}

/* Volume terms R + T and q of one tetrahedron. */
static ss_status add_tet(const ss_fem_mesh *m, size_t t, ss_fem_medium_fn medium, void *ctx,
                         const ss_fem_problem *pb, cholmod_triplet *T, ss_fem_system *sys,
                         ss_error *err) {
  const uint32_t *v = m->tets + 4 * t;
  ss_vec3 p[4];
  for (int k = 0; k < 4; ++k) {
    p[k] = vtx(m, v[k]);
  }
  ss_vec3 e1 = ss_vec3_sub(p[1], p[0]), e2 = ss_vec3_sub(p[2], p[0]), e3 = ss_vec3_sub(p[3], p[0]);
  double det = ss_vec3_dot(ss_vec3_cross(e1, e2), e3), vol = det / 6.0;
  /* grad lambda_k for k = 1..3: rows of the inverse of [e1 e2 e3] */
  ss_vec3 g[4];
  g[1] = ss_vec3_scale(ss_vec3_cross(e2, e3), 1.0 / det);
  g[2] = ss_vec3_scale(ss_vec3_cross(e3, e1), 1.0 / det);
  g[3] = ss_vec3_scale(ss_vec3_cross(e1, e2), 1.0 / det);
  g[0] = ss_vec3_scale(ss_vec3_add(ss_vec3_add(g[1], g[2]), g[3]), -1.0);
  ss_vec3 c = ss_vec3_scale(ss_vec3_add(ss_vec3_add(p[0], p[1]), ss_vec3_add(p[2], p[3])), 0.25);
  ss_fem_coeffs k;
  ss_status st = medium(ctx, c, &k, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "fem: medium at element %zu: ", t);
    return st;
  }
  double D[9];
  if (!spd_inverse(k.M, D)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: the diffusion matrix M of element %zu (centroid %g %g %g) is not "
                        "symmetric positive definite",
                        t, c.x, c.y, c.z);
  }
  if (!(k.mu0 >= 0.0) || !isfinite(k.mu0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: absorption mu0 = %g of element %zu must be finite and >= 0", k.mu0,
                        t);
  }
  double a = k.mu0 / (4.0 * SS_PI);
  for (int i = 0; i < 4; ++i) {
    ss_vec3 Dg = ss_vec3_make(D[0] * g[i].x + D[1] * g[i].y + D[2] * g[i].z,
                              D[3] * g[i].x + D[4] * g[i].y + D[5] * g[i].z,
                              D[6] * g[i].x + D[7] * g[i].y + D[8] * g[i].z);
    for (int j = i; j < 4; ++j) {
      /* eq. 40 and 41: the linear-element mass matrix is V (1 + delta_ij)/20 */
      double r = vol * ss_vec3_dot(Dg, g[j]);
      double tm = a * vol * (i == j ? 2.0 : 1.0) / 20.0;
      add_entry(T, v[i], v[j], r + tm);
    }
    sys->absorb_weight[v[i]] += a * vol / 4.0;
    sys->b[v[i]] += pb->volume_source * vol / 4.0;
  }
  sys->volume_injected += pb->volume_source * vol;
  return SS_OK;
}

/* The spot's Gamma_s over one boundary face: int Gamma_s beta_i ds by the
 * midpoint rule on 4^4 congruent sub-triangles (the disc's edge cuts faces). */
static double spot_face(ss_vec3 p[3], const ss_fem_problem *pb, double area, double w[3]) {
  const int n = 16; /* sub-divisions per edge: n^2 sub-triangles */
  double r2 = pb->spot_radius * pb->spot_radius, total = 0.0;
  w[0] = w[1] = w[2] = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n - i; ++j) {
      for (int up = 0; up < 2; ++up) {
        if (up && i + j == n - 1) {
          continue;
        }
        double l1 = up ? (i + 2.0 / 3.0) / n : (i + 1.0 / 3.0) / n;
        double l2 = up ? (j + 2.0 / 3.0) / n : (j + 1.0 / 3.0) / n, l0 = 1.0 - l1 - l2;
        ss_vec3 x = ss_vec3_add(ss_vec3_add(ss_vec3_scale(p[0], l0), ss_vec3_scale(p[1], l1)),
                                ss_vec3_scale(p[2], l2));
        ss_vec3 d = ss_vec3_sub(x, pb->spot_center);
        if (ss_vec3_dot(d, d) < r2) {
          double da = area / (n * n);
          w[0] += l0 * da;
          w[1] += l1 * da;
          w[2] += l2 * da;
          total += da;
        }
      }
    }
  }
  return total;
}

/* Boundary terms S and g; returns the spot's covered area in *covered. */
static void add_faces(const ss_fem_mesh *m, const ss_fem_problem *pb, cholmod_triplet *T,
                      ss_fem_system *sys, double *spot_w, double *covered) {
  *covered = 0.0;
  double Fdt = 1.0 - ss_fresnel_diffuse_reflectance(pb->eta);
  for (size_t f = 0; f < m->num_faces; ++f) {
    const uint32_t *v = m->faces + 3 * f;
    ss_vec3 p[3] = {vtx(m, v[0]), vtx(m, v[1]), vtx(m, v[2])};
    double area =
        0.5 * ss_vec3_length(ss_vec3_cross(ss_vec3_sub(p[1], p[0]), ss_vec3_sub(p[2], p[0])));
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) {
        /* eq. 42: the triangle mass matrix is area (1 + delta_ij)/12 */
        add_entry(T, v[i], v[j], area * (i == j ? 2.0 : 1.0) / 12.0 / (2.0 * sys->A));
      }
      sys->face_weight[v[i]] += area / 3.0;
    }
    if (pb->face_gamma) {
      /* eq. 39 for a Gamma_s constant on the face: int Gamma_s beta_i = Gamma_s area / 3;
       * gamma_vertex holds the sum until it is divided by face_weight */
      double gf = pb->face_gamma[f];
      for (int i = 0; i < 3; ++i) {
        sys->b[v[i]] += 2.0 / (sys->A * Fdt) * gf * area / 3.0;
        sys->gamma_vertex[v[i]] += gf * area / 3.0;
      }
      sys->spot_injected += gf * area;
    }
    if (pb->spot_power > 0.0) {
      double reach = pb->spot_radius;
      for (int i = 0; i < 3; ++i) {
        reach += ss_vec3_length(ss_vec3_sub(p[i], p[(i + 1) % 3]));
      }
      if (ss_vec3_length(ss_vec3_sub(p[0], pb->spot_center)) < reach) {
        double w[3];
        *covered += spot_face(p, pb, area, w);
        for (int i = 0; i < 3; ++i) {
          spot_w[v[i]] += w[i];
        }
      }
    }
  }
}

static ss_status check_problem(const ss_fem_problem *pb, ss_error *err) {
  if (!(pb->eta > 0.0) || !isfinite(pb->eta)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "fem: eta = %g must be > 0", pb->eta);
  }
  if (!(pb->spot_power >= 0.0) || !isfinite(pb->spot_power) || !(pb->point_power >= 0.0) ||
      !isfinite(pb->point_power) || !(pb->volume_source >= 0.0) || !isfinite(pb->volume_source)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: source powers must be finite and >= 0 (spot %g, point %g, volume %g)",
                        pb->spot_power, pb->point_power, pb->volume_source);
  }
  if (pb->spot_power > 0.0 && (!(pb->spot_radius > 0.0) || !isfinite(pb->spot_radius))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "fem: spot radius %g must be > 0",
                        pb->spot_radius);
  }
  return SS_OK;
}

static ss_status add_sources(const ss_fem_mesh *m, const ss_fem_problem *pb, ss_fem_system *sys,
                             const double *spot_w, double covered, ss_error *err) {
  if (pb->face_gamma) {
    /* the area-weighted mean of the faces' Gamma_s at each boundary vertex */
    for (size_t i = 0; i < sys->n; ++i) {
      sys->gamma_vertex[i] =
          sys->face_weight[i] > 0.0 ? sys->gamma_vertex[i] / sys->face_weight[i] : 0.0;
    }
  }
  if (pb->spot_power > 0.0) {
    if (!(covered > 0.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "fem: the spot (centre %g %g %g, radius %g) does not touch the boundary",
                          pb->spot_center.x, pb->spot_center.y, pb->spot_center.z, pb->spot_radius);
    }
    /* Gamma_s = spot_power / covered area, so that int Gamma_s = spot_power */
    double gamma = pb->spot_power / covered, Fdt = 1.0 - ss_fresnel_diffuse_reflectance(pb->eta);
    for (size_t i = 0; i < sys->n; ++i) {
      /* eq. 39: g_i = 2/(A Fdt) int Gamma_s beta_i ds */
      sys->b[i] += 2.0 / (sys->A * Fdt) * gamma * spot_w[i];
      ss_vec3 d = ss_vec3_sub(vtx(m, (uint32_t)i), pb->spot_center);
      sys->gamma_vertex[i] += ss_vec3_dot(d, d) < pb->spot_radius * pb->spot_radius ? gamma : 0.0;
    }
    sys->spot_injected += pb->spot_power;
  }
  if (pb->point_power > 0.0) {
    size_t t;
    double lambda[4];
    if (!ss_fem_locate(m, pb->point, &t, lambda)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "fem: the point source (%g %g %g) lies outside the mesh", pb->point.x,
                          pb->point.y, pb->point.z);
    }
    for (int k = 0; k < 4; ++k) {
      sys->b[m->tets[4 * t + (size_t)k]] += pb->point_power * lambda[k];
    }
    sys->volume_injected += pb->point_power;
  }
  double rays_injected = 0.0;
  ss_status st = ss_fem_deposit_rays(m, pb, sys->b, &rays_injected, err);
  sys->volume_injected += rays_injected;
  return st;
}

ss_status ss_fem_assemble(const ss_fem_mesh *m, ss_fem_medium_fn medium, void *ctx,
                          const ss_fem_problem *pb, void *common, ss_fem_system *sys,
                          ss_error *err) {
  cholmod_common *cm = common;
  memset(sys, 0, sizeof *sys);
  ss_status st = check_problem(pb, err);
  if (st != SS_OK) {
    return st;
  }
  size_t n = m->num_vertices;
  sys->n = n;
  /* Jensen2001 sec. 2.1 (Jakob2010 eq. 26-27): A = (1 + Fdr)/(1 - Fdr) */
  sys->A = ss_fresnel_A(pb->eta);
  sys->b = calloc(n, sizeof *sys->b);
  sys->gamma_vertex = calloc(n, sizeof *sys->gamma_vertex);
  sys->absorb_weight = calloc(n, sizeof *sys->absorb_weight);
  sys->face_weight = calloc(n, sizeof *sys->face_weight);
  double *spot_w = calloc(n, sizeof *spot_w);
  size_t nnz = 10 * m->num_tets + 6 * m->num_faces;
  cholmod_triplet *T = cholmod_allocate_triplet(n, n, nnz, 1, CHOLMOD_REAL, cm);
  if (!sys->b || !sys->gamma_vertex || !sys->absorb_weight || !sys->face_weight || !spot_w || !T) {
    free(spot_w);
    cholmod_free_triplet(&T, cm);
    ss_fem_system_free(sys, cm);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for %zu unknowns", n);
  }
  for (size_t t = 0; t < m->num_tets && st == SS_OK; ++t) {
    st = add_tet(m, t, medium, ctx, pb, T, sys, err);
  }
  double covered = 0.0;
  if (st == SS_OK) {
    add_faces(m, pb, T, sys, spot_w, &covered);
    st = add_sources(m, pb, sys, spot_w, covered, err);
  }
  free(spot_w);
  if (st == SS_OK) {
    sys->K = cholmod_triplet_to_sparse(T, nnz, cm);
    if (!sys->K) {
      st = ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for the sparse matrix");
    }
  }
  cholmod_free_triplet(&T, cm);
  if (st != SS_OK) {
    ss_fem_system_free(sys, cm);
  }
  return st;
}

void ss_fem_system_free(ss_fem_system *sys, void *common) {
  cholmod_sparse *K = sys->K;
  cholmod_free_sparse(&K, common);
  free(sys->b);
  free(sys->gamma_vertex);
  free(sys->absorb_weight);
  free(sys->face_weight);
  memset(sys, 0, sizeof *sys);
}
