/* Measuring a medium from the radial exitance profile around a narrow beam
 * (Jensen2001 sec. 3): sigma_a and sigma_s' of one colour channel, and an
 * unknown overall scale (exposure x Fresnel), fitted by non-linear least
 * squares (GSL's Levenberg-Marquardt trust region) to the profile a model
 * predicts for a unit-power beam at normal incidence on a half-space:
 *
 *   exact          the half-space Monte Carlo profile (profile_table.h)
 *   dipole         Jensen2001 eq. 4 (the `dipole` BSSRDF)
 *   better-dipole  dEon2014 (the `better-dipole` BSSRDF)
 *   pbd            Habel2013 (the `pbd` BSSRDF, single scattering included)
 *
 * Points with standard errors weigh by them; points without are fitted in
 * the logarithm (each with the same relative error). The parameters are
 * fitted as logarithms (so they stay positive); their standard errors come
 * from the Jacobian at the optimum (the covariance (J^T J)^-1, scaled by
 * chi^2 / dof when the data carry no standard errors) and, optionally, from
 * a bootstrap over the data points. docs/fit.md. */
#ifndef SUBSURF_PROFILE_FIT_H
#define SUBSURF_PROFILE_FIT_H

#include "subsurf/profile_table.h"
#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

typedef enum {
  SS_FIT_EXACT,
  SS_FIT_DIPOLE,
  SS_FIT_BETTER_DIPOLE,
  SS_FIT_PBD,
} ss_fit_model;

#define SS_FIT_MODEL_NAMES "exact, dipole, better-dipole, pbd"

/* The model of a name ("exact", "dipole", "better-dipole", "pbd"); -1 if none. */
int ss_fit_model_from_name(const char *name);
const char *ss_fit_model_name(ss_fit_model m);

/* One channel's measured profile: exitance at radii r (scene units, > 0,
 * increasing), with standard errors (NULL: unknown). With r_lo and r_hi
 * (both or neither), point i is the average over the annulus r_lo[i] <= r <
 * r_hi[i] (which holds r[i]), and the models are averaged over it too, as
 * the half-space reference's radial bins need. */
typedef struct {
  size_t n;
  const double *r, *value, *error;
  const double *r_lo, *r_hi;
} ss_fit_data;

typedef struct {
  ss_fit_model model;
  double eta, g; /* the sample's boundary and Henyey-Greenstein mean cosine */
  /* The exact model's table (its eta and g must be the sample's); NULL: the
   * built-in table. */
  const ss_profile_table *table;
  int absolute; /* 1: the scale is 1 (the data are per unit incident power) */
  /* The radii used: [rmin, rmax]. rmin < 0: automatic, points nearer the
   * beam than rmin_mfp transport mean free paths of the fitted medium are
   * left out (the fit is repeated until the set is stable); rmax <= 0: all. */
  double rmin, rmax, rmin_mfp;
  /* Initial guess (<= 0: a search over a grid of albedos and mean free paths). */
  double sigma_a0, sigma_s_prime0;
  int max_iter;
  int bootstrap; /* resamples of the data points (0: none) */
  uint64_t seed; /* of the bootstrap */
} ss_fit_params;

typedef struct {
  double sigma_a, sigma_s_prime, scale;
  double sigma_a_stderr, sigma_s_prime_stderr, scale_stderr; /* from the Jacobian */
  /* From the bootstrap (NaN without one). */
  double sigma_a_boot_stderr, sigma_s_prime_boot_stderr;
  double alpha_prime, mfp; /* sigma_s' / sigma_t' and 1 / sigma_t' */
  double chi2;             /* sum of squared weighted residuals */
  int dof;                 /* points used - parameters */
  double rmin, rmax;       /* the range used */
  size_t used;             /* points used */
  int iterations;
  /* 0 when the optimiser stopped at its iteration limit or at the edge of
   * the exact table's albedo range: the result is the last iterate. */
  int converged;
  int at_table_edge;
} ss_fit_result;

/* Defaults: exact model, eta 1.3, g 0, built-in table, scale fitted,
 * rmin automatic at 1 transport mean free path, rmax all, automatic
 * initial guess, 200 iterations, no bootstrap, seed 0. */
void ss_fit_params_default(ss_fit_params *p);

/* Checks the data (finite, radii > 0 and increasing, annuli holding their
 * radii, values >= 0 and > 0 without errors, errors > 0) and the
 * parameters, then fits. Fewer usable
 * points than parameters, or a fit that fails, is an error. */
ss_status ss_fit_run(const ss_fit_params *p, const ss_fit_data *d, ss_fit_result *out,
                     ss_error *err);

/* The model's profile for sigma_a, sigma_s' and a scale at n radii (r_lo
 * and r_hi NULL) or averaged over n annuli (for plots and residuals). */
ss_status ss_fit_eval(const ss_fit_params *p, double sigma_a, double sigma_s_prime, double scale,
                      const double *r, const double *r_lo, const double *r_hi, size_t n,
                      double *out, ss_error *err);

#endif
