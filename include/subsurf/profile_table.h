/* The exact radial exitance profile of a half-space lit by a narrow beam at
 * normal incidence, tabulated over the reduced albedo for one boundary eta
 * and one Henyey-Greenstein g, from the half-space Monte Carlo reference
 * (halfspace_profiles.h): what `subsurf fit --model exact` fits measured
 * profiles with (docs/fit.md).
 *
 * Radii are in units of the transport mean free path 1/sigma_t', so that one
 * table serves every medium of the same reduced albedo alpha' = sigma_s' /
 * sigma_t': a medium of sigma_t' has M(r) = sigma_t'^2 M_table(alpha',
 * sigma_t' r), per unit incident power (the entry's Fresnel loss included).
 *
 * Text format (version 1): comment lines start with '#'; then
 * `subsurf-profile-table 1`, `eta E`, `g G`, `paths N`, `u NU u_1..u_NU`
 * (u = sqrt(1 - alpha'), strictly increasing in (0, 1)), `rho NE e_1..e_NE`
 * (the NE - 1 bins' edges, strictly increasing, > 0), one line per u
 * `curve U M_1..M_NB E_1..E_NB` (annulus averages and their standard
 * errors, NB = NE - 1), and the last line `crc32 XXXXXXXX`, the CRC-32
 * (zlib) of every byte before it.
 *
 * Evaluation: each bin is divided by the classical dipole's profile of the
 * same alpha' and eta (Jensen2001 eq. 4, with its Fresnel factors) averaged
 * over the same annulus, a ratio of order one that varies slowly; its
 * logarithm is interpolated bicubically over (ln rho at the bins' geometric
 * centres, u) and multiplies the dipole's point value. Bins whose relative
 * standard error exceeds SS_PROFILE_TABLE_MAX_REL_ERROR (or are empty) take
 * the ratio of the last reliable bin of their curve, as do radii beyond the
 * table's bins; the dipole carries the profile's shape there. */
#ifndef SUBSURF_PROFILE_TABLE_H
#define SUBSURF_PROFILE_TABLE_H

#include "subsurf/progress.h"
#include "subsurf/status.h"

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#define SS_PROFILE_TABLE_VERSION 1
#define SS_PROFILE_TABLE_MAX_U 64
#define SS_PROFILE_TABLE_MAX_BINS 512
#define SS_PROFILE_TABLE_MAX_REL_ERROR 0.1

typedef struct ss_profile_table ss_profile_table;

typedef struct {
  double eta, g;
  uint64_t paths, seed;
  int threads;
  const volatile sig_atomic_t *cancel;
  ss_progress_fn progress;
  void *progress_ctx;
} ss_profile_table_build_params;

/* Defaults: eta 1.3, g 0, 10^6 paths, seed 1. */
void ss_profile_table_build_params_default(ss_profile_table_build_params *p);

/* Runs the reference over the built-in grids (docs/fit.md) and returns the
 * table's text (malloc'd, *size bytes, checksum included). Interrupted:
 * SS_ERR_INTERRUPTED and no text. */
ss_status ss_profile_table_build(const ss_profile_table_build_params *p, char **text, size_t *size,
                                 ss_error *err);

/* Parses a table's text (`label` names it in messages, "FILE:LINE: ..."). */
ss_status ss_profile_table_parse(const char *text, size_t size, const char *label,
                                 ss_profile_table **out, ss_error *err);
/* Reads a regular file of at most 4 MiB and parses it. */
ss_status ss_profile_table_load(const char *path, ss_profile_table **out, ss_error *err);
void ss_profile_table_destroy(ss_profile_table *t);

/* The shipped table (eta 1.3, g 0; data/halfspace_profiles.txt), compiled
 * into the library and parsed on first use; thread-safe; never destroyed. */
ss_status ss_profile_table_builtin(const ss_profile_table **out, ss_error *err);

double ss_profile_table_eta(const ss_profile_table *t);
double ss_profile_table_g(const ss_profile_table *t);
/* The range of reduced albedos the table covers: alpha' = 1 - u^2 for u
 * between its first and last node. */
void ss_profile_table_albedo_range(const ss_profile_table *t, double *lo, double *hi);

/* M_table(alpha', rho) at n radii rho[] (units of 1/sigma_t'), per unit
 * incident power and unit area in 1/sigma_t'^2; alpha' is clamped to the
 * table's range. */
void ss_profile_table_eval(const ss_profile_table *t, double alpha_prime, const double *rho,
                           size_t n, double *out);

#endif
