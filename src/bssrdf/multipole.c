/* Multipole model of a thin slab (DonnerJensen2005 sec. 3).
 *
 * | option     | meaning                                                    |
 * |------------|------------------------------------------------------------|
 * | sigma_s, g | reduced scattering sigma_s' = (1 - g) sigma_s              |
 * | sigma_a    | absorption                                                 |
 * | eta        | n_slab / n_outside, the same on both faces                 |
 * | thickness  | option: slab thickness d >= 1/sigma_t' (inf: the dipole)   |
 * | local_     | option: d from the object's local thickness along the      |
 * | thickness  | normal at the exit point (query.thickness, measured by the |
 * |            | renderer's probe ray), raised to 1/sigma_t'; `thickness`   |
 * |            | where the renderer measured none (and for every hook but   |
 * |            | eval)                                                      |
 *
 * Thinner slabs are rejected: the real source at depth 1/sigma_t' would lie
 * below the slab and T(r) turns negative (the model's own limit).
 * R(r) and T(r) are sums over 2n + 1 dipole pairs mirrored in both
 * extrapolated boundaries, with n chosen so that omitted pairs weigh less
 * than 1e-8 (multipole_profile.c). S = (1/pi) Ft(w_i) R(r) Ft(w_o) as for
 * the dipole; n = 0 (a half-space) is exactly the dipole. */
#include "bssrdf/multipole.h"
#include "bssrdf/radial_model.h"

#include <math.h>
#include <stdlib.h>

#define MULTIPOLE_MAX_PAIRS 10000

typedef struct {
  ss_radial_model base; /* total, transmit: the closed-form disk integrals */
  ss_multipole m[SS_BSSRDF_CHANNELS];
  int local; /* local_thickness */
  ss_bssrdf_coeffs k[SS_BSSRDF_CHANNELS];
  double A;
} multipole;

/* S and M use R(r) clipped at 0 so that they never turn negative; the
 * profile hook reports it unclipped. */
static void multipole_clipped(const void *state, double r, double scale,
                              double out[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = scale * fmax(0.0, ss_multipole_reflectance(&m->m[c], r));
  }
}

static const ss_option multipole_options[] = {
    {.name = "thickness",
     .type = SS_OPTION_DOUBLE,
     .def = "inf",
     .lo = 0.0,
     .hi = INFINITY,
     .range = SS_OPTION_LO_OPEN,
     .help = "slab thickness >= 1/sigma_t' (inf: half-space); --thickness sets it"},
    {.name = "local_thickness",
     .type = SS_OPTION_BOOL,
     .def = "false",
     .help = "in renders, the thickness of the object along the normal at each exit point"},
    {0},
};

static void halfspace_profile(const void *ctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  const ss_multipole *h = ctx;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = ss_multipole_reflectance(&h[c], r);
  }
}

/* The entry sampler fitted to the half-space profile (one pair) whatever the
 * thickness: a local thickness is only known per query, and the explicit and
 * local thickness then draw the same points. */
static void fit_sampler(multipole *m, const ss_bssrdf_params *p) {
  if (p->single_use) {
    ss_profile_sampler_init_mixture(&m->base.sampler, m->base.sampler.mix);
    return;
  }
  ss_multipole h[SS_BSSRDF_CHANNELS];
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_multipole_setup(&h[c], m->k[c], INFINITY, m->A, m->A, MULTIPOLE_MAX_PAIRS);
  }
  ss_profile_sampler_init_diffusion(&m->base.sampler, halfspace_profile, h, m->base.sampler.mix);
}

static ss_status multipole_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  double thickness = ss_bssrdf_params_double(p, &multipole_options[0]);
  multipole *m = calloc(1, sizeof *m);
  if (!m) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "multipole: out of memory");
  }
  ss_radial_model_init(&m->base, p->eta, SS_RADIAL_EXIT_FRESNEL, multipole_clipped);
  double A = ss_fresnel_A(p->eta);
  m->local = ss_bssrdf_params_bool(p, &multipole_options[1]);
  m->A = A;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k =
        ss_bssrdf_coeffs_make(p->medium.sigma_s.c[c], p->medium.sigma_a.c[c], p->medium.g.c[c]);
    if (thickness < 1.0 / k.sigma_t_prime) {
      free(m);
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "multipole: thickness %g is below the source depth 1/sigma_t' = %g of "
                          "channel %c (Donner & Jensen place the source inside the slab)",
                          thickness, 1.0 / k.sigma_t_prime, "RGB"[c]);
    }
    m->k[c] = k;
    ss_multipole_setup(&m->m[c], k, thickness, A, A, MULTIPOLE_MAX_PAIRS);
    m->base.total[c] = ss_multipole_reflectance_disk(&m->m[c], INFINITY);
    m->base.transmit[c] = ss_multipole_transmittance_disk(&m->m[c], INFINITY);
    ss_radial_model_set_diffusion_sampler(&m->base, c, k.sigma_tr, k.sigma_t_prime);
  }
  fit_sampler(m, p);
  *state = m;
  return SS_OK;
}

/* S with the slab's thickness from the query when local_thickness is set and
 * the renderer measured one (Donner & Jensen 2005, eq. 12, with d the local
 * thickness), else the model's own. */
static void multipole_eval(const void *state, const ss_bssrdf_query *q,
                           double s[SS_BSSRDF_CHANNELS]) {
  const multipole *m = state;
  if (!m->local || !(q->thickness > 0.0)) {
    ss_radial_model_eval(state, q, s);
    return;
  }
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), m->base.eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), m->base.eta) * m->base.s_scale;
  double r = ss_vec3_length(ss_vec3_sub(q->x_o, q->x_i));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_multipole slab;
    double d = fmax(q->thickness, 1.0 / m->k[c].sigma_t_prime);
    ss_multipole_setup(&slab, m->k[c], d, m->A, m->A, MULTIPOLE_MAX_PAIRS);
    s[c] = f * fmax(0.0, ss_multipole_reflectance(&slab, r));
  }
}

static int multipole_uses_thickness(const void *state) {
  const multipole *m = state;
  return m->local;
}

/* The paper's profiles, unclipped, with the slab's transmittance. */
static void multipole_profile(const void *state, int channel, double r,
                              ss_bssrdf_profile_value *out) {
  const multipole *m = state;
  out->ms = out->value = ss_multipole_reflectance(&m->m[channel], r);
  out->t = ss_multipole_transmittance(&m->m[channel], r);
}

const ss_bssrdf_ops ss_bssrdf_model_multipole = {
    .name = "multipole",
    .summary = "thin slab R(r), T(r) from mirrored dipole pairs (Donner & Jensen 2005)",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_SLAB,
    .options = multipole_options,
    .create = multipole_create,
    .destroy = free,
    .eval = multipole_eval,
    .sample_entry = ss_profile_sampler_sample_entry,
    .pdf_entry = ss_profile_sampler_pdf_entry,
    .max_radius = ss_profile_sampler_max_radius,
    .total_reflectance = ss_radial_model_total_reflectance,
    .rd = ss_radial_model_rd,
    .profile = multipole_profile,
    .exitance = ss_radial_model_exitance,
    .brdf = ss_radial_model_brdf,
    .total_transmittance = ss_radial_model_total_transmittance,
    .uses_thickness = multipole_uses_thickness,
};
