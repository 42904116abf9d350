/* The flat interface's models and presets (ffi.h): a thin layer over the
 * BSSRDF registry (bssrdf.h) and the measured presets (media.h). */
#include "subsurf/ffi.h"

#include "ffi/ffi_medium.h"

#include "subsurf/bssrdf.h"
#include "subsurf/halfspace.h"
#include "subsurf/media.h"
#include "subsurf/version.h"

#include <math.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct ss_ffi_model {
  ss_bssrdf *bssrdf;
};

const char *ss_ffi_version(void) { return ss_version(); }

ss_medium_optics ss_ffi_medium(const double sigma_s[3], const double sigma_a[3],
                               const double g[3]) {
  ss_medium_optics m = ss_medium_optics_gray(1.0, 0.0, 0.0, SS_PHASE_HG);
  for (int c = 0; c < 3; c++) {
    m.sigma_s.c[c] = sigma_s[c];
    m.sigma_a.c[c] = sigma_a[c];
    m.g.c[c] = g[c];
  }
  return m;
}

/* Copies a message into the caller's buffer. */
static int fail(char *err, size_t err_size, int status, const char *message) {
  if (err && err_size > 0) {
    snprintf(err, err_size, "%s", message);
  }
  return status;
}

/* Writes count names, separated by '\n', into buf (truncated at size). */
static void join_names(char *buf, size_t size, size_t count, const char *(*name_at)(size_t)) {
  if (!buf || size == 0) {
    return;
  }
  size_t used = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < count && used < size; i++) {
    int n = snprintf(buf + used, size - used, "%s%s", i ? "\n" : "", name_at(i));
    used += n > 0 ? (size_t)n : 0;
  }
}

static const char *model_name_at(size_t i) { return ss_bssrdf_model_at(i)->name; }
static const char *preset_name_at(size_t i) { return ss_medium_preset_at(i)->name; }

void ss_ffi_model_names(char *buf, size_t size) {
  join_names(buf, size, ss_bssrdf_model_count(), model_name_at);
}

void ss_ffi_preset_names(char *buf, size_t size) {
  join_names(buf, size, ss_medium_preset_count(), preset_name_at);
}

int ss_ffi_preset(const char *name, double scale, double g, double sigma_s[3], double sigma_a[3],
                  double *eta, char *err, size_t err_size) {
  const ss_medium_preset *p = name ? ss_medium_preset_find(name) : NULL;
  char msg[SS_ERROR_MESSAGE_SIZE];
  if (!p) {
    snprintf(msg, sizeof msg, "unknown medium preset '%s'", name ? name : "(null)");
    return fail(err, err_size, SS_ERR_INVALID_ARGUMENT, msg);
  }
  if (!(scale > 0.0 && scale <= SS_HALFSPACE_MAX_COEFF)) {
    snprintf(msg, sizeof msg, "preset '%s': scale must be in (0, %g] (got %g)", name,
             SS_HALFSPACE_MAX_COEFF, scale);
    return fail(err, err_size, SS_ERR_INVALID_ARGUMENT, msg);
  }
  if (!(g > -1.0 && g < 1.0)) {
    snprintf(msg, sizeof msg, "preset '%s': g must be in (-1, 1) (got %g)", name, g);
    return fail(err, err_size, SS_ERR_INVALID_ARGUMENT, msg);
  }
  ss_medium_optics m = ss_medium_optics_from_preset(p, scale, g, SS_PHASE_HG);
  for (int c = 0; c < 3; c++) {
    sigma_s[c] = m.sigma_s.c[c];
    sigma_a[c] = m.sigma_a.c[c];
  }
  *eta = p->eta;
  return 0;
}

static ss_status create(const char *name, const double sigma_s[3], const double sigma_a[3],
                        const double g[3], double eta, const char *const *option_names,
                        const char *const *option_values, int n_options, ss_ffi_model **out,
                        ss_error *e) {
  const ss_bssrdf_ops *ops = name ? ss_bssrdf_model_find(name) : NULL;
  if (!ops) {
    char names[512];
    ss_bssrdf_model_names(names, sizeof names);
    return ss_error_set(e, SS_ERR_INVALID_ARGUMENT, "unknown model '%.200s' (models: %s)",
                        name ? name : "(null)", names);
  }
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  p.medium = ss_ffi_medium(sigma_s, sigma_a, g);
  p.eta = eta;
  /* Every channel's medium within the ranges `subsurf model` takes. */
  ss_halfspace_params range;
  ss_halfspace_params_default(&range);
  range.medium = p.medium;
  range.eta = eta;
  for (range.channel = 0; range.channel < 3; range.channel++) {
    ss_status st = ss_halfspace_validate(&range, e);
    if (st != SS_OK) {
      return st;
    }
  }
  for (int i = 0; i < n_options; i++) {
    ss_status st = ss_bssrdf_params_set_option(&p, ops, option_names[i], option_values[i], e);
    if (st != SS_OK) {
      return st;
    }
  }
  ss_ffi_model *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(e, SS_ERR_NO_MEMORY, "out of memory");
  }
  ss_status st = ss_bssrdf_create_ops(ops, &p, &m->bssrdf, e);
  if (st != SS_OK) {
    free(m);
    return st;
  }
  *out = m;
  return SS_OK;
}

