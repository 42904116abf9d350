#include "cli/profile_plot.h"

#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *device_for(const char *path) {
  const char *dot = strrchr(path, '.');
  if (!dot) {
    return NULL;
  }
  if (!strcmp(dot, ".svg")) {
    return "svg";
  }
  if (!strcmp(dot, ".pdf")) {
    return "pdf";
  }
  if (!strcmp(dot, ".ps")) {
    return "psc";
  }
  return NULL;
}

int ss_profile_plot_supported(const char *path) { return device_for(path) != NULL; }

int ss_profile_plot_write(const char *cmd, const char *path, const char *title, const double *r,
                          const ss_estimate *ref, int n, const double *const *models,
                          const char *const *names, int nmodels) {
  size_t len = strlen(path) + 32;
  char *tmp = malloc(len);
  double *x = malloc((size_t)n * sizeof *x), *y = malloc((size_t)n * sizeof *y);
  double *lo = malloc((size_t)n * sizeof *lo), *hi = malloc((size_t)n * sizeof *hi);
  if (!tmp || !x || !y || !lo || !hi) {
    fprintf(stderr, "subsurf %s: out of memory for the plot\n", cmd);
    free(tmp);
    free(x);
    free(y);
    free(lo);
    free(hi);
    return -1;
  }
  snprintf(tmp, len, "%s.tmp-%ld", path, (long)getpid());
  /* Axis range over every positive value. */
  double ymin = INFINITY, ymax = -INFINITY;
  for (int i = 0; i < n; ++i) {
    if (ref[i].value > 0.0) {
      ymin = fmin(ymin, ref[i].value);
      ymax = fmax(ymax, ref[i].value);
    }
    for (int k = 0; k < nmodels; ++k) {
      if (models[k][i] > 0.0) {
        ymax = fmax(ymax, models[k][i]);
      }
    }
  }
  if (!isfinite(ymin)) {
    ymin = 1e-6;
    ymax = 1.0;
  }
  ymin = fmax(ymin, ymax * 1e-12);
  plsdev(device_for(path));
  plsfnam(tmp);
  plscolbg(255, 255, 255);
  plinit();
  plcol0(15);
  plenv(log10(r[0]), log10(r[n - 1]), log10(ymin) - 0.2, log10(ymax) + 0.2, 0, 30);
  pllab("r", "exitance M(r) per unit power", title);
  /* The reference: points with one-standard-error bars. */
  int m = 0;
  for (int i = 0; i < n; ++i) {
    if (ref[i].value > 0.0) {
      x[m] = log10(r[i]);
      y[m] = log10(ref[i].value);
      lo[m] = log10(fmax(ref[i].value - ref[i].error, ref[i].value * 1e-3));
      hi[m] = log10(ref[i].value + ref[i].error);
      ++m;
    }
  }
  plcol0(1);
  plpoin(m, x, y, 17);
  plerry(m, x, lo, hi);
  for (int k = 0; k < nmodels; ++k) {
    m = 0;
    for (int i = 0; i < n; ++i) {
      if (models[k][i] > 0.0) {
        x[m] = log10(r[i]);
        y[m] = log10(models[k][i]);
        ++m;
      }
    }
    plcol0(2 + k % 13);
    plwidth(2.0);
    plline(m, x, y);
  }
  /* Legend: the reference's symbol, then one line per model. */
  int nl = nmodels + 1;
  PLINT *opt = calloc((size_t)nl, sizeof *opt), *colors = calloc((size_t)nl, sizeof *colors);
  PLINT *styles = calloc((size_t)nl, sizeof *styles), *numbers = calloc((size_t)nl, sizeof *numbers);
  PLFLT *widths = calloc((size_t)nl, sizeof *widths), *scales = calloc((size_t)nl, sizeof *scales);
  const char **text = calloc((size_t)nl, sizeof *text), **symbols = calloc((size_t)nl, sizeof *symbols);
  if (opt && colors && styles && numbers && widths && scales && text && symbols) {
    for (int k = 0; k < nl; ++k) {
      opt[k] = k == 0 ? PL_LEGEND_SYMBOL : PL_LEGEND_LINE;
      colors[k] = k == 0 ? 1 : 2 + (k - 1) % 13;
      styles[k] = 1;
      widths[k] = 2.0;
      scales[k] = 1.0;
      numbers[k] = 1;
      text[k] = k == 0 ? "halfspace (Monte Carlo)" : names[k - 1];
      symbols[k] = "#(728)";
    }
    PLFLT lw, lh;
    pllegend(&lw, &lh, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, PL_POSITION_RIGHT | PL_POSITION_TOP,
             0.02, 0.02, 0.1, 0, 15, 1, 0, 0, nl, opt, 1.0, 0.8, 2.0, 0.0, colors, text, NULL,
             NULL, NULL, NULL, colors, styles, widths, colors, scales, numbers, symbols);
  }
  plend();
  free(opt);
  free(colors);
  free(styles);
  free(numbers);
  free(widths);
  free(scales);
  free(text);
  free(symbols);
  int rc = 0;
  if (access(tmp, F_OK) != 0 || rename(tmp, path) != 0) {
    fprintf(stderr, "subsurf %s: --plot: could not write '%s'\n", cmd, path);
    remove(tmp);
    rc = -1;
  }
  free(tmp);
  free(x);
  free(y);
  free(lo);
  free(hi);
  return rc;
}
