/* The exact half-space profile table (profile_table.h): building, reading
 * and evaluation. */
#include "subsurf/profile_table.h"

#include "optics/checked_text.h"
#include "subsurf/bssrdf.h"
#include "subsurf/halfspace_profiles.h"

#include <gsl/gsl_interp2d.h>
#include <gsl/gsl_spline2d.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

/* The built grids: u = sqrt(1 - alpha') denser towards u = 0, where the
 * profile reaches farthest, and 16 log bins per decade of rho. */
static const double build_u[] = {0.01, 0.02, 0.03, 0.05, 0.07, 0.1,  0.13, 0.16,
                                 0.2,  0.25, 0.3,  0.35, 0.4,  0.46, 0.52, 0.58,
                                 0.64, 0.7,  0.76, 0.82, 0.87, 0.92, 0.96, 0.99};
#define BUILD_RMIN 0.02
#define BUILD_RMAX 200.0
#define BUILD_BINS 64

struct ss_profile_table {
  double eta, g;
  uint64_t paths;
  int n_u, n_bins;
  double u[SS_PROFILE_TABLE_MAX_U];
  double *edges;         /* [n_bins + 1] */
  double *value, *error; /* [n_u][n_bins] */
  double *log_rho;       /* [n_bins] geometric centres */
  double *log_ratio;     /* [n_u][n_bins]: ln(M / M_dipole), gsl_spline2d's layout */
  gsl_spline2d *spline;
};

void ss_profile_table_build_params_default(ss_profile_table_build_params *p) {
  memset(p, 0, sizeof *p);
  p->eta = 1.3;
  p->paths = 1000000;
  p->seed = 1;
}

/* ---- the classical dipole the table is divided by */

/* The dipole's exitance per unit incident power for sigma_t' = 1
 * (Jensen2001 eq. 4 with its Fresnel factors, the `dipole` model): at the n
 * radii rho[], or, with edges (n + 1 of them), averaged over the n annuli
 * between them as the table's bins are. */
static ss_status dipole_exitance(double alpha_prime, double eta, const double *rho,
                                 const double *edges, size_t n, double *out, ss_error *err) {
  ss_bssrdf_params bp;
  ss_bssrdf_params_default(&bp);
  ss_bssrdf_params_set_gray(&bp, alpha_prime, 1.0 - alpha_prime, 0.0);
  bp.eta = eta;
  bp.single_use = 1;
  ss_bssrdf *b;
  ss_status st = ss_bssrdf_create("dipole", &bp, &b, err);
  if (st != SS_OK) {
    return st;
  }
  for (size_t i = 0; i < n; ++i) {
    double m[SS_BSSRDF_CHANNELS];
    if (edges) {
      ss_bssrdf_radial_average(b, 1.0, edges[i], edges[i + 1], m);
    } else {
      ss_bssrdf_exitance(b, 1.0, rho[i], 0.0, m);
    }
    out[i] = m[0];
  }
  ss_bssrdf_destroy(b);
  return SS_OK;
}

/* ---- building */

typedef struct {
  char *buf;
  size_t len, cap;
  int failed;
} text_out;

