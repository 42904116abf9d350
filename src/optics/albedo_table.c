/* The half-space albedo table (albedo_table.h): reading, interpolation and
 * inversion. */
#include "subsurf/albedo_table.h"

#include "optics/checked_text.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE 8192

struct ss_albedo_table {
  int n_eta, n_g, n_u;
  double eta[SS_ALBEDO_TABLE_MAX_GRID], g[SS_ALBEDO_TABLE_MAX_GRID], u[SS_ALBEDO_TABLE_MAX_GRID];
  double *value; /* [eta][g][u] */
  double *error; /* same layout */
};

double ss_albedo_max(double eta) {
  /* Fresnel reflectance at normal incidence, ((eta - 1)/(eta + 1))^2. */
  double f0 = (eta - 1.0) / (eta + 1.0);
  return 1.0 - f0 * f0;
}

/* ---- reading */

typedef struct {
  const char *text, *end, *label;
  int line;
  ss_error *err;
  char buf[MAX_LINE];
  char *cursor;
} reader;

/* The next line that is not empty or a comment, into r->buf; 0 at the end. */
static int next_line(reader *r, const char **start) {
  while (r->text < r->end) {
    const char *nl = memchr(r->text, '\n', (size_t)(r->end - r->text));
    const char *stop = nl ? nl : r->end;
    size_t n = (size_t)(stop - r->text);
    *start = r->text;
    r->text = nl ? nl + 1 : r->end;
    r->line++;
    if (n >= MAX_LINE) {
      n = MAX_LINE - 1;
    }
    memcpy(r->buf, *start, n);
    r->buf[n] = '\0';
    r->cursor = r->buf;
    if (n > 0 && r->buf[0] != '#') {
      return 1;
    }
  }
  return 0;
}

static ss_status fail(reader *r, const char *what) {
  return ss_error_set(r->err, SS_ERR_PARSE, "%s:%d: %s", r->label, r->line, what);
}

static int word(reader *r, const char *expect) {
  size_t n = strlen(expect);
  if (strncmp(r->cursor, expect, n) || (r->cursor[n] != ' ' && r->cursor[n] != '\0')) {
    return 0;
  }
  r->cursor += n;
  return 1;
}

static int number(reader *r, double *v) {
  if (*r->cursor != ' ') {
    return 0;
  }
  char *e;
  *v = strtod(r->cursor + 1, &e);
  if (e == r->cursor + 1 || (*e != ' ' && *e != '\0') || !isfinite(*v)) {
    return 0;
  }
  r->cursor = e;
  return 1;
}

static ss_status read_grid(reader *r, const char *name, double lo, double hi, double *grid,
                           int *n) {
  const char *start;
  double count;
  if (!next_line(r, &start) || !word(r, name) || !number(r, &count) || count < 2 ||
      count > SS_ALBEDO_TABLE_MAX_GRID || count != floor(count)) {
    char m[96];
    snprintf(m, sizeof m, "expected '%s N v1 ... vN' with 2 <= N <= %d", name,
             SS_ALBEDO_TABLE_MAX_GRID);
    return fail(r, m);
  }
  *n = (int)count;
  for (int i = 0; i < *n; ++i) {
    if (!number(r, &grid[i]) || grid[i] < lo || grid[i] > hi || (i && !(grid[i] > grid[i - 1]))) {
      char m[128];
      snprintf(m, sizeof m, "%s: %d values strictly increasing within [%g, %g] expected", name, *n,
               lo, hi);
      return fail(r, m);
    }
  }
  return *r->cursor ? fail(r, "trailing text after the grid") : SS_OK;
}

