/* `subsurf compare`'s report, DIR/index.html (compare_scene.h): one page
 * that works offline from the folder (relative links only, no network),
 * with the results table, the images side by side, a click-to-flip
 * comparison of each method against the reference, the error maps with
 * their colour bar and the plots. Its script marks the page's state on
 * <body> once loaded: data-status "ok" or the errors seen (script errors
 * and images that failed to load), data-images the images loaded. */
#include "cli/compare_scene.h"
#include "cli/text_buf.h"

#include <math.h>
#include <stdio.h>

static const char style[] =
    "body{font-family:sans-serif;margin:1.5em;color:#222;max-width:1700px}\n"
    "table{border-collapse:collapse;font-size:13px}\n"
    "th,td{border:1px solid #bbb;padding:3px 7px;text-align:right}\n"
    "th{background:#eee}td:first-child{text-align:left;font-family:monospace}\n"
    ".grid{display:flex;flex-wrap:wrap;gap:14px}\n"
    "figure{margin:0;font-size:12px}figcaption{max-width:400px}\n"
    "figure img{display:block;image-rendering:pixelated;border:1px solid #999}\n"
    ".flip img{cursor:pointer}.flip .showing{font-weight:bold}\n"
    ".swatch{display:inline-block;width:10px;height:10px;margin-right:4px}\n"
    "img.plot{max-width:100%;border:1px solid #ccc;margin:4px}\n";

/* Runs in <head>, before any image loads, so that every failure is seen. */
static const char script[] =
    "var reportErrors=[];\n"
    "window.addEventListener('error',function(e){var t=e.target;\n"
    "  reportErrors.push(t&&t.src?'cannot load "
    "'+t.getAttribute('src'):String(e.message));},true);\n"
    "function flip(f){var img=f.querySelector('img'),s=f.querySelector('.showing');\n"
    "  var toRef=img.getAttribute('src')===f.dataset.method;\n"
    "  img.setAttribute('src',toRef?f.dataset.reference:f.dataset.method);\n"
    "  s.textContent=toRef?'reference':f.dataset.name;}\n"
    "document.addEventListener('DOMContentLoaded',function(){\n"
    "  document.querySelectorAll('.flip').forEach(function(f){\n"
    "    f.addEventListener('click',function(){flip(f);});});});\n"
    "window.addEventListener('load',function(){var n=0;\n"
    "  document.querySelectorAll('img').forEach(function(i){\n"
    "    if(i.complete&&i.naturalWidth>0)n++;else reportErrors.push('not shown: "
    "'+i.getAttribute('src'));});\n"
    "  document.body.dataset.images=n;\n"
    "  document.body.dataset.status=reportErrors.length?reportErrors.join('; '):'ok';});\n";

static void number(ss_text_buf *b, const char *fmt, double v) {
  if (isfinite(v)) {
    ss_text_printf(b, fmt, v);
  } else {
    ss_text_printf(b, "%s", isinf(v) ? "never" : "&ndash;");
  }
}