static void emit(text_out *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void emit(text_out *o, const char *fmt, ...) {
  if (o->failed) {
    return;
  }
  for (;;) {
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(o->buf + o->len, o->cap - o->len, fmt, ap);
    va_end(ap);
    if (n < 0) {
      o->failed = 1;
      return;
    }
    if ((size_t)n < o->cap - o->len) {
      o->len += (size_t)n;
      return;
    }
    size_t cap = 2 * o->cap + (size_t)n + 1;
    char *b = realloc(o->buf, cap);
    if (!b) {
      o->failed = 1;
      return;
    }
    o->buf = b;
    o->cap = cap;
  }
}

ss_status ss_profile_table_build(const ss_profile_table_build_params *p, char **text, size_t *size,
                                 ss_error *err) {
  *text = NULL;
  *size = 0;
  int n_u = (int)(sizeof build_u / sizeof build_u[0]);
  ss_halfspace_profiles_params hp;
  ss_halfspace_profiles_params_default(&hp);
  hp.eta = p->eta;
  hp.g = p->g;
  hp.n_albedo = n_u;
  for (int k = 0; k < n_u; ++k) {
    /* alpha' = (1 - g) alpha / (1 - g alpha), solved for alpha. */
    double ap = 1.0 - build_u[k] * build_u[k];
    hp.albedo[k] = ap / (1.0 - p->g + p->g * ap);
  }
  hp.rmin = BUILD_RMIN;
  hp.rmax = BUILD_RMAX;
  hp.rbins = BUILD_BINS + 1;
  hp.paths = p->paths;
  hp.seed = p->seed;
  hp.threads = p->threads;
  hp.cancel = p->cancel;
  hp.progress = p->progress;
  hp.progress_ctx = p->progress_ctx;
  ss_halfspace_profiles_result *r;
  ss_status st = ss_halfspace_profiles_run(&hp, &r, err);
  if (st != SS_OK) {
    return st;
  }
  if (r->interrupted) {
    ss_halfspace_profiles_result_destroy(r);
    return ss_error_set(err, SS_ERR_INTERRUPTED, "interrupted: no table written");
  }
  text_out o = {0};
  emit(&o,
       "# subsurf exact half-space profile table: radial exitance per unit incident power of\n"
       "# a collimated beam at normal incidence, annulus averages in units of the transport\n"
       "# mean free path, for reduced albedo alpha' = 1 - u^2 (format: docs/fit.md);\n"
       "# built by scripts/make_profile_table.c with %llu paths, seed %llu.\n",
       (unsigned long long)r->paths, (unsigned long long)p->seed);
  emit(&o, "subsurf-profile-table %d\neta %.17g\ng %.17g\npaths %llu\nu %d",
       SS_PROFILE_TABLE_VERSION, p->eta, p->g, (unsigned long long)r->paths, n_u);
  for (int k = 0; k < n_u; ++k) {
    emit(&o, " %.17g", build_u[k]);
  }
  emit(&o, "\nrho %d", BUILD_BINS + 1);
  for (int i = 1; i <= BUILD_BINS; ++i) {
    emit(&o, " %.6e", r->r_lo[i]);
  }
  emit(&o, " %.6e\n", r->r_hi[BUILD_BINS]);
  for (int k = 0; k < n_u; ++k) {
    const ss_estimate *e = r->radial + (size_t)k * (size_t)r->rbins;
    emit(&o, "curve %.17g", build_u[k]);
    for (int i = 1; i <= BUILD_BINS; ++i) {
      emit(&o, " %.6e", e[i].value);
    }
    for (int i = 1; i <= BUILD_BINS; ++i) {
      emit(&o, " %.3e", e[i].error);
    }
    emit(&o, "\n");
  }
  ss_halfspace_profiles_result_destroy(r);
  uint32_t crc =
      o.failed ? 0 : (uint32_t)crc32(crc32(0L, Z_NULL, 0), (const Bytef *)o.buf, (uInt)o.len);
  emit(&o, "crc32 %08x\n", (unsigned)crc);
  if (o.failed) {
    free(o.buf);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for the table's text");
  }
  *text = o.buf;
  *size = o.len;
  return SS_OK;
}

/* ---- reading */

typedef struct {
  const char *p, *end, *label;
  int line;
  ss_error *err;
} reader;

static ss_status fail(reader *r, const char *what) {
  return ss_error_set(r->err, SS_ERR_PARSE, "%s:%d: %s", r->label, r->line, what);
}

/* Moves to the next line that is neither empty nor a comment; 0 at the end. */
static int next_line(reader *r) {
  while (r->p < r->end) {
    r->line++;
    if (*r->p != '#' && *r->p != '\n') {
      return 1;
    }
    const char *nl = memchr(r->p, '\n', (size_t)(r->end - r->p));
    r->p = nl ? nl + 1 : r->end;
  }
  return 0;
}

/* The keyword at the start of the line, followed by a space or the end. */
static int keyword(reader *r, const char *word) {
  size_t n = strlen(word);
  if ((size_t)(r->end - r->p) < n || strncmp(r->p, word, n) ||
      (r->p + n < r->end && r->p[n] != ' ' && r->p[n] != '\n')) {
    return 0;
  }
  r->p += n;
  return 1;
}

/* One number preceded by a space, on the current line. */
static int number(reader *r, double *v) {
  if (r->p >= r->end || *r->p != ' ') {
    return 0;
  }
  char buf[64];
  size_t n = 0;
  const char *q = r->p + 1;
  while (q < r->end && *q != ' ' && *q != '\n' && n < sizeof buf - 1) {
    buf[n++] = *q++;
  }
  buf[n] = '\0';
  char *e;
  *v = strtod(buf, &e);
  if (n == 0 || *e || !isfinite(*v)) {
    return 0;
  }
  r->p = q;
  return 1;
}

static int end_of_line(reader *r) {
  if (r->p < r->end && *r->p != '\n') {
    return 0;
  }
  if (r->p < r->end) {
    r->p++;
  }
  return 1;
}

static ss_status read_scalar(reader *r, const char *name, double lo, double hi, double *v) {
  if (!next_line(r) || !keyword(r, name) || !number(r, v) || !end_of_line(r) || *v < lo ||
      *v > hi) {
    char m[128];
    snprintf(m, sizeof m, "expected '%s X' with X in [%g, %g]", name, lo, hi);
    return fail(r, m);
  }
  return SS_OK;
}

static ss_status read_grid(reader *r, const char *name, int max, double lo, double hi, double *v,
                           int *n) {
  double count;
  char m[160];
  snprintf(m, sizeof m, "expected '%s N v_1 .. v_N', 2 <= N <= %d, strictly increasing in (%g, %g)",
           name, max, lo, hi);
  if (!next_line(r) || !keyword(r, name) || !number(r, &count) || count < 2 || count > max ||
      count != floor(count)) {
    return fail(r, m);
  }
  *n = (int)count;
  for (int i = 0; i < *n; ++i) {
    if (!number(r, &v[i]) || !(v[i] > lo && v[i] < hi) || (i && !(v[i] > v[i - 1]))) {
      return fail(r, m);
    }
  }
  return end_of_line(r) ? SS_OK : fail(r, m);
}

static ss_status read_body(reader *r, ss_profile_table *t) {
  double version, paths;
  if (!next_line(r) || !keyword(r, "subsurf-profile-table") || !number(r, &version) ||
      !end_of_line(r)) {
    return fail(r, "not a subsurf profile table (expected 'subsurf-profile-table VERSION')");
  }
  if (version != SS_PROFILE_TABLE_VERSION) {
    char m[96];
    snprintf(m, sizeof m, "version %g is not supported (expected %d)", version,
             SS_PROFILE_TABLE_VERSION);
    return fail(r, m);
  }
  ss_status st = read_scalar(r, "eta", 0.1, 10.0, &t->eta);
  if (st == SS_OK)
    st = read_scalar(r, "g", -0.99, 0.99, &t->g);
  if (st == SS_OK)
    st = read_scalar(r, "paths", 1.0, 1e18, &paths);
  if (st == SS_OK)
    st = read_grid(r, "u", SS_PROFILE_TABLE_MAX_U, 0.0, 1.0, t->u, &t->n_u);
  double edges[SS_PROFILE_TABLE_MAX_BINS + 1];
  int n_edges = 0;
  if (st == SS_OK)
    st = read_grid(r, "rho", SS_PROFILE_TABLE_MAX_BINS + 1, 0.0, INFINITY, edges, &n_edges);
  if (st != SS_OK) {
    return st;
  }
  t->paths = (uint64_t)paths;
  t->n_bins = n_edges - 1;
  size_t cells = (size_t)t->n_u * (size_t)t->n_bins;
  t->edges = malloc((size_t)n_edges * sizeof *t->edges);
  t->value = malloc(cells * sizeof *t->value);
  t->error = malloc(cells * sizeof *t->error);
  if (!t->edges || !t->value || !t->error) {
    return ss_error_set(r->err, SS_ERR_NO_MEMORY, "%s: out of memory", r->label);
  }
  memcpy(t->edges, edges, (size_t)n_edges * sizeof *edges);
  for (int k = 0; k < t->n_u; ++k) {
    double u;
    char m[160];
    snprintf(m, sizeof m, "expected 'curve %.17g' followed by %d exitances and %d errors (>= 0)",
             t->u[k], t->n_bins, t->n_bins);
    if (!next_line(r) || !keyword(r, "curve") || !number(r, &u) || u != t->u[k]) {
      return fail(r, m);
    }
    for (int i = 0; i < 2 * t->n_bins; ++i) {
      double *dst = i < t->n_bins ? &t->value[(size_t)k * t->n_bins + i]
                                  : &t->error[(size_t)k * t->n_bins + i - t->n_bins];
      if (!number(r, dst) || *dst < 0.0) {
        return fail(r, m);
      }
    }
    if (!end_of_line(r)) {
      return fail(r, m);
    }
  }
  if (next_line(r)) {
    return fail(r, "unexpected line after the curves");
  }
  return SS_OK;
}

/* ln(M / M_dipole) per bin, both averaged over the bin's annulus (so that
 * the ratio is the ratio of point values at the bin's centre to second
 * order, however steep the profile), held at the reliable run's end values
 * outside it, and the bicubic spline over it. */
static int reliable_bin(double value, double error, double dipole) {
  return value > 0.0 && error <= SS_PROFILE_TABLE_MAX_REL_ERROR * value && dipole > 0.0;
}

static ss_status prepare(ss_profile_table *t, const char *label, ss_error *err) {
  size_t cells = (size_t)t->n_u * (size_t)t->n_bins;
  t->log_rho = malloc((size_t)t->n_bins * sizeof *t->log_rho);
  t->log_ratio = malloc(cells * sizeof *t->log_ratio);
  double *rho = malloc((size_t)t->n_bins * sizeof *rho),
         *dip = malloc((size_t)t->n_bins * sizeof *dip);
  ss_status st = SS_OK;
  if (!t->log_rho || !t->log_ratio || !rho || !dip) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "profile table: out of memory");
  }
  for (int i = 0; st == SS_OK && i < t->n_bins; ++i) {
    rho[i] = sqrt(t->edges[i] * t->edges[i + 1]);
    t->log_rho[i] = log(rho[i]);
  }
  for (int k = 0; st == SS_OK && k < t->n_u; ++k) {
    st = dipole_exitance(1.0 - t->u[k] * t->u[k], t->eta, NULL, t->edges, (size_t)t->n_bins, dip,
                         err);
    if (st != SS_OK) {
      break;
    }
    const double *v = t->value + (size_t)k * t->n_bins, *e = t->error + (size_t)k * t->n_bins;
    /* The first reliable bin, then the run of reliable bins after it. */
    int first = 0, last;
    while (first < t->n_bins && !reliable_bin(v[first], e[first], dip[first])) {
      ++first;
    }
    for (last = first;
         last + 1 < t->n_bins && reliable_bin(v[last + 1], e[last + 1], dip[last + 1]); ++last) {
    }
    if (first == t->n_bins) {
      st = ss_error_set(err, SS_ERR_PARSE, "%s: the curve u = %g has no reliable bin", label,
                        t->u[k]);
      break;
    }
    for (int i = 0; i < t->n_bins; ++i) {
      int j = i < first ? first : i > last ? last : i;
      /* gsl_spline2d: z[j * nx + i] for x index i (rho), y index j (u). */
      t->log_ratio[(size_t)k * t->n_bins + i] = log(v[j] / dip[j]);
    }
  }
  free(rho);
  free(dip);
  if (st != SS_OK) {
    return st;
  }
  t->spline = gsl_spline2d_alloc(gsl_interp2d_bicubic, (size_t)t->n_bins, (size_t)t->n_u);
  if (!t->spline || gsl_spline2d_init(t->spline, t->log_rho, t->u, t->log_ratio, (size_t)t->n_bins,
                                      (size_t)t->n_u) != 0) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "profile table: cannot set up its interpolation");
  }
  return SS_OK;
}

