/* A minimal SVG line plot with a logarithmic y axis for the forward
 * scattering dipole validation (test_fwddip_vs_halfspace.c): a grid of
 * panels, each with several named curves, colour-blind-safe colours and
 * dashes per series. Values <= 0 break a curve. */
#ifndef SUBSURF_TESTS_FWDDIP_PLOT_H
#define SUBSURF_TESTS_FWDDIP_PLOT_H

#include <math.h>
#include <stdio.h>

#define PLOT_MAX_SERIES 8
#define PLOT_MAX_POINTS 64

typedef struct {
  const char *title;
  int n_series, n_points;
  const char *name[PLOT_MAX_SERIES];
  double x[PLOT_MAX_POINTS];
  double y[PLOT_MAX_SERIES][PLOT_MAX_POINTS];
} plot_panel;

static const char *const plot_colour[PLOT_MAX_SERIES] = {
    "#000000", "#0072b2", "#009e73", "#d55e00", "#e69f00", "#cc79a7", "#56b4e9", "#777777"};
static const char *const plot_dash[PLOT_MAX_SERIES] = {"",    "6,3", "2,2",  "8,3,2,3",
                                                       "4,4", "1,3", "10,4", "3,6"};

static void plot_panel_svg(FILE *f, const plot_panel *p, double ox, double oy, double w, double h,
                           const char *xlabel) {
  double xmin = p->x[0], xmax = p->x[p->n_points - 1], ymin = INFINITY, ymax = 0.0;
  for (int s = 0; s < p->n_series; ++s) {
    for (int i = 0; i < p->n_points; ++i) {
      if (p->y[s][i] > 0.0) {
        ymin = fmin(ymin, p->y[s][i]);
        ymax = fmax(ymax, p->y[s][i]);
      }
    }
  }
  if (!(ymax > 0.0)) {
    return;
  }
  double lmin = floor(log10(ymin)), lmax = ceil(log10(ymax));
  if (lmax - lmin > 6) {
    lmin = lmax - 6;
  }
  if (lmax <= lmin) {
    lmax = lmin + 1;
  }
  fprintf(f, "<rect x='%g' y='%g' width='%g' height='%g' fill='none' stroke='black'/>\n", ox, oy, w,
          h);
  fprintf(f, "<text x='%g' y='%g' font-size='12' text-anchor='middle'>%s</text>\n", ox + w / 2,
          oy - 6, p->title);
  for (double l = lmin; l <= lmax; l += 1.0) {
    double yy = oy + h - h * (l - lmin) / (lmax - lmin);
    fprintf(f, "<line x1='%g' y1='%g' x2='%g' y2='%g' stroke='#dddddd'/>\n", ox, yy, ox + w, yy);
    fprintf(f, "<text x='%g' y='%g' font-size='9' text-anchor='end'>1e%d</text>\n", ox - 3, yy + 3,
            (int)l);
  }
  for (int k = 0; k <= 4; ++k) {
    double xv = xmin + (xmax - xmin) * k / 4, xx = ox + w * k / 4;
    fprintf(f, "<text x='%g' y='%g' font-size='9' text-anchor='middle'>%g</text>\n", xx,
            oy + h + 12, xv);
  }
  fprintf(f, "<text x='%g' y='%g' font-size='10' text-anchor='middle'>%s</text>\n", ox + w / 2,
          oy + h + 24, xlabel);
  for (int s = 0; s < p->n_series; ++s) {
    fprintf(f,
            "<polyline fill='none' stroke='%s' stroke-width='1.4' stroke-dasharray='%s' "
            "points='",
            plot_colour[s], plot_dash[s]);
    for (int i = 0; i < p->n_points; ++i) {
      double v = p->y[s][i];
      if (!(v > 0.0) || log10(v) < lmin) {
        continue;
      }
      double xx = ox + w * (p->x[i] - xmin) / (xmax - xmin);
      double yy = oy + h - h * (log10(v) - lmin) / (lmax - lmin);
      fprintf(f, "%.1f,%.1f ", xx, yy);
    }
    fprintf(f, "'/>\n");
  }
}

/* Panels in rows of `cols`, with one legend (the first panel's names). */
static int plot_write_svg(const char *path, const plot_panel *panels, int n, int cols,
                          const char *xlabel) {
  FILE *f = fopen(path, "w");
  if (!f) {
    return -1;
  }
  const double pw = 260, ph = 180, mx = 60, my = 40;
  int rows = (n + cols - 1) / cols;
  double width = cols * (pw + mx) + 170, height = rows * (ph + my + 20) + 20;
  fprintf(f,
          "<svg xmlns='http://www.w3.org/2000/svg' width='%g' height='%g' "
          "font-family='sans-serif'>\n<rect width='100%%' height='100%%' fill='white'/>\n",
          width, height);
  for (int i = 0; i < n; ++i) {
    plot_panel_svg(f, &panels[i], mx + (i % cols) * (pw + mx), my + (i / cols) * (ph + my + 20), pw,
                   ph, xlabel);
  }
  double lx = cols * (pw + mx) + 10;
  for (int s = 0; s < panels[0].n_series; ++s) {
    double ly = my + 16 * s;
    fprintf(f,
            "<line x1='%g' y1='%g' x2='%g' y2='%g' stroke='%s' stroke-width='1.4' "
            "stroke-dasharray='%s'/><text x='%g' y='%g' font-size='10'>%s</text>\n",
            lx, ly, lx + 30, ly, plot_colour[s], plot_dash[s], lx + 34, ly + 3, panels[0].name[s]);
  }
  fprintf(f, "</svg>\n");
  return fclose(f);
}

#endif
