/* The radial profile figure of `subsurf compare-halfspace`, drawn by PLplot
 * in the layout of the papers' figures (e.g. d'Eon 2012, Frisvad et al.
 * 2014): the exitance on log-log axes, the Monte Carlo reference as points
 * with one-standard-error bars, each model as a line; below it, each
 * model's relative error with the +-5% band the validation reports on.
 * The plugin libsubsurf_plplot.so (plplot_plugin.h). */
#include "cli/plplot_plugin.h"

#include <math.h>
#include <plplot.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* cmap0 indices. Models use Okabe & Ito's colour-blind-safe palette without
 * its yellow (invisible on white); line styles differ too, so that the
 * figure survives greyscale printing. */
enum { COL_BG = 0, COL_FG = 1, COL_GRID = 2, COL_MODEL = 3 };
static const int palette[][3] = {{0, 114, 178}, {213, 94, 0},   {0, 158, 115},  {204, 121, 167},
                                 {230, 159, 0}, {86, 180, 233}, {110, 110, 110}};
#define N_PALETTE ((int)(sizeof palette / sizeof palette[0]))
#define N_STYLES 4
/* A filled circle (Hershey glyph 850) for the reference's points. */
#define REF_SYMBOL "#(850)"

static int resolved(ss_estimate e) { return e.value > 0.0 && e.error <= 0.1 * e.value; }

static void set_colours(void) {
  plscmap0n(COL_MODEL + N_PALETTE);
  plscol0(COL_BG, 255, 255, 255);
  plscol0(COL_FG, 0, 0, 0);
  plscol0(COL_GRID, 215, 215, 215);
  for (int k = 0; k < N_PALETTE; ++k) {
    plscol0(COL_MODEL + k, palette[k][0], palette[k][1], palette[k][2]);
  }
}

static void model_pen(int k) {
  plcol0(COL_MODEL + k % N_PALETTE);
  pllsty(1 + k % N_STYLES);
  plwidth(2.0);
}

/* Light grid first, then the black frame, ticks and labels over it. */
static void frame(const char *xopt, const char *yopt) {
  plcol0(COL_GRID);
  pllsty(1);
  plwidth(0.5);
  plbox(strchr(xopt, 'l') ? "gl" : "g", 0.0, 0, strchr(yopt, 'l') ? "gl" : "g", 0.0, 0);
  plcol0(COL_FG);
  plwidth(1.0);
  plbox(xopt, 0.0, 0, yopt, 0.0, 0);
}

static void legend(const char *const *names, int nmodels) {
  int nl = nmodels + 1;
  PLINT *opt = calloc((size_t)nl, sizeof *opt), *colors = calloc((size_t)nl, sizeof *colors);
  PLINT *text_colors = calloc((size_t)nl, sizeof *text_colors);
  PLINT *styles = calloc((size_t)nl, sizeof *styles);
  PLINT *numbers = calloc((size_t)nl, sizeof *numbers);
  PLFLT *widths = calloc((size_t)nl, sizeof *widths), *scales = calloc((size_t)nl, sizeof *scales);
  const char **text = calloc((size_t)nl, sizeof *text);
  const char **symbols = calloc((size_t)nl, sizeof *symbols);
  if (opt && colors && text_colors && styles && numbers && widths && scales && text && symbols) {
    for (int k = 0; k < nl; ++k) {
      opt[k] = k == 0 ? PL_LEGEND_SYMBOL : PL_LEGEND_LINE;
      colors[k] = k == 0 ? COL_FG : COL_MODEL + (k - 1) % N_PALETTE;
      text_colors[k] = COL_FG;
      styles[k] = k == 0 ? 1 : 1 + (k - 1) % N_STYLES;
      widths[k] = 2.0;
      scales[k] = 1.0;
      numbers[k] = 1;
      text[k] = k == 0 ? "reference (Monte Carlo, 1 s.e.)" : names[k - 1];
      symbols[k] = REF_SYMBOL;
    }
    PLFLT lw, lh;
    pllsty(1);
    plwidth(1.0);
    pllegend(&lw, &lh, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
             PL_POSITION_LEFT | PL_POSITION_BOTTOM | PL_POSITION_INSIDE, 0.02, 0.03, 0.08, COL_BG,
             COL_FG, 1, 0, 0, nl, opt, 0.8, 0.8, 2.0, 0.0, text_colors, text, NULL, NULL, NULL,
             NULL, colors, styles, widths, colors, scales, numbers, symbols);
  }
  free(opt);
  free(colors);
  free(text_colors);
  free(styles);
  free(numbers);
  free(widths);
  free(scales);
  free(text);
  free(symbols);
}

/* The smallest of 10, 20, 50, 100 (%) above every resolved relative error;
 * larger errors are clipped at 100%. */
static double error_range(const ss_estimate *ref, int n, const double *const *models, int nmodels) {
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < nmodels && resolved(ref[i]); ++k) {
      worst = fmax(worst, 100.0 * fabs(models[k][i] / ref[i].value - 1.0));
    }
  }
  static const double ranges[] = {10.0, 20.0, 50.0};
  for (size_t j = 0; j < sizeof ranges / sizeof ranges[0]; ++j) {
    if (worst <= ranges[j]) {
      return ranges[j];
    }
  }
  return 100.0;
}

