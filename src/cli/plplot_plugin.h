/* The PLplot figure of profile_plot.h as a plugin, libsubsurf_plplot.so
 * (plugins/plplot_plugin.c), opened by `--plot` (io/plugin.h) instead of
 * linked: libplplot and the ten libraries it pulls in cost every subsurf
 * process ~8 ms of dynamic loading (bench/RESULTS.md). Only plain
 * arrays cross this boundary; the plugin calls nothing of libsubsurf. */
#ifndef SUBSURF_CLI_PLPLOT_PLUGIN_H
#define SUBSURF_CLI_PLPLOT_PLUGIN_H

#include "subsurf/halfspace.h"

#include <stddef.h>

#define SS_PLPLOT_PLUGIN_FILE "libsubsurf_plplot.so"

/* The figure's content: M(r) at the bin centres r[0..n) of the reference
 * and of each model (models[k][0..n)). */
typedef struct {
  const char *title;
  const double *r;
  const ss_estimate *ref;
  int n;
  const double *const *models;
  const char *const *names;
  int nmodels;
} ss_plot_data;

/* Draws the figure with PLplot's `device` ("svg", "pdf", "psc") into
 * `file`: 0, or -1 with one line saying why in message[0..size). PLplot's
 * fatal errors come back here instead of ending the process. */
typedef int ss_plplot_draw_fn(const char *device, const char *file, const ss_plot_data *d,
                              char *message, size_t size);

ss_plplot_draw_fn ss_plplot_plugin_draw;

#endif