static ss_status read_curve(reader *r, ss_albedo_table *t, int ie, int ig) {
  const char *start;
  double eta, g;
  double *v = t->value + ((size_t)ie * t->n_g + ig) * t->n_u;
  double *e = t->error + ((size_t)ie * t->n_g + ig) * t->n_u;
  if (!next_line(r, &start) || !word(r, "curve") || !number(r, &eta) || !number(r, &g) ||
      eta != t->eta[ie] || g != t->g[ig]) {
    char m[128];
    snprintf(m, sizeof m, "expected 'curve %.17g %.17g' followed by %d values and %d errors",
             t->eta[ie], t->g[ig], t->n_u, t->n_u);
    return fail(r, m);
  }
  for (int k = 0; k < 2 * t->n_u; ++k) {
    double *dst = k < t->n_u ? &v[k] : &e[k - t->n_u];
    if (!number(r, dst) || *dst < 0.0 || *dst > 1.0) {
      return fail(r, "expected numbers in [0, 1] (albedos, then standard errors)");
    }
  }
  if (*r->cursor) {
    return fail(r, "trailing text after the curve");
  }
  if (fabs(v[0] - ss_albedo_max(eta)) > 1e-6 || v[t->n_u - 1] != 0.0) {
    return fail(r, "a curve must start at 1 - F(0) (u = 0) and end at 0 (u = 1)");
  }
  for (int k = 1; k < t->n_u; ++k) {
    if (!(v[k] < v[k - 1])) {
      return fail(r, "a curve must decrease strictly in u");
    }
  }
  return SS_OK;
}

static ss_status read_body(reader *r, ss_albedo_table *t) {
  const char *start;
  double version;
  if (!next_line(r, &start) || !word(r, "subsurf-albedo-table") || !number(r, &version) ||
      *r->cursor) {
    return fail(r, "not a subsurf albedo table (expected 'subsurf-albedo-table VERSION')");
  }
  if (version != SS_ALBEDO_TABLE_VERSION) {
    char m[96];
    snprintf(m, sizeof m, "version %g is not supported (expected %d)", version,
             SS_ALBEDO_TABLE_VERSION);
    return fail(r, m);
  }
  ss_status st = read_grid(r, "eta", 1.0, 10.0, t->eta, &t->n_eta);
  if (st == SS_OK)
    st = read_grid(r, "g", -0.99, 0.99, t->g, &t->n_g);
  if (st == SS_OK)
    st = read_grid(r, "u", 0.0, 1.0, t->u, &t->n_u);
  if (st != SS_OK) {
    return st;
  }
  if (t->u[0] != 0.0 || t->u[t->n_u - 1] != 1.0) {
    return fail(r, "the u grid must run from 0 to 1");
  }
  size_t n = (size_t)t->n_eta * t->n_g * t->n_u;
  t->value = malloc(n * sizeof *t->value);
  t->error = malloc(n * sizeof *t->error);
  if (!t->value || !t->error) {
    return ss_error_set(r->err, SS_ERR_NO_MEMORY, "%s: out of memory", r->label);
  }
  for (int ie = 0; ie < t->n_eta; ++ie) {
    for (int ig = 0; ig < t->n_g; ++ig) {
      if ((st = read_curve(r, t, ie, ig)) != SS_OK) {
        return st;
      }
    }
  }
  if (next_line(r, &start)) {
    return fail(r, "unexpected line after the curves");
  }
  return SS_OK;
}

ss_status ss_albedo_table_parse(const char *text, size_t size, const char *label,
                                ss_albedo_table **out, ss_error *err) {
  *out = NULL;
  size_t body;
  ss_status st = ss_checked_text_verify(text, size, label, &body, err);
  if (st != SS_OK) {
    return st;
  }
  ss_albedo_table *t = calloc(1, sizeof *t);
  if (!t) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", label);
  }
  reader r = {.text = text, .end = text + body, .label = label, .err = err};
  st = read_body(&r, t);
  if (st != SS_OK) {
    ss_albedo_table_destroy(t);
    return st;
  }
  *out = t;
  return SS_OK;
}

ss_status ss_albedo_table_load(const char *path, ss_albedo_table **out, ss_error *err) {
  *out = NULL;
  char *text;
  size_t size;
  ss_status st = ss_checked_text_read(path, SS_INPUT_ALBEDO_TABLE, &text, &size, err);
  if (st == SS_OK) {
    st = ss_albedo_table_parse(text, size, path, out, err);
  }
  free(text);
  return st;
}

