/* The `table-gwc` model: Ferrier's non-perpendicular multiple-scattering
 * table (table_gwc.h), with subsurf's two-lobe azimuthal fit unless the
 * loaded file holds the paper's three-anchor GWC.
 *
 * | option     | meaning                                                     |
 * |------------|-------------------------------------------------------------|
 * | sigma_s,   | per channel: albedo rho = sigma_s/sigma_t picks the table   |
 * | sigma_a    | cell, sigma_t scales radii (the table is in sigma_t = 1)    |
 * | g          | phase mean cosine the table is built for (one table per     |
 * |            | distinct g among the channels)                              |
 * | eta        | n_inside / n_outside, > 1                                   |
 * | table      | a `subsurf table build` file to load instead of building    |
 * |            | (~5 s); its eta and g must match the material's             |
 *
 * Without a file the full tables come from params.tables when set (shared
 * by every material of the scene with the same eta and g, table_cache.h).
 *
 * S = Ft(w_i) S_ms(r, phi; theta_i) Ft(w_o) / (pi (1 - 2 C1(1/eta))):
 * multiple scattering only, as in the paper. Given only the exit point,
 * entry points are drawn by the radius marginal of the paper's path-tracing
 * sampler (sec. 7.1: theta_i from the effective albedo, r, then a uniform
 * azimuth phi'), whose density is exact in closed form. */
#include "subsurf/table_cache.h"
#include "subsurf/table_file.h"
#include "subsurf/table_gwc.h"

#include "bssrdf/bssrdf_util.h"
#include "bssrdf/entry_geometry.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  double eta, t_out;
  /* Per channel, the table at the channel's albedo (a 10 KiB slice). */
  ss_table_gwc *table[SS_BSSRDF_CHANNELS];
  double rho[SS_BSSRDF_CHANNELS], sigma_t[SS_BSSRDF_CHANNELS];
} gwc_model;

static void gwc_destroy(void *state) {
  gwc_model *m = state;
  if (!m) {
    return;
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_table_gwc_destroy(m->table[c]);
  }
  free(m);
}

static const ss_option gwc_options[] = {
    {.name = "table",
     .type = SS_OPTION_STRING,
     .def = "",
     .meta = "FILE",
     .help = "a `subsurf table build` file to load instead of building"},
    {0},
};

static ss_status gwc_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  const char *table_path = ss_bssrdf_params_string(p, &gwc_options[0]);
  ss_status st = ss_bssrdf_params_check(p, "table-gwc", err);
  if (st != SS_OK) {
    return st;
  }
  if (!(p->eta > 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "table-gwc: eta must be > 1 (Ferrier's table), got %g", p->eta);
  }
  gwc_model *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table-gwc: out of memory");
  }
  m->eta = p->eta;
  m->t_out = ss_fresnel_transmission_out(p->eta);
  /* Full tables, one per distinct g (or the file's), sliced per channel. */
  ss_table_gwc *full[SS_BSSRDF_CHANNELS] = {NULL, NULL, NULL};
  int n_full = 0;
  if (table_path[0]) {
    st = ss_table_gwc_load(table_path, &full[0], err);
    n_full = st == SS_OK;
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS && st == SS_OK; ++c) {
    m->sigma_t[c] = p->medium.sigma_s.c[c] + p->medium.sigma_a.c[c];
    m->rho[c] = p->medium.sigma_s.c[c] / m->sigma_t[c];
    const ss_table_gwc *src = NULL;
    if (table_path[0]) {
      st = ss_table_file_check_material(table_path, full[0]->eta, full[0]->g, p->eta,
                                        p->medium.g.c[c], err);
      src = full[0];
    }
    if (st == SS_OK && !src && p->tables) {
      st =
          ss_table_cache_gwc(p->tables, p->eta, p->medium.g.c[c], SS_TABLE_GWC_TWO_LOBE, &src, err);
    }
    for (int i = 0; i < n_full && !src; ++i) {
      if (full[i]->g == p->medium.g.c[c]) {
        src = full[i];
      }
    }
    if (st == SS_OK && !src) {
      st = ss_table_gwc_build(p->eta, p->medium.g.c[c], SS_TABLE_GWC_TWO_LOBE, &full[n_full], err);
      if (st == SS_OK) {
        src = full[n_full++];
      }
    }
    if (st == SS_OK) {
      st = ss_table_gwc_slice(src, m->rho[c], &m->table[c], err);
    }
  }
  for (int i = 0; i < n_full; ++i) {
    ss_table_gwc_destroy(full[i]);
  }
  if (st != SS_OK) {
    gwc_destroy(m);
    return st;
  }
  *state = m;
  return SS_OK;
}

