/* The half-space's radial exitance profile for many single-scattering
 * albedos from one Monte Carlo run (Kienle1996, "white" Monte Carlo): paths are traced without
 * absorption in a medium of sigma_t = 1 behind a smooth boundary eta, with the Henyey-Greenstein
 * phase function of mean cosine g, and a path that leaves the medium after n scattering events
 * counts alpha^n for every albedo alpha, its exact survival probability under absorption. The
 * collimated unit-power beam enters at normal incidence at the origin, as in ss_halfspace_run,
 * whose radial profile for one albedo this reproduces.
 *
 * Radii are in units of the transport mean free path 1/sigma_t' of each
 * albedo (sigma_t' = 1 - g alpha for sigma_t = 1), so that one table serves
 * every medium of the same reduced albedo, eta and g: a medium with
 * transport coefficient sigma_t' has M(r) = sigma_t'^2 M_table(sigma_t' r). */
#ifndef SUBSURF_HALFSPACE_PROFILES_H
#define SUBSURF_HALFSPACE_PROFILES_H

#include "subsurf/halfspace.h"
#include "subsurf/progress.h"
#include "subsurf/status.h"

#include <signal.h>
#include <stdint.h>

#define SS_HALFSPACE_PROFILES_MAX_ALBEDOS 64

typedef struct {
  double eta, g;
  int n_albedo;
  double albedo[SS_HALFSPACE_PROFILES_MAX_ALBEDOS]; /* single-scattering albedos in (0, 1] */
  /* Bin 0 is [0, rmin), then rbins - 1 log-spaced bins up to rmax, in units
   * of 1/sigma_t' (as ss_halfspace_params' radial bins). */
  double rmin, rmax;
  int rbins;
  uint64_t paths, seed;
  uint64_t max_depth; /* a path is cut at this many scattering events */
  int threads;        /* 0: OpenMP's default */
  const volatile sig_atomic_t *cancel;
  ss_progress_fn progress; /* from one thread at a time */
  void *progress_ctx;
} ss_halfspace_profiles_params;

typedef struct {
  uint64_t paths, scatter_events;
  double seconds;
  int interrupted;
  ss_estimate truncated; /* power of the paths cut by max_depth (weight 1) */
  int n_albedo, rbins;
  double *r_lo, *r_hi;      /* bin edges in units of 1/sigma_t' */
  ss_estimate *reflectance; /* [n_albedo] */
  ss_estimate *radial;      /* [n_albedo][rbins]: exitance per unit area (in 1/sigma_t'^2) */
} ss_halfspace_profiles_result;

/* Defaults: eta 1.3, g 0, no albedo, rmin 0.01, rmax 300, 321 bins, 10^6
 * paths, seed 0, max_depth 10^5. */
void ss_halfspace_profiles_params_default(ss_halfspace_profiles_params *p);
ss_status ss_halfspace_profiles_run(const ss_halfspace_profiles_params *p,
                                    ss_halfspace_profiles_result **out, ss_error *err);
void ss_halfspace_profiles_result_destroy(ss_halfspace_profiles_result *r);

#endif
