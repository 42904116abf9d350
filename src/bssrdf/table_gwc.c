/* Building Ferrier's (rho, theta, r) table from direct photon beam diffusion
 * (Ferrier2016 sec. 3.1-3.3) with either azimuthal model of table_gwc.h. */
#include "subsurf/table_gwc.h"

#include "subsurf/catmull_rom.h"
#include "subsurf/gwc.h"
#include "subsurf/pbd.h"
#include "subsurf/sampling.h"
#include "subsurf/table_radial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Gauss-Legendre nodes per beam piece: 16 keep PBD within ~1e-5 of its
 * converged value (test_pbd.c), far below the table's interpolation error,
 * at half the cost of 32. */
#define GWC_BEAM_NODES 16
/* Azimuths on [0, pi] for the two-lobe fit (odd radii) and for the radial
 * energy alone (even radii): the trapezoid rule on the smooth periodic
 * profile errs like c^(2 (n - 1)), below 1e-6 for c <= 0.55. */
#define GWC_AZIMUTHS 17
#define GWC_AZIMUTHS_ENERGY 13

/* A table with n_rho albedo rows (100, or 1 for a material slice). */
static ss_status alloc_rows(double eta, double g, int fit, size_t n_rho, ss_table_gwc **out,
                            ss_error *err) {
  if (fit != SS_TABLE_GWC_ANCHORS && fit != SS_TABLE_GWC_TWO_LOBE) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "table-gwc: unknown azimuthal fit %d", fit);
  }
  ss_table_gwc *t = calloc(1, sizeof *t);
  if (!t) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table-gwc: out of memory");
  }
  t->eta = eta;
  t->g = g;
  t->fit = fit;
  t->n_rho = n_rho;
  t->n_theta = SS_TABLE_THETA_COUNT;
  t->n_r = SS_TABLE_RADIUS_COUNT;
  t->n_rs = fit == SS_TABLE_GWC_ANCHORS ? t->n_r : t->n_r / 2;
  t->n_shape = fit == SS_TABLE_GWC_ANCHORS ? 2 : 3;
  size_t rows = t->n_rho * t->n_theta;
  t->rho = malloc(t->n_rho * sizeof *t->rho);
  t->theta = malloc((t->n_theta + 1) * sizeof *t->theta);
  t->radius = malloc(t->n_r * sizeof *t->radius);
  t->radius_shape = malloc(t->n_rs * sizeof *t->radius_shape);
  t->energy = calloc(rows * t->n_r, sizeof *t->energy);
  t->shape = calloc(rows * t->n_rs * t->n_shape, sizeof *t->shape);
  t->cdf = calloc(rows * t->n_r, sizeof *t->cdf);
  t->albedo = calloc(t->n_rho * (t->n_theta + 1), sizeof *t->albedo);
  t->albedo_cdf = calloc(t->n_rho * (t->n_theta + 1), sizeof *t->albedo_cdf);
  t->radial_energy = calloc(t->n_rho * t->n_r, sizeof *t->radial_energy);
  t->radial_cdf = calloc(t->n_rho * t->n_r, sizeof *t->radial_cdf);
  t->cdf_guide = calloc(rows * SS_TABLE_GWC_GUIDE, 1);
  t->radial_guide = calloc(t->n_rho * SS_TABLE_GWC_GUIDE, 1);
  if (!t->rho || !t->theta || !t->radius || !t->radius_shape || !t->energy || !t->shape ||
      !t->cdf || !t->albedo || !t->albedo_cdf || !t->radial_energy || !t->radial_cdf ||
      !t->cdf_guide || !t->radial_guide) {
    ss_table_gwc_destroy(t);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table-gwc: out of memory");
  }
  if (n_rho > 1) {
    ss_table_rho_grid(t->rho, t->n_rho);
  }
  ss_table_radius_grid(t->radius, t->n_r);
  /* Ferrier2016 sec. 3.1: theta_i = i pi / 18. */
  for (size_t i = 0; i <= t->n_theta; ++i) {
    t->theta[i] = (double)i * SS_PI / 18.0;
  }
  for (size_t k = 0; k < t->n_rs; ++k) {
    t->radius_shape[k] = fit == SS_TABLE_GWC_ANCHORS ? t->radius[k] : t->radius[2 * k + 1];
  }
  /* The theta axis runs on to the mirror node (table_gwc.h). */
  if ((t->n_rho >= 4 && !ss_cr_grid_init(&t->rho_grid, t->n_rho, t->rho, 0)) ||
      !ss_cr_grid_init(&t->theta_grid, t->n_theta + 1, t->theta, 1) ||
      !ss_cr_grid_init(&t->r_grid, t->n_r, t->radius, 0) ||
      !ss_cr_grid_init(&t->rs_grid, t->n_rs, t->radius_shape, 0) ||
      !(t->shape_interval = malloc(t->n_r - 1))) {
    ss_table_gwc_destroy(t);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table-gwc: out of memory");
  }
  for (size_t i = 0; i + 1 < t->n_r; ++i) {
    double mid = 0.5 * (t->radius[i] + t->radius[i + 1]);
    mid = fmin(fmax(mid, t->radius_shape[0]), t->radius_shape[t->n_rs - 1]);
    t->shape_interval[i] = (uint8_t)ss_cr_find_interval(t->n_rs, t->radius_shape, mid);
  }
  *out = t;
  return SS_OK;
}