void ss_albedo_table_destroy(ss_albedo_table *t) {
  if (t) {
    free(t->value);
    free(t->error);
    free(t);
  }
}

/* The shipped file's bytes (generated by CMake from data/halfspace_albedo.txt). */
extern const unsigned char ss_albedo_table_data[];
extern const size_t ss_albedo_table_data_size;

static pthread_once_t builtin_once = PTHREAD_ONCE_INIT;
static ss_albedo_table *builtin;
static ss_error builtin_err;

static void builtin_parse(void) {
  ss_albedo_table_parse((const char *)ss_albedo_table_data, ss_albedo_table_data_size,
                        "data/halfspace_albedo.txt (built in)", &builtin, &builtin_err);
}

ss_status ss_albedo_table_builtin(const ss_albedo_table **out, ss_error *err) {
  pthread_once(&builtin_once, builtin_parse);
  *out = builtin;
  if (!builtin) {
    if (err) {
      *err = builtin_err;
    }
    return builtin_err.status;
  }
  return SS_OK;
}

/* ---- interpolation */

void ss_albedo_table_range(const ss_albedo_table *t, double *eta_lo, double *eta_hi, double *g_lo,
                           double *g_hi) {
  *eta_lo = t->eta[0];
  *eta_hi = t->eta[t->n_eta - 1];
  *g_lo = t->g[0];
  *g_hi = t->g[t->n_g - 1];
}

ss_status ss_albedo_table_check(const ss_albedo_table *t, double g, double eta, ss_error *err) {
  if (!(eta >= t->eta[0] && eta <= t->eta[t->n_eta - 1])) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "eta %g is outside the albedo table's range [%g, %g]", eta, t->eta[0],
                        t->eta[t->n_eta - 1]);
  }
  if (!(g >= t->g[0] && g <= t->g[t->n_g - 1])) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "g %g is outside the albedo table's range [%g, %g]", g, t->g[0],
                        t->g[t->n_g - 1]);
  }
  return SS_OK;
}

/* Cell and weight of x on a grid (x clamped to it). */
static int locate(const double *grid, int n, double x, double *w) {
  int i = 0;
  while (i < n - 2 && x >= grid[i + 1]) {
    ++i;
  }
  double t = (x - grid[i]) / (grid[i + 1] - grid[i]);
  *w = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  return i;
}

/* The curve at (g, eta): bilinear in eta and g, node by node. Albedos are
 * interpolated per unit power entering (each curve divided by its value at
 * u = 0, 1 - F(0)) and the result scaled by 1 - F(0) of eta, so that u = 0
 * stays exact at any eta; standard errors as they are. */
static void curve_at(const ss_albedo_table *t, double g, double eta, const double *src,
                     double *out) {
  double we, wg;
  int ie = locate(t->eta, t->n_eta, eta, &we), ig = locate(t->g, t->n_g, g, &wg);
  const double *c00 = src + ((size_t)ie * t->n_g + ig) * t->n_u;
  const double *c01 = c00 + t->n_u, *c10 = c00 + (size_t)t->n_g * t->n_u, *c11 = c10 + t->n_u;
  int values = src == t->value;
  for (int k = 0; k < t->n_u; ++k) {
    double a = c00[k], b = c01[k], c = c10[k], d = c11[k];
    if (values) {
      a /= c00[0], b /= c01[0], c /= c10[0], d /= c11[0];
    }
    out[k] = (1.0 - we) * ((1.0 - wg) * a + wg * b) + we * ((1.0 - wg) * c + wg * d);
  }
  if (values) {
    double top = ss_albedo_max(eta);
    for (int k = 1; k < t->n_u; ++k) {
      out[k] *= top;
    }
    out[0] = top;
  }
}

/* PCHIP slope at node k of (x, y) (Fritsch & Butland 1984 weighted harmonic
 * mean inside; the shape-preserving three-point formula at the ends). */