ss_status ss_profile_table_parse(const char *text, size_t size, const char *label,
                                 ss_profile_table **out, ss_error *err) {
  *out = NULL;
  size_t body;
  ss_status st = ss_checked_text_verify(text, size, label, &body, err);
  if (st != SS_OK) {
    return st;
  }
  ss_profile_table *t = calloc(1, sizeof *t);
  if (!t) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", label);
  }
  reader r = {.p = text, .end = text + body, .label = label, .err = err};
  st = read_body(&r, t);
  if (st == SS_OK) {
    st = prepare(t, label, err);
  }
  if (st != SS_OK) {
    ss_profile_table_destroy(t);
    return st;
  }
  *out = t;
  return SS_OK;
}

ss_status ss_profile_table_load(const char *path, ss_profile_table **out, ss_error *err) {
  *out = NULL;
  char *text;
  size_t size;
  ss_status st = ss_checked_text_read(path, SS_INPUT_PROFILE_TABLE, &text, &size, err);
  if (st == SS_OK) {
    st = ss_profile_table_parse(text, size, path, out, err);
  }
  free(text);
  return st;
}

void ss_profile_table_destroy(ss_profile_table *t) {
  if (t) {
    gsl_spline2d_free(t->spline);
    free(t->edges);
    free(t->value);
    free(t->error);
    free(t->log_rho);
    free(t->log_ratio);
    free(t);
  }
}

