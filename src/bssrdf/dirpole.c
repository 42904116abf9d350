/* Directional dipole (Frisvad2014).
 *
 * | option     | meaning                                                    |
 * |------------|------------------------------------------------------------|
 * | sigma_s, g | reduced scattering sigma_s' = (1 - g) sigma_s              |
 * | sigma_a    | absorption                                                 |
 * | eta        | n_inside / n_outside: refraction of w_i, Fresnel, C1, C2   |
 *
 * The real source is a ray source along the refracted incident direction
 * w_r; its image is mirrored in the modified tangent plane with normal n*.
 * S depends on w_i through w_r and on w_o only through Ft(w_o). The
 * normalisation C_n = 1/(1 - 2 C1(1/eta)) makes M(x_o) = Ft(w_i) R with R the
 * bracketed term / (4 pi), the profile reported at normal incidence.
 * Entry sampling: a radius fitted to the profile's radial marginal under
 * diffuse incidence (profile_sampler.h; the incidence is not known when the
 * entry point is drawn), with the dipoles' exponential mixture (rates sigma_tr
 * and sigma_t') as its defensive share, and a uniform azimuth; exact pdf. */
#include "bssrdf/handle.h"
#include "bssrdf/radial_model.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  ss_profile_sampler sampler; /* first: the ss_profile_sampler hooks read it */
  double eta, t_out, c_phi, c_e, A;
  double D[SS_BSSRDF_CHANNELS], sigma_tr[SS_BSSRDF_CHANNELS], d_e[SS_BSSRDF_CHANNELS];
  double backlit_z2[SS_BSSRDF_CHANNELS]; /* (1/(3 sigma_t))^2 */
} dirpole;

static void dirpole_exitance_entered(const dirpole *d, double cos_i, double x, double y,
                                     double out[SS_BSSRDF_CHANNELS]);

/* The exitance's mean over the azimuth at radius r, averaged over diffuse
 * incidence (weight Ft(mu) mu): 4 Gauss-Legendre nodes in mu, 8 midpoints in
 * phi over [0, pi] (the profile is even in y). The sampler's shape only. */
static void diffuse_marginal(const void *ctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  static const double mu_node[4] = {0.0694318442, 0.3300094782, 0.6699905218, 0.9305681558};
  static const double mu_weight[4] = {0.1739274226, 0.3260725774, 0.3260725774, 0.1739274226};
  const dirpole *d = ctx;
  ss_channels_zero(out);
  for (int i = 0; i < 4; ++i) {
    double w = mu_weight[i] * mu_node[i] * ss_ft_outside(mu_node[i], d->eta);
    for (int j = 0; j < 8; ++j) {
      double phi = SS_PI * (j + 0.5) / 8.0, v[SS_BSSRDF_CHANNELS];
      dirpole_exitance_entered(d, mu_node[i], r * cos(phi), r * sin(phi), v);
      for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
        out[c] += w * v[c];
      }
    }
  }
}

static ss_status dirpole_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  dirpole *d = calloc(1, sizeof *d);
  if (!d) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "dirpole: out of memory");
  }
  d->eta = p->eta;
  d->t_out = ss_fresnel_transmission_out(p->eta);
  /* Frisvad et al. 2014, eq. 16-17: C_phi, C_E from the Fresnel moments of
   * light arriving from inside, and A = (1 - C_E)/(2 C_phi). */
  d->c_phi = ss_fresnel_c_phi(p->eta);
  d->c_e = ss_fresnel_c_e(p->eta);
  d->A = (1.0 - d->c_e) / (2.0 * d->c_phi);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k =
        ss_bssrdf_coeffs_make(p->medium.sigma_s.c[c], p->medium.sigma_a.c[c], p->medium.g.c[c]);
    d->D[c] = k.D;
    d->sigma_tr[c] = sqrt(p->medium.sigma_a.c[c] / k.D);
    /* Frisvad et al. 2014, eq. 21: extrapolation distance. */
    d->d_e[c] = 2.131 * k.D / sqrt(k.alpha_prime);
    d->backlit_z2[c] = 1.0 / (9.0 * k.sigma_t * k.sigma_t);
    ss_radial_mix_init_diffusion(&d->sampler.mix[c], k.sigma_tr, k.sigma_t_prime);
  }
  if (p->single_use) {
    ss_profile_sampler_init_mixture(&d->sampler, d->sampler.mix);
  } else {
    ss_profile_sampler_init_diffusion(&d->sampler, diffuse_marginal, d, d->sampler.mix);
  }
  *state = d;
  return SS_OK;
}