ss_ffi_model *ss_ffi_model_create(const char *name, const double sigma_s[3],
                                  const double sigma_a[3], const double g[3], double eta,
                                  const char *const *option_names, const char *const *option_values,
                                  int n_options, int *status, char *err, size_t err_size) {
  ss_error e;
  ss_ffi_model *m = NULL;
  ss_status st =
      create(name, sigma_s, sigma_a, g, eta, option_names, option_values, n_options, &m, &e);
  if (status) {
    *status = (int)st;
  }
  if (st != SS_OK) {
    fail(err, err_size, (int)st, e.message);
  }
  return m;
}

void ss_ffi_model_destroy(ss_ffi_model *m) {
  if (m) {
    ss_bssrdf_destroy(m->bssrdf);
    free(m);
  }
}

unsigned ss_ffi_model_flags(const ss_ffi_model *m) { return ss_bssrdf_flags(m->bssrdf); }

/* The query ranges of the command line's `subsurf model`: radii and
 * positions within the reference's length limit, theta-i in [0, 90) and
 * theta-o in (-90, 90) degrees. */
#define LMAX SS_HALFSPACE_MAX_LENGTH

static int in_range(double v, double lo, double hi) { return v >= lo && v <= hi; }

static int bad(char *err, size_t err_size, const char *what, double lo, double hi, double got) {
  char msg[256];
  snprintf(msg, sizeof msg, "%s must be in [%g, %g] (got %g)", what, lo, hi, got);
  return fail(err, err_size, SS_ERR_INVALID_ARGUMENT, msg);
}

static int bad_cos_i(double cos_i, char *err, size_t err_size) {
  if (cos_i > 0.0 && cos_i <= 1.0) {
    return 0;
  }
  char msg[128];
  snprintf(msg, sizeof msg, "cos_i must be in (0, 1] (got %g)", cos_i);
  return fail(err, err_size, SS_ERR_INVALID_ARGUMENT, msg);
}

/* The first of n points outside [-LMAX, LMAX] in x or y, as an error. */
static int bad_points(const double *x, const double *y, size_t n, char *err, size_t err_size) {
  for (size_t i = 0; i < n; i++) {
    if (!in_range(x[i], -LMAX, LMAX)) {
      return bad(err, err_size, "x", -LMAX, LMAX, x[i]);
    }
    if (!in_range(y[i], -LMAX, LMAX)) {
      return bad(err, err_size, "y", -LMAX, LMAX, y[i]);
    }
  }
  return 0;
}

int ss_ffi_model_profile(const ss_ffi_model *m, int channel, const double *r, size_t n,
                         double *value, double *ms, double *ss, char *err, size_t err_size) {
  if (channel < 0 || channel > 2) {
    char msg[64];
    snprintf(msg, sizeof msg, "channel must be 0, 1 or 2 (got %d)", channel);
    return fail(err, err_size, SS_ERR_INVALID_ARGUMENT, msg);
  }
  for (size_t i = 0; i < n; i++) {
    if (!in_range(r[i], 0.0, LMAX)) {
      return bad(err, err_size, "r", 0.0, LMAX, r[i]);
    }
  }
  for (size_t i = 0; i < n; i++) {
    ss_bssrdf_profile_value v;
    ss_bssrdf_profile(m->bssrdf, channel, r[i], &v);
    if (value) {
      value[i] = v.value;
    }
    if (ms) {
      ms[i] = v.ms;
    }
    if (ss) {
      ss[i] = v.ss;
    }
  }
  return 0;
}

int ss_ffi_model_total_reflectance(const ss_ffi_model *m, double cos_i, double out[3], char *err,
                                   size_t err_size) {
  int rc = bad_cos_i(cos_i, err, err_size);
  if (rc == 0) {
    ss_bssrdf_total_reflectance(m->bssrdf, cos_i, out);
  }
  return rc;
}

int ss_ffi_model_exitance(const ss_ffi_model *m, double cos_i, const double *x, const double *y,
                          size_t n, double *out, char *err, size_t err_size) {
  int rc = bad_cos_i(cos_i, err, err_size);
  if (rc == 0) {
    rc = bad_points(x, y, n, err, err_size);
  }
  for (size_t i = 0; rc == 0 && i < n; i++) {
    ss_bssrdf_exitance(m->bssrdf, cos_i, x[i], y[i], out + 3 * i);
  }
  return rc;
}

int ss_ffi_model_radiance(const ss_ffi_model *m, double cos_i, const double *x, const double *y,
                          const double *w_o, size_t n, double *out, char *err, size_t err_size) {
  int rc = bad_cos_i(cos_i, err, err_size);
  if (rc == 0) {
    rc = bad_points(x, y, n, err, err_size);
  }
  for (size_t i = 0; rc == 0 && i < n; i++) {
    ss_vec3 w = ss_vec3_make(w_o[3 * i], w_o[3 * i + 1], w_o[3 * i + 2]);
    double len = sqrt(ss_vec3_dot(w, w));
    if (!(fabs(len - 1.0) <= 1e-6) || !(w.z > 0.0)) {
      char msg[160];
      snprintf(msg, sizeof msg, "w_o must be unit vectors with z > 0 (got %g, %g, %g at point %zu)",
               w.x, w.y, w.z, i);
      rc = fail(err, err_size, SS_ERR_INVALID_ARGUMENT, msg);
    }
  }
  for (size_t i = 0; rc == 0 && i < n; i++) {
    ss_vec3 w = ss_vec3_make(w_o[3 * i], w_o[3 * i + 1], w_o[3 * i + 2]);
    ss_bssrdf_query q = ss_bssrdf_halfspace_query(cos_i, x[i], y[i], w);
    ss_bssrdf_eval(m->bssrdf, &q, out + 3 * i);
  }
  return rc;
}
