/* Photon beam diffusion BSSRDF (Habel2013),
 * evaluated directly by quadrature along the refracted beam (pbd.h).
 *
 * | option       | meaning                                                   |
 * |--------------|-----------------------------------------------------------|
 * | sigma_s, g   | scattering and phase mean cosine (reduced for diffusion,  |
 * |              | real Henyey-Greenstein phase for single scattering)       |
 * | sigma_a      | absorption                                                |
 * | eta          | n_inside / n_outside                                      |
 * | beam_samples | option: beam quadrature effort, ceil(n / 3) GL nodes      |
 * |              | on each side of the beam's closest approach (34 for 100)  |
 * | tabulate     | option: eval through a per-material (theta, phi, r) table |
 * |              | of S_ms and S_ss (pbd_table.h, built at creation, ~0.2 s) |
 * |              | instead of the beam integral at every call                |
 *
 * S = Ft(w_i) [S_ms(r, phi; theta_i) + S_ss(r)] Ft(w_o) / (pi (1 - 2 C1(1/eta))):
 * the exitance is Ft(w_i) S_p and leaves with pbrt-v3's normalised Fresnel
 * lobe. The multiple-scattering term sees the incidence angle and the exit
 * azimuth from the incidence plane; the single-scattering term is pbrt-v3's
 * normal-incidence profile at every angle. Entry points are sampled from a
 * radius fitted to the normal-incidence profile S_p(r) (profile_sampler.h)
 * with a mixture of area exponentials (rates sigma_tr and sigma_t') as its
 * defensive share, uniform in azimuth. Its point source (bssrdf.h) is the
 * one the beam integral integrates. */
#include "subsurf/pbd.h"

#include "bssrdf/entry_geometry.h"
#include "bssrdf/pbd_table.h"
#include "bssrdf/profile_sampler.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  ss_profile_sampler sampler; /* first: the ss_profile_sampler hooks read it */
  double eta, t_out;
  ss_pbd pbd[SS_BSSRDF_CHANNELS];
  double rho_eff[SS_BSSRDF_CHANNELS];
  double ss_total[SS_BSSRDF_CHANNELS];     /* int 2 pi r E_ss dr */
  ss_pbd_table *table[SS_BSSRDF_CHANNELS]; /* NULL: direct evaluation */
} pbd_model;

static void pbd_destroy(void *state) {
  pbd_model *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    free(m->table[c]);
  }
  free(m);
}

/* S_p(r) = E_ms + E_ss at normal incidence (the sampler's shape). */
static void normal_profile(const void *ctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  const pbd_model *m = ctx;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_pbd_beam beam = ss_pbd_beam_make(&m->pbd[c], 0.0);
    out[c] = ss_pbd_ms(&m->pbd[c], &beam, r, 0.0) + ss_pbd_ss(&m->pbd[c], r);
  }
}

static const ss_option pbd_options[] = {
    {.name = "beam_samples",
     .type = SS_OPTION_INT,
     .def = "100",
     .lo = 6,
     .hi = 3 * SS_PBD_MAX_NODES,
     .help = "depth samples along the refracted beam"},
    {.name = "tabulate",
     .type = SS_OPTION_BOOL,
     .def = "true",
     .help = "evaluate S through a per-material (theta, phi, r) table built at creation (~0.2 s) "
             "instead of the beam integral"},
    {0},
};

static ss_status pbd_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  ss_status st = ss_bssrdf_params_check(p, "pbd", err);
  if (st != SS_OK) {
    return st;
  }
  int beam_samples = ss_bssrdf_params_int(p, &pbd_options[0]);
  pbd_model *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "pbd: out of memory");
  }
  m->eta = p->eta;
  m->t_out = ss_fresnel_transmission_out(p->eta);
  int nodes = (beam_samples + 2) / 3;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    st = ss_pbd_init(&m->pbd[c], p->medium.sigma_s.c[c], p->medium.sigma_a.c[c], p->medium.g.c[c],
                     p->eta, nodes, err);
    if (st != SS_OK) {
      free(m);
      return st;
    }
    m->rho_eff[c] = ss_pbd_effective_albedo(&m->pbd[c]);
    m->ss_total[c] = m->rho_eff[c] - ss_pbd_ms_albedo(&m->pbd[c], 0.0);
    const ss_pbd *q = &m->pbd[c];
    double rates[2] = {fmax(q->sigma_tr, 1e-3 * q->sigma_t_p), q->sigma_t_p};
    double weights[2] = {0.75, 0.25};
    ss_radial_mix_init(&m->sampler.mix[c], 2, rates, weights);
  }
  if (p->single_use) {
    ss_profile_sampler_init_mixture(&m->sampler, m->sampler.mix);
  } else {
    ss_profile_sampler_init_diffusion(&m->sampler, normal_profile, m, m->sampler.mix);
  }
  if (ss_bssrdf_params_bool(p, &pbd_options[1]) && !p->single_use) {
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      m->table[c] = malloc(sizeof *m->table[c]);
      if (!m->table[c]) {
        pbd_destroy(m);
        return ss_error_set(err, SS_ERR_NO_MEMORY, "pbd: out of memory");
      }
      /* the sampler's range: below the core, beyond the tail */
      ss_pbd_table_build(m->table[c], &m->pbd[c], 0.005 / m->pbd[c].sigma_t_p,
                         2.0 * ss_radial_mix_max_radius(&m->sampler.mix[c]));
    }
  }
  *state = m;
  return SS_OK;
}