static void header(const ss_compare_options *o, ss_text_buf *b) {
  ss_text_printf(b, "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                    "<title>subsurf compare: ");
  ss_text_escaped(b, o->scene);
  ss_text_printf(b, "</title>\n<style>\n%s</style>\n<script>\n%s</script>\n</head>\n", style,
                 script);
  ss_text_printf(b, "<body data-methods=\"%d\">\n<h1>subsurf compare: ", o->num_methods);
  ss_text_escaped(b, o->scene);
  ss_text_printf(b, "</h1>\n<p>Every method ");
  if (o->spp > 0) {
    ss_text_printf(b, "at %d samples per pixel", o->spp);
  } else {
    ss_text_printf(b, "with %g s of wall time", o->time);
  }
  ss_text_printf(b, ", against the reference <a href=\"%s\">",
                 o->ref.rendered ? "reference.exr" : "reference.png");
  ss_text_escaped(b, o->ref.file);
  ss_text_printf(b, "</a>");
  if (o->ref.rendered) {
    ss_text_printf(b, " (volpath, %u spp, %.1f s, estimated relative standard error %.3g)",
                   o->ref.spp, o->ref.seconds, o->ref.rel_error);
  }
  ss_text_printf(b, ". Errors are measured over the pixels where the camera first sees a "
                    "translucent object; relMSE is mean((v &minus; ref)<sup>2</sup> / "
                    "(ref + 0.01)<sup>2</sup>). Numbers: <a href=\"results.json\">results.json"
                    "</a>, <a href=\"results.csv\">results.csv</a>.</p>\n");
}

static void table(const ss_compare_options *o, const ss_compare_curve *curves, ss_text_buf *b) {
  ss_text_printf(b, "<h2>Results</h2>\n<table id=\"results\">\n<tr><th>method</th><th>time "
                    "(s)</th><th>spp</th><th>relMSE</th><th>relMSE r / g / b</th><th>mean / "
                    "reference r / g / b</th><th>time to volpath's relMSE (s)</th>"
                    "<th>converged relMSE</th></tr>\n");
  for (int i = 0; i < o->num_methods; ++i) {
    const ss_compare_result *r = &o->results[i];
    ss_text_printf(b,
                   "<tr class=\"method\"><td><span class=\"swatch\" "
                   "style=\"background:%s\"></span>",
                   ss_compare_method_colour(i));
    ss_text_escaped(b, r->method.text);
    ss_text_printf(b, "</td><td>%.3g</td><td>%u</td><td>%.4g</td><td>%.3g / %.3g / %.3g</td><td>",
                   r->seconds, r->spp, r->error.rel_mse, r->error.rel_mse_c[0],
                   r->error.rel_mse_c[1], r->error.rel_mse_c[2]);
    for (int c = 0; c < 3; ++c) {
      number(b, c < 2 ? "%.3f / " : "%.3f", ss_image_error_mean_ratio(&r->error, c));
    }
    ss_text_printf(b, "</td><td>");
    number(b, "%.3g", curves[i].time_to_volpath);
    ss_text_printf(b, "</td><td>");
    number(b, "%.3g", curves[i].converged);
    ss_text_printf(b, "</td></tr>\n");
  }
  ss_text_printf(b, "</table>\n");
}

/* <img> of DIR/FILE at the report's display width. */
static void image(ss_text_buf *b, const char *file, int width, int height, const char *alt) {
  int w = width < 256 ? 256 : width > 400 ? 400 : width;
  ss_text_printf(b, "<img src=\"");
  ss_text_escaped(b, file);
  ss_text_printf(b, "\" width=\"%d\" height=\"%d\" alt=\"", w,
                 (int)lround((double)w * height / width));
  ss_text_escaped(b, alt);
  ss_text_printf(b, "\">");
}

static void caption(ss_text_buf *b, const ss_compare_result *r) {
  ss_text_printf(b, "<figcaption><b>");
  ss_text_escaped(b, r->method.text);
  ss_text_printf(b, "</b>: %.3g s, %u spp, relMSE %.3g (<a href=\"", r->seconds, r->spp,
                 r->error.rel_mse);
  ss_text_escaped(b, r->file);
  ss_text_printf(b, ".exr\">EXR</a>)</figcaption>");
}

static void figures(const ss_compare_options *o, int w, int h, ss_text_buf *b) {
  char file[SS_NAME_SIZE * 4 + 16];
  ss_text_printf(b, "<h2>Images</h2>\n<div class=\"grid\" id=\"images\">\n<figure>");
  image(b, "reference.png", w, h, "reference");
  ss_text_printf(b, "<figcaption><b>reference</b></figcaption></figure>\n");
  for (int i = 0; i < o->num_methods; ++i) {
    snprintf(file, sizeof file, "%s.png", o->results[i].file);
    ss_text_printf(b, "<figure class=\"method\">");
    image(b, file, w, h, o->results[i].method.text);
    caption(b, &o->results[i]);
    ss_text_printf(b, "</figure>\n");
  }
  ss_text_printf(b, "</div>\n<h2>Flip against the reference</h2>\n<p>Click an image to switch "
                    "between the method and the reference.</p>\n<div class=\"grid\">\n");
  for (int i = 0; i < o->num_methods; ++i) {
    const ss_compare_result *r = &o->results[i];
    snprintf(file, sizeof file, "%s.png", r->file);
    ss_text_printf(b, "<figure class=\"flip\" data-reference=\"reference.png\" data-method=\"");
    ss_text_escaped(b, file);
    ss_text_printf(b, "\" data-name=\"");
    ss_text_escaped(b, r->method.text);
    ss_text_printf(b, "\">");
    image(b, file, w, h, r->method.text);
    ss_text_printf(b, "<figcaption>showing <span class=\"showing\">");
    ss_text_escaped(b, r->method.text);
    ss_text_printf(b, "</span> (click: the other)</figcaption></figure>\n");
  }
  ss_text_printf(b, "</div>\n<h2>Relative error</h2>\n<div class=\"grid\">\n");
  for (int i = 0; i < o->num_methods; ++i) {
    snprintf(file, sizeof file, "%s-error.png", o->results[i].file);
    ss_text_printf(b, "<figure>");
    image(b, file, w, h, o->results[i].method.text);
    ss_text_printf(b, "<img src=\"error-colorbar.svg\" width=\"360\" height=\"78\" "
                      "alt=\"colour bar\">");
    caption(b, &o->results[i]);
    ss_text_printf(b, "</figure>\n");
  }
  ss_text_printf(b, "</div>\n");
}

int ss_compare_write_html(const ss_compare_options *o, int width, int height) {
  ss_compare_curve curves[SS_COMPARE_MAX_METHODS];
  const ss_compare_result *volpath = ss_compare_find_volpath(o->results, o->num_methods);
  for (int i = 0; i < o->num_methods; ++i) {
    ss_compare_curve_of(&o->results[i], volpath, &curves[i]);
  }
  ss_text_buf b = {0};
  header(o, &b);
  table(o, curves, &b);
  figures(o, width, height, &b);
  ss_text_printf(&b, "<h2>Plots</h2>\n<div>\n<img class=\"plot\" src=\"convergence.svg\" "
                     "alt=\"relMSE against time\">\n");
  for (int c = 0; c < 3; ++c) {
    ss_text_printf(&b, "<img class=\"plot\" src=\"mean-ratio-%c.svg\" alt=\"mean ratio\">\n",
                   "rgb"[c]);
  }
  ss_text_printf(&b, "</div>\n</body>\n</html>\n");
  char path[SS_PATH_SIZE + 32];
  snprintf(path, sizeof path, "%s/index.html", o->dir);
  ss_error err;
  ss_status st = ss_text_save(&b, path, SS_FILE_HTML, &err);
  ss_text_free(&b);
  if (st != SS_OK) {
    fprintf(stderr, "subsurf compare: %s\n", err.message);
    return 1;
  }
  return 0;
}
