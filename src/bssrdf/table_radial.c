/* The pbrt-style radial BSSRDF table (pbrt-v3 ComputeBeamDiffusionBSSRDF,
 * TabulatedBSSRDF, SubsurfaceFromDiffuse; Ferrier2016 sec. 2.2): building from direct
 * PBD, Catmull-Rom evaluation and sampling, inversion of the albedo. The
 * model that uses it is table_radial_model.c. */
#include "subsurf/table_radial.h"

#include "subsurf/catmull_rom.h"
#include "subsurf/pbd.h"

#include "bssrdf/bssrdf_util.h"

#include <math.h>
#include <stdlib.h>

/* Gauss-Legendre nodes per beam piece: converged to ~1e-9 (test_pbd.c). */
#define TABLE_BEAM_NODES 32

void ss_table_rho_grid(double *rho, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    rho[i] = -expm1(-8.0 * (double)i / (double)(n - 1)) / -expm1(-8.0);
  }
}

void ss_table_radius_grid(double *r, size_t n) {
  r[0] = 0.0;
  if (n > 1) {
    r[1] = 0.0025;
  }
  for (size_t i = 2; i < n; ++i) {
    r[i] = r[i - 1] * 1.2;
  }
}

ss_status ss_table_radial_alloc(double eta, double g, ss_table_radial **out, ss_error *err) {
  ss_table_radial *t = calloc(1, sizeof *t);
  size_t n_rho = SS_TABLE_RHO_COUNT, n_r = SS_TABLE_RADIUS_COUNT;
  if (t) {
    t->rho = malloc(n_rho * sizeof *t->rho);
    t->radius = malloc(n_r * sizeof *t->radius);
    t->profile = calloc(n_rho * n_r, sizeof *t->profile);
    t->cdf = calloc(n_rho * n_r, sizeof *t->cdf);
    t->rho_eff = calloc(n_rho, sizeof *t->rho_eff);
  }
  if (!t || !t->rho || !t->radius || !t->profile || !t->cdf || !t->rho_eff) {
    ss_table_radial_destroy(t);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table-radial: out of memory");
  }
  t->eta = eta;
  t->g = g;
  t->n_rho = n_rho;
  t->n_r = n_r;
  ss_table_rho_grid(t->rho, n_rho);
  ss_table_radius_grid(t->radius, n_r);
  *out = t;
  return SS_OK;
}

void ss_table_radial_destroy(ss_table_radial *t) {
  if (!t) {
    return;
  }
  free(t->rho);
  free(t->radius);
  free(t->profile);
  free(t->cdf);
  free(t->rho_eff);
  free(t);
}

void ss_table_radial_finish(ss_table_radial *t) {
  double F[SS_TABLE_RADIUS_COUNT];
  for (size_t i = 0; i < t->n_rho; ++i) {
    t->rho_eff[i] = ss_cr_integrate(t->n_r, t->radius, t->profile + i * t->n_r, 1, F);
    for (size_t j = 0; j < t->n_r; ++j) {
      t->cdf[i * t->n_r + j] = (float)F[j];
    }
  }
}

ss_status ss_table_radial_build(double eta, double g, ss_table_radial **out, ss_error *err) {
  ss_table_radial *t;
  ss_status st = ss_table_radial_alloc(eta, g, &t, err);
  if (st != SS_OK) {
    return st;
  }
  /* Validate the material once so that the parallel loop cannot fail. */
  ss_pbd probe;
  st = ss_pbd_init(&probe, 0.5, 0.5, g, eta, TABLE_BEAM_NODES, err);
  if (st != SS_OK) {
    ss_table_radial_destroy(t);
    ss_error_prefix(err, "table-radial: ");
    return st;
  }
  /* The Fresnel moments in ss_pbd_init use GSL quadrature, whose
   * error-handler switch is global state: compute them outside the threads. */
  ss_pbd base = probe;
#pragma omp parallel for schedule(dynamic)
  for (size_t i = 0; i < t->n_rho; ++i) {
    ss_pbd p = base;
    ss_pbd_set_albedo(&p, t->rho[i], 1.0 - t->rho[i]);
    ss_pbd_beam beam = ss_pbd_beam_make(&p, 0.0);
    /* pbrt-v3 ComputeBeamDiffusionBSSRDF: store 2 pi r (E_ss + E_ms). */
    for (size_t j = 0; j < t->n_r; ++j) {
      double r = t->radius[j];
      t->profile[i * t->n_r + j] =
          r > 0.0 ? (float)(2.0 * SS_PI * r * (ss_pbd_ms(&p, &beam, r, 0.0) + ss_pbd_ss(&p, r)))
                  : 0.0f;
    }
  }
  ss_table_radial_finish(t);
  *out = t;
  return SS_OK;
}

