/* `subsurf compare`'s plots as SVG written directly (compare_scene.h): the
 * convergence plot (relMSE against time, log-log, one line per method), a
 * bar chart of the mean ratio to the reference per channel, and the colour
 * bar of the error maps (error_map.h). Plain SVG rather than PLplot's SVG
 * driver: a few kilobytes that the HTML report shows as they are, with the
 * method names as text and a tooltip per point, no fonts or global plotting
 * state, and files written atomically like every other output. */
#include "cli/compare_scene.h"
#include "cli/text_buf.h"

#include "subsurf/error_map.h"
#include "subsurf/image_io.h"

#include <math.h>
#include <stdio.h>

#define WIDTH 720
#define HEIGHT 420
#define LEFT 80
#define RIGHT 200 /* room for the legend */
#define TOP 30
#define BOTTOM 60

static const char *const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                      "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};

const char *ss_compare_method_colour(int i) {
  return palette[i % (int)(sizeof palette / sizeof palette[0])];
}

static void svg_begin(ss_text_buf *b, int w, int h, const char *title) {
  ss_text_printf(b,
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
                 "viewBox=\"0 0 %d %d\" font-family=\"sans-serif\" font-size=\"12\">\n"
                 "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n<title>",
                 w, h, w, h, w, h);
  ss_text_escaped(b, title);
  ss_text_printf(b,
                 "</title>\n<text x=\"%d\" y=\"18\" text-anchor=\"middle\" "
                 "font-size=\"14\">",
                 w / 2);
  ss_text_escaped(b, title);
  ss_text_printf(b, "</text>\n");
}

/* A log10 axis over [lo, hi] decades. */
typedef struct {
  double lo, hi;
} log_axis;

static log_axis log_axis_of(double min, double max) {
  log_axis a = {floor(log10(min)), ceil(log10(max))};
  if (a.hi <= a.lo) {
    a.hi = a.lo + 1.0;
  }
  return a;
}

static double log_pos(log_axis a, double v, double from, double to) {
  return from + (log10(v) - a.lo) / (a.hi - a.lo) * (to - from);
}

static void plot_frame(ss_text_buf *b, const char *xlabel, const char *ylabel) {
  const int pw = WIDTH - LEFT - RIGHT, ph = HEIGHT - TOP - BOTTOM;
  ss_text_printf(b,
                 "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" "
                 "stroke=\"black\"/>\n"
                 "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">%s</text>\n"
                 "<text transform=\"translate(18 %d) rotate(-90)\" "
                 "text-anchor=\"middle\">%s</text>\n",
                 LEFT, TOP, pw, ph, LEFT + pw / 2, HEIGHT - 12, xlabel, TOP + ph / 2, ylabel);
}

/* Decade ticks with grid lines on both log axes. */
static void log_ticks(ss_text_buf *b, log_axis x, log_axis y) {
  const double x0 = LEFT, x1 = WIDTH - RIGHT, y0 = HEIGHT - BOTTOM, y1 = TOP;
  for (double k = x.lo; k <= x.hi; ++k) {
    double px = log_pos(x, pow(10.0, k), x0, x1);
    ss_text_printf(b,
                   "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n"
                   "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n",
                   px, y0, px, y1, px, y0 + 16, pow(10.0, k));
  }
  for (double k = y.lo; k <= y.hi; ++k) {
    double py = log_pos(y, pow(10.0, k), y0, y1);
    ss_text_printf(b,
                   "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n"
                   "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n",
                   x0, py, x1, py, x0 - 6, py + 4, pow(10.0, k));
  }
}

static void legend_entry(ss_text_buf *b, int i, const char *name) {
  int y = TOP + 10 + 18 * i, x = WIDTH - RIGHT + 12;
  ss_text_printf(b,
                 "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"%s\" "
                 "stroke-width=\"2\"/>\n<text x=\"%d\" y=\"%d\">",
                 x, y, x + 20, y, ss_compare_method_colour(i), x + 26, y + 4);
  ss_text_escaped(b, name);
  ss_text_printf(b, "</text>\n");
}

