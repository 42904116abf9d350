/* Log-log plots of radial exitance profiles (reference with error bars,
 * models as lines) through PLplot, like the figures of the papers. */
#ifndef SUBSURF_CLI_PROFILE_PLOT_H
#define SUBSURF_CLI_PROFILE_PLOT_H

#include "subsurf/halfspace.h"

/* 1 when PLplot can write `path` (.svg, .pdf or .ps), else 0. */
int ss_profile_plot_supported(const char *path);

/* Opens the PLplot plugin (plplot_plugin.h), so that a command finds it
 * missing before its work rather than after: 0, or -1 after printing one
 * line "subsurf CMD: --plot: ...". */
int ss_profile_plot_ready(const char *cmd);

/* Plots M(r) at the bin centres r[0..n) of the reference and of each model
 * (models[k][0..n)). The output is checked first, PLplot draws into a
 * private temporary file (its fatal errors come back here instead of ending
 * the process), and the result goes to `path` as core/atomic_file.h writes
 * outputs. Returns 0, or -1 after printing one line "subsurf CMD: --plot:
 * ..." on failure, with nothing written. */
int ss_profile_plot_write(const char *cmd, const char *path, const char *title, const double *r,
                          const ss_estimate *ref, int n, const double *const *models,
                          const char *const *names, int nmodels);

#endif
