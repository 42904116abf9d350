/* The flat interface's models and presets (ffi.h): a thin layer over the
 * BSSRDF registry (bssrdf.h) and the measured presets (media.h). */
#include "subsurf/ffi.h"

#include "ffi/ffi_medium.h"

#include "subsurf/bssrdf.h"
#include "subsurf/media.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct ss_ffi_model {
  ss_bssrdf *bssrdf;
};

const char *ss_ffi_version(void) { return SUBSURF_VERSION; }

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
  if (!(scale > 0.0) || !(scale < 1e12) || !(g > -1.0 && g < 1.0)) {
    snprintf(msg, sizeof msg, "preset '%s': scale must be in (0, 1e12) and g in (-1, 1)", name);
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

ss_ffi_model *ss_ffi_model_create(const char *name, const double sigma_s[3],
                                  const double sigma_a[3], const double g[3], double eta,
                                  const char *const *option_names, const char *const *option_values,
                                  int n_options, char *err, size_t err_size) {
  ss_error e;
  const ss_bssrdf_ops *ops = name ? ss_bssrdf_model_find(name) : NULL;
  if (!ops) {
    char names[2048];
    ss_bssrdf_model_names(names, sizeof names);
    if (err && err_size > 0) {
      snprintf(err, err_size, "unknown model '%s' (models: %s)", name ? name : "(null)", names);
    }
    return NULL;
  }
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  p.medium = ss_ffi_medium(sigma_s, sigma_a, g);
  p.eta = eta;
  for (int i = 0; i < n_options; i++) {
    if (ss_bssrdf_params_set_option(&p, ops, option_names[i], option_values[i], &e) != SS_OK) {
      fail(err, err_size, e.status, e.message);
      return NULL;
    }
  }
  ss_ffi_model *m = calloc(1, sizeof *m);
  if (!m) {
    fail(err, err_size, SS_ERR_NO_MEMORY, "out of memory");
    return NULL;
  }
  if (ss_bssrdf_create_ops(ops, &p, &m->bssrdf, &e) != SS_OK) {
    fail(err, err_size, e.status, e.message);
    free(m);
    return NULL;
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

void ss_ffi_model_profile(const ss_ffi_model *m, int channel, const double *r, size_t n,
                          double *value, double *ms, double *ss) {
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
}

void ss_ffi_model_total_reflectance(const ss_ffi_model *m, double cos_i, double out[3]) {
  ss_bssrdf_total_reflectance(m->bssrdf, cos_i, out);
}

void ss_ffi_model_exitance(const ss_ffi_model *m, double cos_i, const double *x, const double *y,
                           size_t n, double *out) {
  for (size_t i = 0; i < n; i++) {
    ss_bssrdf_exitance(m->bssrdf, cos_i, x[i], y[i], out + 3 * i);
  }
}

void ss_ffi_model_radiance(const ss_ffi_model *m, double cos_i, const double *x, const double *y,
                           const double *w_o, size_t n, double *out) {
  for (size_t i = 0; i < n; i++) {
    ss_vec3 w = ss_vec3_make(w_o[3 * i], w_o[3 * i + 1], w_o[3 * i + 2]);
    ss_bssrdf_query q = ss_bssrdf_halfspace_query(cos_i, x[i], y[i], w);
    ss_bssrdf_eval(m->bssrdf, &q, out + 3 * i);
  }
}
