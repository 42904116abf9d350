/* The `table-radial` model: pbrt-v3's tabulated BSSRDF (table_radial.h).
 *
 * | option     | meaning                                                     |
 * |------------|-------------------------------------------------------------|
 * | sigma_s,   | per channel: albedo rho = sigma_s/sigma_t picks the table   |
 * | sigma_a    | row, sigma_t scales radii (the table is in sigma_t = 1)     |
 * | g          | phase mean cosine the table is built for (one table per     |
 * |            | distinct g among the channels)                              |
 * | eta        | n_inside / n_outside                                        |
 * | table      | a `subsurf table build --kind radial` file to load instead  |
 * |            | of building (its eta and g must match the material's)       |
 *
 * Without a file the tables come from params.tables when set (shared by
 * every material of the scene with the same eta and g, table_cache.h).
 *
 * S = Ft(w_i) S_p(r) Ft(w_o) / (pi (1 - 2 C1(1/eta))) with S_p the tabulated
 * multiple + single scattering of normal incidence. Entry radii are drawn
 * from the inverse CDF of 2 pi r S_p tabulated per material on a geometric
 * grid (profile_sampler.h, as the analytic radial models do): a table
 * lookup per sample and per pdf instead of pbrt's Catmull-Rom inversion and
 * 2-D interpolation, which took a third of the render's time. */
#include "subsurf/table_cache.h"
#include "subsurf/table_file.h"
#include "subsurf/table_radial.h"

#include "bssrdf/bssrdf_util.h"
#include "bssrdf/profile_sampler.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  ss_profile_sampler sampler; /* first: the ss_profile_sampler hooks read it */
  double eta, t_out;
  int n_tables; /* the tables this model owns (none when shared) */
  ss_table_radial *tables[SS_BSSRDF_CHANNELS];
  const ss_table_radial *table[SS_BSSRDF_CHANNELS]; /* per channel */
  double rho[SS_BSSRDF_CHANNELS], sigma_t[SS_BSSRDF_CHANNELS];
} radial_model;

static void radial_destroy(void *state) {
  radial_model *m = state;
  if (!m) {
    return;
  }
  for (int i = 0; i < m->n_tables; ++i) {
    ss_table_radial_destroy(m->tables[i]);
  }
  free(m);
}

static const ss_option radial_options[] = {
    {.name = "table",
     .type = SS_OPTION_STRING,
     .def = "",
     .meta = "FILE",
     .help = "a `subsurf table build --kind radial` file to load instead of building"},
    {0},
};

/* S_p in world units: the table is in sigma_t = 1 (PBR 3rd ed. sec. 15.5.7). */
static double sp_world(const radial_model *m, int c, double r) {
  double st = m->sigma_t[c];
  return st * st * ss_table_radial_sp(m->table[c], m->rho[c], st * r);
}

static void sp_shape(const void *ctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = sp_world(ctx, c, r);
  }
}

/* The sampler of 2 pi r S_p per channel, with the classical dipole's
 * sigma_tr / sigma_t' exponential mixture as its defensive share (Jensen et
 * al. 2001 eq. 4 coefficients; pbrt's sampler where a one-use model skips
 * the table). */
static void fit_sampler(radial_model *m, const ss_bssrdf_params *p) {
  ss_radial_mix mix[SS_BSSRDF_CHANNELS];
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double sa = p->medium.sigma_a.c[c];
    double stp = p->medium.sigma_s.c[c] * (1.0 - p->medium.g.c[c]) + sa;
    ss_radial_mix_init_diffusion(&mix[c], sqrt(3.0 * sa * stp), stp);
  }
  if (p->single_use) {
    ss_profile_sampler_init_mixture(&m->sampler, mix);
  } else {
    ss_profile_sampler_init_diffusion(&m->sampler, sp_shape, m, mix);
  }
}

static ss_status radial_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  const char *table_path = ss_bssrdf_params_string(p, &radial_options[0]);
  ss_status st = ss_bssrdf_params_check(p, "table-radial", err);
  if (st != SS_OK) {
    return st;
  }
  radial_model *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table-radial: out of memory");
  }
  m->eta = p->eta;
  m->t_out = ss_fresnel_transmission_out(p->eta);
  if (table_path[0]) {
    st = ss_table_radial_load(table_path, &m->tables[0], err);
    if (st == SS_OK) {
      m->n_tables = 1;
    }
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS && st == SS_OK; ++c) {
    m->sigma_t[c] = p->medium.sigma_s.c[c] + p->medium.sigma_a.c[c];
    m->rho[c] = p->medium.sigma_s.c[c] / m->sigma_t[c];
    if (table_path[0]) {
      st = ss_table_file_check_material(table_path, m->tables[0]->eta, m->tables[0]->g, p->eta,
                                        p->medium.g.c[c], err);
      m->table[c] = m->tables[0];
      continue;
    }
    if (p->tables) {
      st = ss_table_cache_radial(p->tables, p->eta, p->medium.g.c[c], &m->table[c], err);
      continue;
    }
    for (int i = 0; i < m->n_tables; ++i) {
      if (m->tables[i]->g == p->medium.g.c[c]) {
        m->table[c] = m->tables[i];
      }
    }
    if (!m->table[c]) {
      st = ss_table_radial_build(p->eta, p->medium.g.c[c], &m->tables[m->n_tables], err);
      if (st == SS_OK) {
        m->table[c] = m->tables[m->n_tables++];
      }
    }
  }
  if (st != SS_OK) {
    radial_destroy(m);
    return st;
  }
  fit_sampler(m, p);
  *state = m;
  return SS_OK;
}

static void radial_eval(const void *state, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]) {
  const radial_model *m = state;
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), m->eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), m->eta) / (SS_PI * m->t_out);
  double r = ss_vec3_length(ss_vec3_sub(q->x_o, q->x_i));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s[c] = f * sp_world(m, c, r);
  }
}

static void radial_total(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const radial_model *m = state;
  double ft = ss_ft_outside(cos_i, m->eta);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ft * ss_table_radial_rho_eff(m->table[c], m->rho[c]);
  }
}

static void radial_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const radial_model *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ss_table_radial_rho_eff(m->table[c], m->rho[c]);
  }
}

/* The table stores the sum of both terms: reported as `ms`, `ss` = 0. */
static void radial_profile(const void *state, int channel, double r, ss_bssrdf_profile_value *out) {
  const radial_model *m = state;
  out->value = out->ms = sp_world(m, channel, r);
  out->ss = 0.0;
  out->t = 0.0;
}

static void radial_exitance(const void *state, double cos_i, double x, double y,
                            double out[SS_BSSRDF_CHANNELS]) {
  const radial_model *m = state;
  double ft = ss_ft_outside(cos_i, m->eta), r = hypot(x, y);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ft * sp_world(m, c, r);
  }
}

const ss_bssrdf_ops ss_bssrdf_model_table_radial = {
    .name = "table-radial",
    .summary = "pbrt-v3's tabulated PBD, normal incidence, Catmull-Rom (Ferrier2016 sec. 2.2)",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_TABULATED,
    .options = radial_options,
    .create = radial_create,
    .destroy = radial_destroy,
    .eval = radial_eval,
    .sample_entry = ss_profile_sampler_sample_entry,
    .pdf_entry = ss_profile_sampler_pdf_entry,
    .max_radius = ss_profile_sampler_max_radius,
    .total_reflectance = radial_total,
    .rd = radial_rd,
    .profile = radial_profile,
    .exitance = radial_exitance,
};
