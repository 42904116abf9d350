/* Log-log plots of radial exitance profiles (reference with error bars,
 * models as lines) through PLplot, like the figures of the papers. */
#ifndef SUBSURF_CLI_PROFILE_PLOT_H
#define SUBSURF_CLI_PROFILE_PLOT_H

#include "subsurf/halfspace.h"

/* 1 when PLplot can write `path` (.svg, .pdf or .ps), else 0. */
int ss_profile_plot_supported(const char *path);

/* Plots M(r) at the bin centres r[0..n) of the reference and of each model
 * (models[k][0..n)), into a temporary file renamed to `path` on success.
 * Returns 0, or -1 after printing "subsurf CMD: ..." on failure. */
int ss_profile_plot_write(const char *cmd, const char *path, const char *title, const double *r,
                          const ss_estimate *ref, int n, const double *const *models,
                          const char *const *names, int nmodels);

#endif