ss_status ss_table_gwc_alloc(double eta, double g, int fit, ss_table_gwc **out, ss_error *err) {
  return alloc_rows(eta, g, fit, SS_TABLE_RHO_COUNT, out, err);
}

ss_status ss_table_gwc_slice(const ss_table_gwc *t, double rho, ss_table_gwc **out, ss_error *err) {
  long off;
  double w[4];
  if (!ss_cr_weights(t->n_rho, t->rho, rho, &off, w)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "table-gwc: albedo %g outside [0, 1]", rho);
  }
  ss_table_gwc *s;
  ss_status st = alloc_rows(t->eta, t->g, t->fit, 1, &s, err);
  if (st != SS_OK) {
    return st;
  }
  s->rho[0] = rho;
  /* The albedo spline is linear in the data: interpolating the rows first
   * gives the same function of (theta, r) as interpolating at each query. */
  size_t ne = t->n_theta * t->n_r, ns = t->n_theta * t->n_rs * t->n_shape;
  for (size_t q = 0; q < ne; ++q) {
    double v = 0.0;
    for (int k = 0; k < 4; ++k) {
      v += w[k] != 0.0 ? w[k] * t->energy[(size_t)(off + k) * ne + q] : 0.0;
    }
    s->energy[q] = (float)v;
  }
  for (size_t q = 0; q < ns; ++q) {
    double v = 0.0;
    for (int k = 0; k < 4; ++k) {
      v += w[k] != 0.0 ? w[k] * t->shape[(size_t)(off + k) * ns + q] : 0.0;
    }
    s->shape[q] = (float)v;
  }
  ss_table_gwc_finish(s);
  *out = s;
  return SS_OK;
}

void ss_table_gwc_destroy(ss_table_gwc *t) {
  if (!t) {
    return;
  }
  free(t->rho);
  free(t->theta);
  free(t->radius);
  free(t->radius_shape);
  free(t->energy);
  free(t->shape);
  free(t->cdf);
  free(t->albedo);
  free(t->albedo_cdf);
  free(t->radial_energy);
  free(t->radial_cdf);
  free(t->cdf_guide);
  free(t->radial_guide);
  free(t->shape_interval);
  ss_cr_grid_free(&t->rho_grid);
  ss_cr_grid_free(&t->theta_grid);
  ss_cr_grid_free(&t->r_grid);
  ss_cr_grid_free(&t->rs_grid);
  free(t);
}

size_t ss_table_gwc_bytes(const ss_table_gwc *t) {
  size_t rows = t->n_rho * t->n_theta;
  size_t floats = rows * (2 * t->n_r + t->n_rs * t->n_shape) + 2 * t->n_rho * (t->n_theta + 1);
  size_t doubles = t->n_rho + t->n_theta + 1 + t->n_r + t->n_rs + SS_TABLE_THETA_COUNT;
  return floats * sizeof(float) + doubles * sizeof(double);
}

const char *ss_table_gwc_fit_name(int fit) {
  return fit == SS_TABLE_GWC_TWO_LOBE ? "two-lobe" : "anchors";
}

int ss_table_gwc_fit_from_name(const char *name, int *fit) {
  if (!strcmp(name, "anchors") || !strcmp(name, "gwc")) {
    *fit = SS_TABLE_GWC_ANCHORS;
    return 1;
  }
  if (!strcmp(name, "two-lobe")) {
    *fit = SS_TABLE_GWC_TWO_LOBE;
    return 1;
  }
  return 0;
}