/* Frisvad et al. 2014, eq. 11 without C_n/(4 pi^2) (applied by the caller):
 * the diffusive radiant exitance of a ray source along w at offset x. */
static double sd_prime(const dirpole *d, int c, ss_vec3 x, ss_vec3 w, ss_vec3 n_o, double r) {
  double D = d->D[c], sr = d->sigma_tr[c] * r, r2 = r * r;
  double xw = ss_vec3_dot(x, w), wn = ss_vec3_dot(w, n_o), xn = ss_vec3_dot(x, n_o);
  double t_phi = d->c_phi * (r2 / D + 3.0 * (1.0 + sr) * xw);
  double t_e = d->c_e * (3.0 * D * (1.0 + sr) * wn -
                         ((1.0 + sr) + 3.0 * D * (3.0 * (1.0 + sr) + sr * sr) / r2 * xw) * xn);
  return exp(-sr) / (r2 * r) * (t_phi - t_e);
}

/* The bracket of S_d / (C_n / (4 pi^2)) for the real minus the virtual ray
 * source, clamped at 0 (Frisvad et al. 2014, eq. 12-15). */
static void dirpole_core(const dirpole *d, ss_vec3 x_i, ss_vec3 n_i, ss_vec3 w_r, ss_vec3 x_o,
                         ss_vec3 n_o, double out[SS_BSSRDF_CHANNELS]) {
  ss_vec3 x = ss_vec3_sub(x_o, x_i);
  double r2 = ss_vec3_length2(x), r = sqrt(r2);
  /* Modified tangent-plane normal n* = x^ x normalize(n_i x x) (Frederickx2017
   * eq. 12); at r = 0 (or x parallel to n_i) it is n_i. */
  ss_vec3 n_star = n_i;
  ss_vec3 nix = ss_vec3_cross(n_i, x);
  if (r > 0.0 && ss_vec3_length2(nix) > 1e-24 * r2) {
    n_star = ss_vec3_cross(ss_vec3_scale(x, 1.0 / r), ss_vec3_normalize(nix));
  }
  ss_vec3 w_v = ss_vec3_sub(w_r, ss_vec3_scale(n_star, 2.0 * ss_vec3_dot(w_r, n_star)));
  double xwr = ss_vec3_dot(x, w_r), mu0 = -ss_vec3_dot(n_o, w_r);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double D = d->D[c], de = d->d_e[c];
    double dr2;
    if (mu0 > 0.0) {
      /* Frisvad et al. 2014, eq. 19-20: corrected distance to the real source. */
      double cos_beta = -sqrt(fmax(0.0, r2 - xwr * xwr) / (r2 + de * de));
      dr2 = r2 + D * mu0 * (D * mu0 - 2.0 * de * cos_beta);
    } else {
      dr2 = r2 + d->backlit_z2[c];
    }
    ss_vec3 x_v = ss_vec3_madd(x_i, n_star, 2.0 * d->A * de);
    ss_vec3 xv = ss_vec3_sub(x_o, x_v);
    double dv = ss_vec3_length(xv);
    double s = sd_prime(d, c, x, w_r, n_o, sqrt(dr2)) - sd_prime(d, c, xv, w_v, n_o, dv);
    out[c] = fmax(0.0, s);
  }
}