extern const unsigned char ss_profile_table_data[];
extern const size_t ss_profile_table_data_size;

static pthread_once_t builtin_once = PTHREAD_ONCE_INIT;
static ss_profile_table *builtin;
static ss_error builtin_err;

static void builtin_parse(void) {
  ss_profile_table_parse((const char *)ss_profile_table_data, ss_profile_table_data_size,
                         "data/halfspace_profiles.txt (built in)", &builtin, &builtin_err);
}

ss_status ss_profile_table_builtin(const ss_profile_table **out, ss_error *err) {
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

/* ---- evaluation */

double ss_profile_table_eta(const ss_profile_table *t) { return t->eta; }
double ss_profile_table_g(const ss_profile_table *t) { return t->g; }

void ss_profile_table_albedo_range(const ss_profile_table *t, double *lo, double *hi) {
  *lo = 1.0 - t->u[t->n_u - 1] * t->u[t->n_u - 1];
  *hi = 1.0 - t->u[0] * t->u[0];
}

void ss_profile_table_eval(const ss_profile_table *t, double alpha_prime, const double *rho,
                           size_t n, double *out) {
  double u = sqrt(fmax(1.0 - alpha_prime, 0.0));
  u = fmin(fmax(u, t->u[0]), t->u[t->n_u - 1]);
  double ap = 1.0 - u * u;
  ss_error err;
  if (dipole_exitance(ap, t->eta, rho, NULL, n, out, &err) != SS_OK) {
    /* Only an allocation of the dipole's small state can fail here. */
    for (size_t i = 0; i < n; ++i) {
      out[i] = NAN;
    }
    return;
  }
  double x_lo = t->log_rho[0], x_hi = t->log_rho[t->n_bins - 1];
  for (size_t i = 0; i < n; ++i) {
    double x = rho[i] > 0.0 ? fmin(fmax(log(rho[i]), x_lo), x_hi) : x_lo;
    out[i] *= exp(gsl_spline2d_eval(t->spline, x, u, NULL, NULL));
  }
}