static void draw(const char *title, const double *r, const ss_estimate *ref, int n,
                 const double *const *models, const char *const *names, int nmodels, double *x,
                 double *y, double *lo, double *hi) {
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
  double x0 = log10(r[0]) - 0.05, x1 = log10(r[n - 1]) + 0.05;

  /* Upper panel: the profiles. */
  pladv(0);
  plvpor(0.13, 0.94, 0.42, 0.92);
  plwind(x0, x1, log10(ymin) - 0.3, log10(ymax) + 0.3);
  frame("bclst", "bclnstv");
  plmtex("l", 5.0, 0.5, 0.5, "exitance M(r) per unit power");
  plmtex("t", 1.2, 0.5, 0.5, title);
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
  for (int k = 0; k < nmodels; ++k) {
    int mk = 0;
    double *xk = lo + m, *yk = hi + m; /* scratch beyond the reference's points */
    for (int i = 0; i < n; ++i) {
      if (models[k][i] > 0.0) {
        xk[mk] = log10(r[i]);
        yk[mk] = log10(models[k][i]);
        ++mk;
      }
    }
    model_pen(k);
    plline(mk, xk, yk);
  }
  plcol0(COL_FG);
  pllsty(1);
  plwidth(1.0);
  plerry(m, x, lo, hi);
  plssym(0.0, 0.6);
  plstring(m, x, y, REF_SYMBOL);
  legend(names, nmodels);

  /* Lower panel: relative errors over the bins the reference resolves. */
  double range = error_range(ref, n, models, nmodels);
  plvpor(0.13, 0.94, 0.10, 0.36);
  plwind(x0, x1, -range, range);
  frame("bclnst", "bcnstv");
  plmtex("b", 2.8, 0.5, 0.5, "radius r (1/sigma_t = 1 mean free path)");
  plmtex("l", 5.0, 0.5, 0.5, "model/ref - 1 (%)");
  plmtex("r", 1.5, 0.5, 0.5, "dashed: \u00b15%");
  double bx[2] = {x0, x1}, by[2];
  plcol0(COL_FG);
  plwidth(1.0);
  pllsty(1);
  by[0] = by[1] = 0.0;
  plline(2, bx, by);
  pllsty(2);
  for (int s = -1; s <= 1; s += 2) {
    by[0] = by[1] = 5.0 * s;
    plline(2, bx, by);
  }
  pllsty(1);
  m = 0;
  for (int i = 0; i < n; ++i) {
    if (resolved(ref[i])) {
      double rel = 100.0 * ref[i].error / ref[i].value;
      x[m] = log10(r[i]);
      lo[m] = -rel;
      hi[m] = rel;
      ++m;
    }
  }
  plerry(m, x, lo, hi);
  for (int k = 0; k < nmodels; ++k) {
    m = 0;
    for (int i = 0; i < n; ++i) {
      if (resolved(ref[i])) {
        x[m] = log10(r[i]);
        y[m] = 100.0 * (models[k][i] / ref[i].value - 1.0);
        ++m;
      }
    }
    model_pen(k);
    plline(m, x, y);
  }
}

/* PLplot ends the process on a fatal error (plexit prints, then exits)
 * unless its exit handler does not return: the handler keeps the message
 * and jumps back into plot_to, which reports it. Non-fatal errors (plabort)
 * go to plot_error through plsError instead of stderr. */
static jmp_buf plplot_exit;
static char plplot_message[256];
static PLINT plot_errcode;
static char plot_error[1024];

static int on_plplot_exit(const char *msg) {
  snprintf(plplot_message, sizeof plplot_message, "%s", msg && *msg ? msg : "PLplot error");
  longjmp(plplot_exit, 1);
}

static void one_line(char *s) {
  for (char *p = s; *p; ++p) {
    if (*p == '\n') {
      *p = ' ';
    }
  }
}

/* Draws into `file` with PLplot; 0, or -1 with the reason in plplot_message. */
static int plot_to(const char *device, const char *file, const ss_plot_data *d, double *x,
                   double *y, double *lo, double *hi) {
  plplot_message[0] = plot_error[0] = '\0';
  plot_errcode = 0;
  plsexit(on_plplot_exit);
  if (setjmp(plplot_exit)) {
    plsexit(NULL);
    one_line(plplot_message);
    return -1;
  }
  plsdev(device);
  plsfnam(file);
  plsError(&plot_errcode, plot_error);
  set_colours();
  plinit();
  draw(d->title, d->r, d->ref, d->n, d->models, d->names, d->nmodels, x, y, lo, hi);
  plend();
  plsexit(NULL);
  if (plot_errcode) {
    snprintf(plplot_message, sizeof plplot_message, "%s", plot_error);
    one_line(plplot_message);
    return -1;
  }
  return 0;
}

int ss_plplot_plugin_draw(const char *device, const char *file, const ss_plot_data *d,
                          char *message, size_t size) {
  /* lo and hi hold 2n: the model curves of the upper panel use their tails. */
  size_t n = (size_t)d->n;
  double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
  double *lo = malloc(2 * n * sizeof *lo), *hi = malloc(2 * n * sizeof *hi);
  int rc = -1;
  if (!x || !y || !lo || !hi) {
    snprintf(message, size, "out of memory for the plot");
  } else if ((rc = plot_to(device, file, d, x, y, lo, hi)) != 0) {
    snprintf(message, size, "%s", plplot_message);
  }
  free(x);
  free(y);
  free(lo);
  free(hi);
  return rc;
}