static void dirpole_eval(const void *state, const ss_bssrdf_query *q,
                         double s[SS_BSSRDF_CHANNELS]) {
  const dirpole *d = state;
  ss_channels_zero(s);
  ss_vec3 w_r;
  double cos_i = ss_vec3_dot(q->w_i, q->n_i), cos_o = ss_vec3_dot(q->w_o, q->n_o);
  if (cos_i <= 0.0 || cos_o <= 0.0 || !ss_refract(q->w_i, q->n_i, d->eta, &w_r)) {
    return;
  }
  dirpole_core(d, q->x_i, q->n_i, w_r, q->x_o, q->n_o, s);
  double f = ss_ft_outside(cos_i, d->eta) * ss_ft_outside(cos_o, d->eta) /
             (d->t_out * 4.0 * SS_PI * SS_PI);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s[c] *= f;
  }
}

/* M = Ft(w_i) bracket / (4 pi): int Ft(w_o) cos dw_o = pi (1 - 2 C1(1/eta)) cancels C_n. */
static void dirpole_exitance_entered(const dirpole *d, double cos_i, double x, double y,
                                     double out[SS_BSSRDF_CHANNELS]) {
  double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
  ss_vec3 n = ss_vec3_make(0, 0, 1), w_r;
  if (!ss_refract(ss_vec3_make(-sin_i, 0.0, cos_i), n, d->eta, &w_r)) {
    ss_channels_zero(out);
    return;
  }
  dirpole_core(d, ss_vec3_make(0, 0, 0), n, w_r, ss_vec3_make(x, y, 0.0), n, out);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] /= 4.0 * SS_PI;
  }
}

static void dirpole_exitance(const void *state, double cos_i, double x, double y,
                             double out[SS_BSSRDF_CHANNELS]) {
  const dirpole *d = state;
  dirpole_exitance_entered(d, cos_i, x, y, out);
  double f = ss_ft_outside(cos_i, d->eta);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] *= f;
  }
}

static void dirpole_profile(const void *state, int channel, double r,
                            ss_bssrdf_profile_value *out) {
  double v[SS_BSSRDF_CHANNELS];
  dirpole_exitance_entered(state, 1.0, r, 0.0, v);
  out->ms = out->value = v[channel];
}

typedef struct {
  const dirpole *d;
} ring_ctx;

static void ring_profile(void *vctx, double r, double out[SS_BSSRDF_CHANNELS]) {
  const ring_ctx *c = vctx;
  dirpole_exitance_entered(c->d, 1.0, r, 0.0, out);
  for (int k = 0; k < SS_BSSRDF_CHANNELS; ++k) {
    out[k] *= 2.0 * SS_PI * r;
  }
}

/* Per unit power entering at normal incidence: 2 pi int r R(r) dr. */
static void dirpole_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const dirpole *d = state;
  ring_ctx c = {d};
  double small = INFINITY, large = 0.0;
  for (int k = 0; k < SS_BSSRDF_CHANNELS; ++k) {
    small = fmin(small, 0.05 * d->D[k]);
    large = fmax(large, ss_radial_mix_max_radius(&d->sampler.mix[k]));
  }
  ss_vec_integrate_halfline(ring_profile, &c, small, large, out);
}

const ss_bssrdf_ops ss_bssrdf_model_dirpole = {
    .name = "dirpole",
    .summary = "directional dipole: ray source along the refracted beam (Frisvad et al. 2014)",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_ANGULAR,
    .create = dirpole_create,
    .destroy = free,
    .eval = dirpole_eval,
    .sample_entry = ss_profile_sampler_sample_entry,
    .pdf_entry = ss_profile_sampler_pdf_entry,
    .max_radius = ss_profile_sampler_max_radius,
    .rd = dirpole_rd,
    .profile = dirpole_profile,
    .exitance = dirpole_exitance,
};
