/* The grid on which tests/validate/ compares BSSRDF models with the exact
 * half-space Monte Carlo reference: index matched and
 * eta = 1.33, albedo 0.5 to 0.999, normal and 60 degree incidence. Shared so
 * that every table of docs/models.md quotes the same reference runs (same
 * parameters and seed, hence bit-identical references). */
#ifndef SUBSURF_TESTS_HALFSPACE_GRID_H
#define SUBSURF_TESTS_HALFSPACE_GRID_H

#include "subsurf/bssrdf.h"
#include "subsurf/halfspace.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define GRID_ETAS 2
#define GRID_THETAS 2
#define GRID_ALBEDOS 4
#define GRID_MAX_BINS 64

static const double grid_eta[GRID_ETAS] = {1.0, 1.33};
static const double grid_theta[GRID_THETAS] = {0.0, 60.0};
static const double grid_albedo[GRID_ALBEDOS] = {0.5, 0.9, 0.99, 0.999};

/* sigma_t = 1, isotropic; 2e5 paths give standard errors of 0.05-0.2% on R.
 * 40 radial bins from 0.02 to 8 diffusion lengths (at most 40 mean free
 * paths), where the reference still resolves the profile. */
static inline void grid_params(int e, int t, int a, ss_halfspace_params *p) {
  ss_halfspace_params_default(p);
  p->medium.sigma_s = ss_rgb_gray(grid_albedo[a]);
  p->medium.sigma_a = ss_rgb_gray(1.0 - grid_albedo[a]);
  p->eta = grid_eta[e];
  p->theta_i = grid_theta[t] * SS_PI / 180.0;
  p->paths = 200000;
  p->seed = 17;
  p->rbins = 40;
  p->rmin = 0.02;
  p->rmax = fmin(40.0, 8.0 / sqrt(3.0 * p->medium.sigma_a.c[0]));
}

/* The total reflectance and annulus-averaged exitance on the reference's
 * bins of a model, or of the sum of two models written "a+b" (e.g.
 * "dipole+single", Jensen et al.'s S_d + S^(1)). `gwc_table`, when not NULL,
 * is the table file the table-gwc model loads instead of building its table.
 * Returns SS_OK, or the model's refusal of these parameters. */
static inline ss_status grid_predict(const char *name, const ss_halfspace_params *p,
                                     const ss_halfspace_result *ref, const char *gwc_table,
                                     double *total, double *radial, ss_error *err) {
  char parts[2][32] = {{0}};
  const char *plus = strchr(name, '+');
  if (plus) {
    snprintf(parts[0], sizeof parts[0], "%.*s", (int)(plus - name), name);
    snprintf(parts[1], sizeof parts[1], "%s", plus + 1);
  } else {
    snprintf(parts[0], sizeof parts[0], "%s", name);
  }
  *total = 0.0;
  for (int i = 0; i < ref->rbins; ++i) {
    radial[i] = 0.0;
  }
  for (int k = 0; k < 2 && parts[k][0]; ++k) {
    ss_bssrdf_params bp;
    ss_bssrdf_params_default(&bp);
    ss_bssrdf_params_set_gray(&bp, p->medium.sigma_s.c[0], p->medium.sigma_a.c[0], 0.0);
    bp.eta = p->eta;
    ss_status st = SS_OK;
    if (!strcmp(parts[k], "table-gwc")) {
      st = ss_bssrdf_params_set_option(&bp, ss_bssrdf_model_find("table-gwc"), "table", gwc_table,
                                       err);
    }
    ss_bssrdf *b = NULL;
    st = st == SS_OK ? ss_bssrdf_create(parts[k], &bp, &b, err) : st;
    if (st != SS_OK) {
      return st;
    }
    double v[SS_BSSRDF_CHANNELS], cos_i = cos(p->theta_i);
    ss_bssrdf_total_reflectance(b, cos_i, v);
    *total += v[0];
    for (int i = 0; i < ref->rbins; ++i) {
      ss_bssrdf_radial_average(b, cos_i, ref->r_lo[i], ref->r_hi[i], v);
      radial[i] += v[0];
    }
    ss_bssrdf_destroy(b);
  }
  return SS_OK;
}

/* Mean relative profile error over the bins with r >= r_from that the
 * reference resolves (standard error below 10% of the value); `bins`
 * receives how many were compared (0: the mean is 0). */
static inline double grid_profile_error(const ss_halfspace_result *ref, const double *ref_value,
                                        const double *model, double r_from, int *bins) {
  double sum = 0.0;
  *bins = 0;
  for (int i = 0; i < ref->rbins; ++i) {
    double v = ref_value[i];
    if (ref->r_lo[i] < r_from || !(v > 0.0) || ref->radial[i].error > 0.1 * v) {
      continue;
    }
    sum += fabs(model[i] / v - 1.0);
    (*bins)++;
  }
  return *bins ? sum / *bins : 0.0;
}

#endif
