/* Classical dipole diffusion BSSRDF (Jensen2001
 * sec. 2.1-2.4).
 *
 * | option       | meaning                                                  |
 * |--------------|----------------------------------------------------------|
 * | sigma_s, g   | reduced scattering sigma_s' = (1 - g) sigma_s            |
 * | sigma_a      | absorption                                               |
 * | eta          | n_inside / n_outside: Fresnel factors and A              |
 * | min_distance | option: evaluate R_d at max(r, 1/sigma_t') (sec. 4)      |
 *
 * S_d = (1/pi) Ft(eta, w_i) R_d(|x_o - x_i|) Ft(eta, w_o); the entry point is
 * sampled from a mixture of area exponentials with rates sigma_tr (the
 * profile's tail) and sigma_t' (its core). Its point source (bssrdf.h) is
 * the same pair with the real source at any depth. */
#include "bssrdf/radial_model.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  ss_radial_model base; /* total: 2 pi int R_d r dr of R_d as evaluated */
  double alpha_prime[SS_BSSRDF_CHANNELS], sigma_tr[SS_BSSRDF_CHANNELS];
  double z_r[SS_BSSRDF_CHANNELS], z_v[SS_BSSRDF_CHANNELS], r_min[SS_BSSRDF_CHANNELS];
  double two_z_b[SS_BSSRDF_CHANNELS]; /* z_v - z_r: twice the extrapolation distance */
  double rd[SS_BSSRDF_CHANNELS];      /* the paper's closed form */
} dipole;

/* Jensen et al. 2001, eq. 4 (R_d for a dipole at z_r and -z_v). */
static void dipole_rd(const void *state, double r, double scale, double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double rc = r < d->r_min[c] ? d->r_min[c] : r, r2 = rc * rc;
    out[c] = scale * (d->alpha_prime[c] / (4.0 * SS_PI) *
                      (ss_dipole_source(d->z_r[c], r2, d->sigma_tr[c]) +
                       ss_dipole_source(d->z_v[c], r2, d->sigma_tr[c])));
  }
}

/* The pair at any depth (Jensen et al. 2001, eq. 4 with the real source at
 * z instead of z_r and the virtual one mirrored about the extrapolated
 * boundary at -z_b, at -(z + 2 z_b)), per unit power at z, as exitance:
 *     M(r; z) = t_out / (4 pi) [z (1 + s d_r) e^{-s d_r} / d_r^3
 *                                + (z + 2 z_b)(1 + s d_v) e^{-s d_v} / d_v^3],
 * d_r^2 = r^2 + z^2, d_v^2 = r^2 + (z + 2 z_b)^2, s = sigma_tr; t_out = 1 - 2
 * C1(1/eta), the part of the Ft(w_o)/pi lobe leaving (radial_model.h), so
 * that exitance(1, r) = Ft(1) alpha' M(r; z_r). Its plane integral is
 * t_out (e^{-s z} + e^{-s (z + 2 z_b)}) / 2: t_out for any z without
 * absorption. The min_distance option clamps the surface profile's 1/r^2
 * core, which a source below the surface does not have: not applied. */
static void dipole_point_source(const void *state, double z, double r,
                                double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  double r2 = r * r;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = d->base.m_scale / (4.0 * SS_PI) *
             (ss_dipole_source(z, r2, d->sigma_tr[c]) +
              ss_dipole_source(z + d->two_z_b[c], r2, d->sigma_tr[c]));
  }
}

static const ss_option dipole_options[] = {
    {.name = "min_distance",
     .type = SS_OPTION_BOOL,
     .def = "false",
     .help = "evaluate R_d at max(r, 1/sigma_t') (Jensen et al. 2001, sec. 4)"},
    {0},
};

static ss_status dipole_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  int min_distance = ss_bssrdf_params_bool(p, &dipole_options[0]);
  dipole *d = calloc(1, sizeof *d);
  if (!d) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "dipole: out of memory");
  }
  ss_radial_model_init(&d->base, p->eta, SS_RADIAL_EXIT_FRESNEL, dipole_rd);
  /* Jensen et al. 2001, sec. 2.1: A = (1 + Fdr)/(1 - Fdr). */
  double A = ss_fresnel_A(p->eta);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k =
        ss_bssrdf_coeffs_make(p->medium.sigma_s.c[c], p->medium.sigma_a.c[c], p->medium.g.c[c]);
    d->alpha_prime[c] = k.alpha_prime;
    d->sigma_tr[c] = k.sigma_tr;
    d->z_r[c] = 1.0 / k.sigma_t_prime;
    d->z_v[c] = d->z_r[c] * (1.0 + 4.0 * A / 3.0);
    d->two_z_b[c] = d->z_v[c] - d->z_r[c];
    d->r_min[c] = min_distance ? 1.0 / k.sigma_t_prime : 0.0;
    /* Jensen et al. 2001, sec. 2.4: total diffuse reflectance. */
    double s = sqrt(3.0 * (1.0 - k.alpha_prime));
    d->rd[c] = 0.5 * k.alpha_prime * (1.0 + exp(-4.0 / 3.0 * A * s)) * exp(-s);
    d->base.total[c] = d->rd[c];
    ss_radial_model_set_diffusion_sampler(&d->base, c, k.sigma_tr, k.sigma_t_prime);
  }
  ss_radial_model_fit_sampler(&d->base, p);
  if (min_distance) {
    /* the clamped profile no longer integrates to the closed form */
    ss_radial_model_integrate_total(&d->base);
  }
  *state = d;
  return SS_OK;
}

static void dipole_rd_closed(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const dipole *d = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = d->rd[c];
  }
}

const ss_bssrdf_ops ss_bssrdf_model_dipole = {
    .name = "dipole",
    .summary = "classical dipole with Fresnel factors (Jensen et al. 2001)",
    .flags = SS_BSSRDF_RADIAL,
    .options = dipole_options,
    .create = dipole_create,
    .destroy = free,
    .eval = ss_radial_model_eval,
    .sample_entry = ss_profile_sampler_sample_entry,
    .pdf_entry = ss_profile_sampler_pdf_entry,
    .max_radius = ss_profile_sampler_max_radius,
    .total_reflectance = ss_radial_model_total_reflectance,
    .rd = dipole_rd_closed,
    .profile = ss_radial_model_profile,
    .exitance = ss_radial_model_exitance,
    .radiance_line = ss_radial_model_radiance_line,
    .brdf = ss_radial_model_brdf,
    .point_source_exitance = dipole_point_source,
};