/* relMSE after each pass against the wall time so far, log-log. */
static void convergence_plot(const ss_compare_options *o, ss_text_buf *b) {
  double tmin = INFINITY, tmax = 0.0, emin = INFINITY, emax = 0.0;
  for (int i = 0; i < o->num_methods; ++i) {
    const ss_compare_result *r = &o->results[i];
    for (int k = 0; k < r->num_passes; ++k) {
      const ss_compare_pass *p = &r->passes[k];
      if (p->seconds > 0.0 && p->rel_mse > 0.0 && isfinite(p->rel_mse)) {
        tmin = fmin(tmin, p->seconds);
        tmax = fmax(tmax, p->seconds);
        emin = fmin(emin, p->rel_mse);
        emax = fmax(emax, p->rel_mse);
      }
    }
  }
  svg_begin(b, WIDTH, HEIGHT, "relMSE against time (log-log)");
  plot_frame(b, "time (s)", "relMSE");
  if (!(tmax > 0.0)) {
    ss_text_printf(b, "<text x=\"%d\" y=\"%d\">no pass with a positive relMSE</text>\n", LEFT + 20,
                   HEIGHT / 2);
    ss_text_printf(b, "</svg>\n");
    return;
  }
  log_axis x = log_axis_of(tmin, tmax), y = log_axis_of(emin, emax);
  log_ticks(b, x, y);
  const double x0 = LEFT, x1 = WIDTH - RIGHT, y0 = HEIGHT - BOTTOM, y1 = TOP;
  for (int i = 0; i < o->num_methods; ++i) {
    const ss_compare_result *r = &o->results[i];
    const char *colour = ss_compare_method_colour(i);
    ss_text_printf(b,
                   "<g class=\"method\"><polyline fill=\"none\" stroke=\"%s\" "
                   "stroke-width=\"2\" points=\"",
                   colour);
    for (int k = 0; k < r->num_passes; ++k) {
      const ss_compare_pass *p = &r->passes[k];
      if (p->seconds > 0.0 && p->rel_mse > 0.0 && isfinite(p->rel_mse)) {
        ss_text_printf(b, "%.1f,%.1f ", log_pos(x, p->seconds, x0, x1),
                       log_pos(y, p->rel_mse, y0, y1));
      }
    }
    ss_text_printf(b, "\"/>\n");
    for (int k = 0; k < r->num_passes; ++k) {
      const ss_compare_pass *p = &r->passes[k];
      if (p->seconds > 0.0 && p->rel_mse > 0.0 && isfinite(p->rel_mse)) {
        ss_text_printf(b, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"><title>",
                       log_pos(x, p->seconds, x0, x1), log_pos(y, p->rel_mse, y0, y1), colour);
        ss_text_escaped(b, r->method.text);
        ss_text_printf(b, ": %u spp, %.3g s, relMSE %.3g</title></circle>\n", p->spp, p->seconds,
                       p->rel_mse);
      }
    }
    ss_text_printf(b, "</g>\n");
    legend_entry(b, i, r->method.text);
  }
  ss_text_printf(b, "</svg>\n");
}

/* Mean radiance over the mask relative to the reference's, channel c; a
 * dashed line at 1. Bars beyond the top are clipped and labelled. */
static void ratio_chart(const ss_compare_options *o, int c, ss_text_buf *b) {
  static const char *const names[3] = {"red", "green", "blue"};
  char title[96];
  snprintf(title, sizeof title, "mean radiance / reference, %s channel", names[c]);
  svg_begin(b, WIDTH, HEIGHT, title);
  plot_frame(b, "", "mean ratio to the reference");
  double top = 1.25;
  for (int i = 0; i < o->num_methods; ++i) {
    double v = ss_image_error_mean_ratio(&o->results[i].error, c);
    top = isfinite(v) ? fmin(fmax(top, 1.1 * v), 4.0) : top;
  }
  const double x0 = LEFT, pw = WIDTH - LEFT - RIGHT, y0 = HEIGHT - BOTTOM, ph = y0 - TOP;
  for (double t = 0.0; t <= top + 1e-9; t += top > 2.0 ? 0.5 : 0.25) {
    double py = y0 - t / top * ph;
    ss_text_printf(b,
                   "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n"
                   "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n",
                   x0, py, x0 + pw, py, x0 - 6, py + 4, t);
  }
  double slot = pw / (o->num_methods > 0 ? o->num_methods : 1);
  for (int i = 0; i < o->num_methods; ++i) {
    const ss_compare_result *r = &o->results[i];
    double v = ss_image_error_mean_ratio(&r->error, c), cx = x0 + slot * (i + 0.5);
    if (isfinite(v)) {
      double h = fmin(fmax(v, 0.0), top) / top * ph;
      ss_text_printf(b,
                     "<rect class=\"bar\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" "
                     "fill=\"%s\"><title>",
                     cx - 0.3 * slot, y0 - h, 0.6 * slot, h, ss_compare_method_colour(i));
      ss_text_escaped(b, r->method.text);
      ss_text_printf(b,
                     ": %.4g</title></rect>\n<text x=\"%.1f\" y=\"%.1f\" "
                     "text-anchor=\"middle\">%.3f%s</text>\n",
                     v, cx, y0 - h - 4, v, v > top ? " (clipped)" : "");
    } else {
      ss_text_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">n/a</text>\n", cx,
                     y0 - 4);
    }
    ss_text_printf(b,
                   "<text transform=\"translate(%.1f %.1f) rotate(-25)\" "
                   "text-anchor=\"end\" font-size=\"11\">",
                   cx, y0 + 14);
    ss_text_escaped(b, r->method.text);
    ss_text_printf(b, "</text>\n");
  }
  double one = y0 - 1.0 / top * ph;
  ss_text_printf(b,
                 "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"black\" "
                 "stroke-dasharray=\"6 4\"/>\n<text x=\"%.1f\" y=\"%.1f\">reference</text>\n"
                 "</svg>\n",
                 x0, one, x0 + pw, one, x0 + pw + 6, one + 4);
}