/* S_ms in world units (the table is in sigma_t = 1). */
static double ms_world(const gwc_model *m, int c, double theta, double r, double phi) {
  double st = m->sigma_t[c];
  return st * st * ss_table_gwc_eval(m->table[c], m->rho[c], theta, st * r, phi);
}

static void gwc_eval(const void *state, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]) {
  const gwc_model *m = state;
  double theta, r, phi;
  ss_entry_geometry(q, &theta, &r, &phi);
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), m->eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), m->eta) / (SS_PI * m->t_out);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s[c] = f == 0.0 ? 0.0 : f * ms_world(m, c, theta, r, phi);
  }
}

static int gwc_sample(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel, double u1,
                      double u2, ss_bssrdf_entry *e) {
  const gwc_model *m = state;
  double st = m->sigma_t[channel];
  double r = ss_table_gwc_sample_radial(m->table[channel], m->rho[channel], u1);
  if (!(r > 0.0)) {
    return 0;
  }
  e->r = r / st;
  e->phi = 2.0 * SS_PI * u2;
  e->pdf = st * st * ss_table_gwc_pdf_radial(m->table[channel], m->rho[channel], r);
  return e->pdf > 0.0;
}

static double gwc_pdf(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel, double r,
                      double phi) {
  const gwc_model *m = state;
  double st = m->sigma_t[channel];
  return st * st * ss_table_gwc_pdf_radial(m->table[channel], m->rho[channel], st * r);
}

static double gwc_max_radius(const void *state, int channel) {
  const gwc_model *m = state;
  double r = ss_table_gwc_sample_radial(m->table[channel], m->rho[channel], 0.9999);
  return r > 0.0 ? r / m->sigma_t[channel] : 0.0;
}

static void gwc_total(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const gwc_model *m = state;
  double ft = ss_ft_outside(cos_i, m->eta), theta = acos(fmin(1.0, fabs(cos_i)));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ft * ss_table_gwc_albedo(m->table[c], m->rho[c], theta);
  }
}

static void gwc_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const gwc_model *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ss_table_gwc_albedo(m->table[c], m->rho[c], 0.0);
  }
}

static void gwc_profile(const void *state, int channel, double r, ss_bssrdf_profile_value *out) {
  const gwc_model *m = state;
  out->value = out->ms = ms_world(m, channel, 0.0, r, 0.0);
  out->ss = 0.0;
  out->t = 0.0;
}

static void gwc_exitance(const void *state, double cos_i, double x, double y,
                         double out[SS_BSSRDF_CHANNELS]) {
  const gwc_model *m = state;
  double ft = ss_ft_outside(cos_i, m->eta), theta = acos(fmin(1.0, fabs(cos_i)));
  double r = hypot(x, y), phi = fabs(atan2(y, x));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ft == 0.0 ? 0.0 : ft * ms_world(m, c, theta, r, phi);
  }
}

const ss_bssrdf_ops ss_bssrdf_model_table_gwc = {
    .name = "table-gwc",
    .summary = "Ferrier's (rho, theta, r) PBD table, azimuthal lobes, multiple scattering "
               "(Ferrier2016)",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_ANGULAR | SS_BSSRDF_TABULATED,
    .options = gwc_options,
    .create = gwc_create,
    .destroy = gwc_destroy,
    .eval = gwc_eval,
    .sample_entry = gwc_sample,
    .pdf_entry = gwc_pdf,
    .max_radius = gwc_max_radius,
    .total_reflectance = gwc_total,
    .rd = gwc_rd,
    .profile = gwc_profile,
    .exitance = gwc_exitance,
};