/* Entry b: the last node k <= n - 2 whose cumulative value is at most
 * b / SS_TABLE_GWC_GUIDE of the row's total. */
static void guide_row(size_t n, const float *cdf, uint8_t *guide) {
  size_t k = 0;
  for (size_t b = 0; b < SS_TABLE_GWC_GUIDE; ++b) {
    double target = (double)b / SS_TABLE_GWC_GUIDE * cdf[n - 1];
    while (k + 2 < n && cdf[k + 1] <= target) {
      ++k;
    }
    guide[b] = (uint8_t)k;
  }
}

void ss_table_gwc_finish(ss_table_gwc *t) {
  size_t rows = t->n_rho * t->n_theta, nt = t->n_theta + 1;
  double F[SS_TABLE_RADIUS_COUNT > SS_TABLE_THETA_COUNT ? SS_TABLE_RADIUS_COUNT
                                                        : SS_TABLE_THETA_COUNT + 1];
  /* Ferrier2016 sec. 4.3: the cumulative radial energy for sampling r. */
  for (size_t row = 0; row < rows; ++row) {
    double a = ss_cr_integrate(t->n_r, t->radius, t->energy + row * t->n_r, 1, F);
    t->albedo[(row / t->n_theta) * nt + row % t->n_theta] = (float)a;
    for (size_t j = 0; j < t->n_r; ++j) {
      t->cdf[row * t->n_r + j] = (float)F[j];
    }
    guide_row(t->n_r, t->cdf + row * t->n_r, t->cdf_guide + row * SS_TABLE_GWC_GUIDE);
  }
  /* Sec. 7.1: the effective albedo over theta, for sampling theta_i; the
   * ghost column mirrors 80 deg about 90 deg. */
  for (size_t i = 0; i < t->n_rho; ++i) {
    float *a = t->albedo + i * nt;
    a[t->n_theta] = a[t->n_theta - 2];
    ss_cr_integrate(nt, t->theta, a, 1, F);
    for (size_t j = 0; j < nt; ++j) {
      t->albedo_cdf[i * nt + j] = (float)F[j];
    }
  }
  /* Integrals over [0, pi/2] of each node's spline basis (the spline is
   * linear in the data): the radius marginal of the path sampler mixes rows
   * with them. */
  float unit[SS_TABLE_THETA_COUNT + 1];
  for (size_t j = 0; j < t->n_theta; ++j) {
    for (size_t k = 0; k < t->n_theta; ++k) {
      unit[k] = k == j ? 1.0f : 0.0f;
    }
    unit[t->n_theta] = unit[t->n_theta - 2];
    ss_cr_integrate(nt, t->theta, unit, 1, F);
    t->theta_weight[j] = F[t->n_theta - 1];
  }
  /* The path sampler's radius marginal: theta integrated out of the spline
   * (the spline is linear in the data, so the integral mixes the rows). */
  for (size_t i = 0; i < t->n_rho; ++i) {
    float *e = t->radial_energy + i * t->n_r;
    for (size_t k = 0; k < t->n_r; ++k) {
      double v = 0.0;
      for (size_t j = 0; j < t->n_theta; ++j) {
        v += t->theta_weight[j] * t->energy[(i * t->n_theta + j) * t->n_r + k];
      }
      e[k] = (float)v;
    }
    ss_cr_integrate(t->n_r, t->radius, e, 1, F);
    for (size_t k = 0; k < t->n_r; ++k) {
      t->radial_cdf[i * t->n_r + k] = (float)F[k];
    }
    guide_row(t->n_r, t->radial_cdf + i * t->n_r, t->radial_guide + i * SS_TABLE_GWC_GUIDE);
  }
}

/* One (rho, theta) row with the paper's three-anchor GWC: (E, beta, c). */
static void build_row_anchors(ss_table_gwc *t, const ss_pbd *p, const ss_pbd_beam *beam,
                              size_t row) {
  for (size_t j = 0; j < t->n_r; ++j) {
    double r = t->radius[j], f[3];
    float *sh = t->shape + (row * t->n_rs + j) * 2;
    if (r == 0.0) {
      t->energy[row * t->n_r + j] = 0.0f;
      sh[0] = sh[1] = 0.0f;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      f[k] = beam->sin_t == 0.0 && k > 0 ? f[0] : ss_pbd_ms(p, beam, r, acos(ss_gwc_anchor_cos[k]));
    }
    ss_gwc fit;
    ss_gwc_fit3(ss_gwc_anchor_cos, f, &fit);
    /* Ferrier2016 eq. 1: E = (2 pi alpha + beta) r. */
    t->energy[row * t->n_r + j] = (float)(ss_gwc_integral(&fit) * r);
    double integral = ss_gwc_integral(&fit);
    sh[0] = integral > 0.0 ? (float)(fit.beta / integral) : 0.0f;
    sh[1] = (float)fit.c;
  }
}