static void pbd_eval(const void *state, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]) {
  const pbd_model *m = state;
  double theta, r, phi;
  ss_entry_geometry(q, &theta, &r, &phi);
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), m->eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), m->eta) / (SS_PI * m->t_out);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    if (f == 0.0) {
      s[c] = 0.0;
    } else if (m->table[c]) {
      s[c] = f * ss_pbd_table_eval(m->table[c], &m->pbd[c], theta, r, phi);
    } else {
      ss_pbd_beam beam = ss_pbd_beam_make(&m->pbd[c], theta);
      s[c] = f * (ss_pbd_ms(&m->pbd[c], &beam, r, phi) + ss_pbd_ss(&m->pbd[c], r));
    }
  }
}

static void pbd_total(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const pbd_model *m = state;
  double ft = ss_ft_outside(cos_i, m->eta);
  double theta = acos(fmin(1.0, fabs(cos_i)));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ft == 0.0 ? 0.0 : ft * (ss_pbd_ms_albedo(&m->pbd[c], theta) + m->ss_total[c]);
  }
}

static void pbd_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const pbd_model *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = m->rho_eff[c];
  }
}

static void pbd_profile(const void *state, int channel, double r, ss_bssrdf_profile_value *out) {
  const pbd_model *m = state;
  ss_pbd_beam beam = ss_pbd_beam_make(&m->pbd[channel], 0.0);
  out->ms = ss_pbd_ms(&m->pbd[channel], &beam, r, 0.0);
  out->ss = ss_pbd_ss(&m->pbd[channel], r);
  out->value = out->ms + out->ss;
  out->t = 0.0;
}

static void pbd_exitance(const void *state, double cos_i, double x, double y,
                         double out[SS_BSSRDF_CHANNELS]) {
  const pbd_model *m = state;
  double ft = ss_ft_outside(cos_i, m->eta);
  double theta = acos(fmin(1.0, fabs(cos_i))), r = hypot(x, y), phi = atan2(y, x);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_pbd_beam beam = ss_pbd_beam_make(&m->pbd[c], theta);
    out[c] =
        ft == 0.0 ? 0.0 : ft * (ss_pbd_ms(&m->pbd[c], &beam, r, phi) + ss_pbd_ss(&m->pbd[c], r));
  }
}

/* The point source the beam integrates (bssrdf.h; pbd.h): exitance at
 * lateral distance r per unit power scattered at depth z. */
static void pbd_point_source(const void *state, double z, double r,
                             double out[SS_BSSRDF_CHANNELS]) {
  const pbd_model *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ss_pbd_point_source(&m->pbd[c], z, r);
  }
}

const ss_bssrdf_ops ss_bssrdf_model_pbd = {
    .name = "pbd",
    .summary = "photon beam diffusion, any incidence, + single scattering (Habel et al. 2013)",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_ANGULAR | SS_BSSRDF_TABULATED,
    .options = pbd_options,
    .create = pbd_create,
    .destroy = pbd_destroy,
    .eval = pbd_eval,
    .sample_entry = ss_profile_sampler_sample_entry,
    .pdf_entry = ss_profile_sampler_pdf_entry,
    .max_radius = ss_profile_sampler_max_radius,
    .total_reflectance = pbd_total,
    .rd = pbd_rd,
    .profile = pbd_profile,
    .exitance = pbd_exitance,
    .point_source_exitance = pbd_point_source,
};