/* The albedo axis' spline weights as a mixture of profile rows. */
static int rho_mix(const ss_table_radial *t, double rho, ss_cr_mix *m) {
  long off;
  double w[4];
  if (!ss_cr_weights(t->n_rho, t->rho, rho, &off, w)) {
    return 0;
  }
  m->count = 0;
  for (int k = 0; k < 4; ++k) {
    if (w[k] != 0.0) {
      m->row[m->count] = (size_t)(off + k);
      m->w[m->count] = w[k];
      m->count++;
    }
  }
  return 1;
}

static double profile_at(const ss_table_radial *t, const ss_cr_mix *m, double r) {
  long off;
  double w[4];
  if (!ss_cr_weights(t->n_r, t->radius, r, &off, w)) {
    return 0.0;
  }
  double v = 0.0;
  for (int k = 0; k < 4; ++k) {
    if (w[k] != 0.0) {
      v += w[k] * ss_cr_mix_at(m, t->profile, t->n_r, 1, (size_t)(off + k));
    }
  }
  return v;
}

double ss_table_radial_sp(const ss_table_radial *t, double rho, double r) {
  ss_cr_mix m;
  if (!(r > 0.0) || !rho_mix(t, rho, &m)) {
    return 0.0;
  }
  /* Cancel the 2 pi r of the stored marginal (pbrt-v3 TabulatedBSSRDF::Sr). */
  return fmax(0.0, profile_at(t, &m, r) / (2.0 * SS_PI * r));
}

double ss_table_radial_rho_eff(const ss_table_radial *t, double rho) {
  ss_cr_mix m;
  if (!rho_mix(t, rho, &m)) {
    return 0.0;
  }
  return ss_cr_mix_at(&m, t->cdf, t->n_r, 1, t->n_r - 1);
}

double ss_table_radial_sample(const ss_table_radial *t, double rho, double u) {
  ss_cr_mix m;
  if (!rho_mix(t, rho, &m)) {
    return -1.0;
  }
  double r = ss_cr_sample_mix(t->n_r, t->radius, &m, t->profile, 1, t->cdf, u, NULL, NULL);
  return isfinite(r) ? r : -1.0;
}

double ss_table_radial_pdf_area(const ss_table_radial *t, double rho, double r) {
  ss_cr_mix m;
  if (!(r > 0.0) || !rho_mix(t, rho, &m)) {
    return 0.0;
  }
  double total = ss_cr_mix_at(&m, t->cdf, t->n_r, 1, t->n_r - 1);
  if (!(total > 0.0)) {
    return 0.0;
  }
  return fmax(0.0, profile_at(t, &m, r) / (2.0 * SS_PI * r * total));
}

double ss_table_radial_invert(const ss_table_radial *t, double rho_eff) {
  return ss_cr_invert(t->n_rho, t->rho, t->rho_eff, rho_eff);
}

ss_status ss_subsurface_from_diffuse(const ss_table_radial *t, const double diffuse[3],
                                     const double mfp[3], double sigma_s[3], double sigma_a[3],
                                     ss_error *err) {
  for (int c = 0; c < 3; ++c) {
    if (!(diffuse[c] >= 0.0 && diffuse[c] <= 1.0) || !(mfp[c] > 0.0) || !isfinite(mfp[c])) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "subsurface from diffuse: channel %d: diffuse %g must lie in [0, 1] "
                          "and mean free path %g be > 0",
                          c, diffuse[c], mfp[c]);
    }
    double rho = ss_table_radial_invert(t, diffuse[c]);
    sigma_s[c] = rho / mfp[c];
    sigma_a[c] = (1.0 - rho) / mfp[c];
  }
  return SS_OK;
}