/* One row with two Wrapped Cauchy lobes: exact E, least-squares shape. */
static void build_row_two_lobe(ss_table_gwc *t, const ss_pbd *p, const ss_pbd_beam *beam,
                               size_t row) {
  double phi[GWC_AZIMUTHS], w[GWC_AZIMUTHS], f[GWC_AZIMUTHS], h[GWC_AZIMUTHS];
  for (size_t j = 0; j < t->n_r; ++j) {
    double r = t->radius[j];
    if (r == 0.0) {
      t->energy[row * t->n_r + j] = 0.0f;
      continue;
    }
    int shape_node = j % 2 == 1, n = shape_node ? GWC_AZIMUTHS : GWC_AZIMUTHS_ENERGY;
    double sum = 0.0;
    for (int m = 0; m < n; ++m) {
      phi[m] = SS_PI * m / (n - 1);
      w[m] = (m == 0 || m == n - 1) ? 0.5 : 1.0;
      f[m] = beam->sin_t == 0.0 && m > 0 ? f[0] : ss_pbd_ms(p, beam, r, phi[m]);
      sum += w[m] * f[m];
    }
    /* E = r int_{-pi}^{pi} S dphi, trapezoid on the even periodic profile. */
    double e = 2.0 * r * sum * SS_PI / (n - 1);
    t->energy[row * t->n_r + j] = (float)e;
    if (!shape_node) {
      continue;
    }
    float *sh = t->shape + (row * t->n_rs + j / 2) * 3;
    ss_wc2 fit = {1.0, 0.0, 0.0};
    if (beam->sin_t > 0.0 && e > 0.0) {
      for (int m = 0; m < n; ++m) {
        h[m] = f[m] * r / e;
      }
      ss_wc2_fit((size_t)n, phi, h, w, &fit);
    }
    double harm[3];
    ss_wc2_harmonics(&fit, harm);
    sh[0] = (float)harm[0];
    sh[1] = (float)harm[1];
    sh[2] = (float)harm[2];
  }
}

ss_status ss_table_gwc_build(double eta, double g, int fit, ss_table_gwc **out, ss_error *err) {
  ss_pbd probe;
  ss_status st = ss_pbd_init(&probe, 0.5, 0.5, g, eta, GWC_BEAM_NODES, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "table-gwc: ");
    return st;
  }
  if (!(eta > 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "table-gwc: eta must be > 1 (Ferrier's model), got %g", eta);
  }
  ss_table_gwc *t;
  st = ss_table_gwc_alloc(eta, g, fit, &t, err);
  if (st != SS_OK) {
    return st;
  }
  /* Materials first, serially: ss_pbd_init's Fresnel moments use GSL
   * quadrature, whose error-handler switch is global state. */
  ss_pbd *mat = malloc(t->n_rho * sizeof *mat);
  if (!mat) {
    ss_table_gwc_destroy(t);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table-gwc: out of memory");
  }
  for (size_t i = 0; i < t->n_rho; ++i) {
    mat[i] = probe;
    ss_pbd_set_albedo(&mat[i], t->rho[i], 1.0 - t->rho[i]);
  }
  long rows = (long)(t->n_rho * t->n_theta);
#pragma omp parallel for schedule(dynamic)
  for (long row = 0; row < rows; ++row) {
    size_t i = (size_t)row / t->n_theta, k = (size_t)row % t->n_theta;
    ss_pbd_beam beam = ss_pbd_beam_make(&mat[i], t->theta[k]);
    if (fit == SS_TABLE_GWC_ANCHORS) {
      build_row_anchors(t, &mat[i], &beam, (size_t)row);
    } else {
      build_row_two_lobe(t, &mat[i], &beam, (size_t)row);
    }
  }
  free(mat);
  ss_table_gwc_finish(t);
  *out = t;
  return SS_OK;
}