static double pchip_slope(const double *x, const double *y, int n, int k) {
  if (k == 0 || k == n - 1) {
    int a = k == 0 ? 0 : n - 2, b = k == 0 ? 1 : n - 3;
    double h0 = x[a + 1] - x[a], h1 = x[b + 1] - x[b];
    double d0 = (y[a + 1] - y[a]) / h0, d1 = (y[b + 1] - y[b]) / h1;
    double d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (d * d0 <= 0.0) {
      return 0.0;
    }
    if (d0 * d1 <= 0.0 && fabs(d) > 3.0 * fabs(d0)) {
      return 3.0 * d0;
    }
    return d;
  }
  double h0 = x[k] - x[k - 1], h1 = x[k + 1] - x[k];
  double d0 = (y[k] - y[k - 1]) / h0, d1 = (y[k + 1] - y[k]) / h1;
  if (d0 * d1 <= 0.0) {
    return 0.0;
  }
  double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0;
  return (w1 + w2) / (w1 / d0 + w2 / d1);
}

/* The cubic Hermite piece on [x_k, x_{k+1}] at s in [0, 1]. */
typedef struct {
  double y0, y1, m0, m1; /* values, slopes times the width */
} hermite;

static hermite piece(const double *x, const double *y, int n, int k) {
  double h = x[k + 1] - x[k];
  hermite p = {y[k], y[k + 1], h * pchip_slope(x, y, n, k), h * pchip_slope(x, y, n, k + 1)};
  return p;
}

static double hermite_eval(const hermite *p, double s, double *deriv) {
  double s2 = s * s, s3 = s2 * s;
  if (deriv) {
    *deriv = (6.0 * s2 - 6.0 * s) * (p->y0 - p->y1) + (3.0 * s2 - 4.0 * s + 1.0) * p->m0 +
             (3.0 * s2 - 2.0 * s) * p->m1;
  }
  return (2.0 * s3 - 3.0 * s2 + 1.0) * p->y0 + (s3 - 2.0 * s2 + s) * p->m0 +
         (-2.0 * s3 + 3.0 * s2) * p->y1 + (s3 - s2) * p->m1;
}

double ss_albedo_table_albedo(const ss_albedo_table *t, double alpha_reduced, double g, double eta,
                              double *error) {
  double a = alpha_reduced < 0.0 ? 0.0 : alpha_reduced > 1.0 ? 1.0 : alpha_reduced;
  double u = sqrt(1.0 - a), y[SS_ALBEDO_TABLE_MAX_GRID], w;
  curve_at(t, g, eta, t->value, y);
  int k = locate(t->u, t->n_u, u, &w);
  hermite p = piece(t->u, y, t->n_u, k);
  if (error) {
    double e[SS_ALBEDO_TABLE_MAX_GRID];
    curve_at(t, g, eta, t->error, e);
    *error = (1.0 - w) * e[k] + w * e[k + 1];
  }
  return hermite_eval(&p, w, NULL);
}

double ss_albedo_table_invert(const ss_albedo_table *t, double albedo, double g, double eta) {
  double y[SS_ALBEDO_TABLE_MAX_GRID];
  curve_at(t, g, eta, t->value, y);
  if (!(albedo < y[0])) {
    return 1.0;
  }
  if (!(albedo > 0.0)) {
    return 0.0;
  }
  int k = 0;
  while (k < t->n_u - 2 && albedo <= y[k + 1]) {
    ++k;
  }
  /* y[k] > albedo > y[k + 1]: the piece decreases monotonically from y[k] to
   * y[k + 1], so Newton steps kept inside a shrinking bracket converge to
   * its one root. */
  hermite p = piece(t->u, y, t->n_u, k);
  double lo = 0.0, hi = 1.0, s = (y[k] - albedo) / (y[k] - y[k + 1]);
  for (int i = 0; i < 100; ++i) {
    double d, f = hermite_eval(&p, s, &d) - albedo;
    if (f > 0.0) {
      lo = s;
    } else {
      hi = s;
    }
    double next = d < 0.0 ? s - f / d : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) {
      next = 0.5 * (lo + hi);
    }
    if (fabs(next - s) < 1e-15 || hi - lo < 1e-15) {
      s = next;
      break;
    }
    s = next;
  }
  double u = t->u[k] + s * (t->u[k + 1] - t->u[k]);
  return 1.0 - u * u;
}