/* The colour as the error map's PNG shows it (sRGB-encoded). */
static void hex_colour(ss_rgb c, char out[8]) {
  snprintf(out, 8, "#%02x%02x%02x", (int)lround(255.0 * ss_srgb_encode(c.c[0])),
           (int)lround(255.0 * ss_srgb_encode(c.c[1])),
           (int)lround(255.0 * ss_srgb_encode(c.c[2])));
}

/* The error maps' colour scale: ss_error_map_colour is linear between five
 * stops and PNGs are sRGB-encoded, so the gradient has a stop every 1/32. */
static void colour_bar(ss_text_buf *b) {
  const int w = 360, h = 78, x0 = 20, bw = 300, y0 = 26, bh = 18;
  svg_begin(b, w, h, "relative error |v - ref| / (ref + 0.01)");
  ss_text_printf(b, "<defs><linearGradient id=\"scale\">\n");
  char hex[8];
  for (int k = 0; k <= 32; ++k) {
    hex_colour(ss_error_map_colour(SS_ERROR_MAP_MAX * k / 32.0), hex);
    ss_text_printf(b, "<stop offset=\"%.4g%%\" stop-color=\"%s\"/>\n", 100.0 * k / 32.0, hex);
  }
  ss_text_printf(b,
                 "</linearGradient></defs>\n<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" "
                 "fill=\"url(#scale)\" stroke=\"black\"/>\n",
                 x0, y0, bw, bh);
  for (int k = 0; k <= 4; ++k) {
    double v = SS_ERROR_MAP_MAX * k / 4.0;
    int px = x0 + bw * k / 4;
    ss_text_printf(b,
                   "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"black\"/>\n"
                   "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">%s%g</text>\n",
                   px, y0 + bh, px, y0 + bh + 4, px, y0 + bh + 17, k == 4 ? "&#8805; " : "", v);
  }
  hex_colour(ss_rgb_gray(SS_ERROR_MAP_OUTSIDE), hex);
  ss_text_printf(b,
                 "<rect x=\"%d\" y=\"%d\" width=\"12\" height=\"12\" fill=\"%s\"/>\n"
                 "<text x=\"%d\" y=\"%d\" font-size=\"10\">not</text>\n"
                 "<text x=\"%d\" y=\"%d\" font-size=\"10\">compared</text>\n</svg>\n",
                 x0 + bw + 6, y0 + 3, hex, x0 + bw + 2, y0 + bh + 10, x0 + bw - 8, y0 + bh + 21);
}

/* Saves `b` as DIR/NAME; 0, or 1 after printing why. */
static int save(const ss_compare_options *o, const char *name, ss_text_buf *b) {
  char path[SS_PATH_SIZE + 64];
  snprintf(path, sizeof path, "%s/%s", o->dir, name);
  ss_error err;
  ss_status st = ss_text_save(b, path, SS_FILE_SVG, &err);
  ss_text_free(b);
  if (st != SS_OK) {
    fprintf(stderr, "subsurf compare: %s\n", err.message);
    return 1;
  }
  return 0;
}

int ss_compare_write_plots(const ss_compare_options *o) {
  ss_text_buf b = {0};
  convergence_plot(o, &b);
  int rc = save(o, "convergence.svg", &b);
  for (int c = 0; c < 3 && rc == 0; ++c) {
    char name[32];
    snprintf(name, sizeof name, "mean-ratio-%c.svg", "rgb"[c]);
    ratio_chart(o, c, &b);
    rc = save(o, name, &b);
  }
  if (rc == 0) {
    colour_bar(&b);
    rc = save(o, "error-colorbar.svg", &b);
  }
  return rc;
}
