/* Options, media and boundary of the forward scattering dipole models
 * (fwddip_model.h). */
#include "bssrdf/fwddip_model.h"

#include "subsurf/fresnel.h"

#include <math.h>
#include <stdlib.h>

/* The options of fwddip; fwddip-brdf declares the same without reciprocal. */
#define S_RTOL_OPTION                                                                              \
  {                                                                                                \
    .name = "s_rtol", .type = SS_BSSRDF_OPTION_DOUBLE, .def = "1e-3", .lo = 1e-9, .hi = 0.1,       \
    .help = "relative accuracy of the integral over path length s (adaptive Gauss-Kronrod in "     \
            "log s, see docs/fwddip.md)"                                                           \
  }
#define IMAGE_A_OPTION                                                                             \
  {                                                                                                \
    .name = "image_a", .type = SS_BSSRDF_OPTION_CHOICE, .def = "fresnel",                          \
    .choices = "fresnel|one",                                                                      \
    .help =                                                                                        \
        "image source at 2 A d_e: A from the Fresnel moments (internal reflection folded in), "    \
        "or 1 (the paper's absorbing boundary)"                                                    \
  }

const ss_bssrdf_option ss_fwddip_options[] = {
    S_RTOL_OPTION,
    {.name = "reciprocal",
     .type = SS_BSSRDF_OPTION_BOOL,
     .def = "false",
     .help = "the reciprocal propagator of eq. 15 instead of eq. 14"},
    IMAGE_A_OPTION,
    {.name = "ballistic",
     .type = SS_BSSRDF_OPTION_DOUBLE,
     .def = "0.5",
     .lo = 0.0,
     .hi = 1.0,
     .help = "the bssrdf integrator's probability of the ballistic entry strategy (a ray back "
             "along the refracted exit direction, eq. 10), one-sample MIS with the probe rays"},
    {0},
};

const ss_bssrdf_option ss_fwddip_brdf_options[] = {S_RTOL_OPTION, IMAGE_A_OPTION, {0}};

/* Every option of fwddip and fwddip-brdf is read here (an option a model
 * does not declare cannot be set on it, so it reads as its default). */
static void config_read(const ss_bssrdf_params *p, ss_fwddip_config *cfg) {
  cfg->s_rtol = ss_bssrdf_params_double(p, &ss_fwddip_options[0]);
  cfg->reciprocal = ss_bssrdf_params_bool(p, &ss_fwddip_options[1]);
  cfg->image_a = ss_bssrdf_params_choice(p, &ss_fwddip_options[2]);
  cfg->ballistic = ss_bssrdf_params_double(p, &ss_fwddip_options[3]);
}

/* Gauss-Legendre in cos_t over the cone that leaves (cos_t above the
 * critical cosine), two 8-point panels; midpoints in phi. */
static void direction_rule(ss_fwddip_state *st) {
  double mu_c = st->eta > 1.0 ? sqrt(1.0 - 1.0 / (st->eta * st->eta)) : 0.0;
  double half = 0.25 * (1.0 - mu_c);
  int n = 0;
  for (int panel = 0; panel < 2; ++panel) {
    for (int a = 0; a < SS_GL8_N; ++a) {
      double mu = mu_c + half * (2 * panel + 1 + ss_gl8_x[a]);
      double w =
          half * ss_gl8_w[a] * mu * ss_ft_inside(mu, st->eta) * 2.0 * SS_PI / SS_FWDDIP_DIR_PHI;
      for (int b = 0; b < SS_FWDDIP_DIR_PHI; ++b) {
        st->dir[n] = ss_spherical_direction(mu, 2.0 * SS_PI * (b + 0.5) / SS_FWDDIP_DIR_PHI);
        st->dir_weight[n++] = w;
      }
    }
  }
}

ss_status ss_fwddip_state_init(ss_fwddip_state *st, const ss_bssrdf_params *p, const char *model,
                               ss_error *err) {
  static const char ch[] = "RGB";
  config_read(p, &st->cfg);
  st->eta = p->eta;
  /* Frisvad et al. 2014, eq. 16-17 (A = 1 when index matched); seed 000
   * eq. 13 uses A = 1 for its absorbing boundary. */
  double A =
      st->cfg.image_a ? 1.0 : (1.0 - ss_fresnel_c_e(p->eta)) / (2.0 * ss_fresnel_c_phi(p->eta));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k = ss_bssrdf_coeffs_make(p->medium.sigma_s.c[c], p->medium.sigma_a.c[c], p->medium.g.c[c]);
    if (!(k.sigma_s_prime > 0.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "%s: sigma_s[%c] must be > 0 (the propagator's scale is sigma_s'/2), "
                          "got %g",
                          model, ch[c], p->medium.sigma_s.c[c]);
    }
    st->m[c] = ss_fwddip_medium_make(k.sigma_s_prime, p->medium.sigma_a.c[c]);
    /* Seed 000, eq. 13: z_v = 2 A d_e, d_e = 2.131 D / sqrt(alpha'). */
    st->z_v[c] = 2.0 * A * 2.131 * k.D / sqrt(k.alpha_prime);
    st->sigma_t_prime[c] = k.sigma_t_prime;
    st->same_as[c] = c;
    for (int b = 0; b < c; ++b) {
      if (st->m[b].p == st->m[c].p && st->m[b].sigma_a == st->m[c].sigma_a &&
          st->z_v[b] == st->z_v[c]) {
        st->same_as[c] = b;
        break;
      }
    }
    ss_radial_mix_init_diffusion(&st->sampler.ch[c], k.sigma_tr, k.sigma_t_prime);
  }
  direction_rule(st);
  return SS_OK;
}

int ss_fwddip_boundary(double eta, ss_vec3 w_i, ss_vec3 n_i, ss_vec3 w_o, ss_vec3 n_o,
                       ss_vec3 *wi_e, ss_vec3 *wo_e, double *factor) {
  double cos_i = ss_vec3_dot(w_i, n_i), cos_o = ss_vec3_dot(w_o, n_o);
  ss_vec3 t_o;
  if (cos_i <= 0.0 || cos_o <= 0.0 || !ss_refract(w_i, n_i, eta, wi_e) ||
      !ss_refract(w_o, n_o, eta, &t_o)) {
    return 0;
  }
  *wo_e = ss_vec3_neg(t_o);
  *factor = (1.0 - ss_fresnel_dielectric(cos_i, eta)) * (1.0 - ss_fresnel_dielectric(cos_o, eta)) /
            (eta * eta);
  return 1;
}

ss_status ss_fwddip_state_create(const ss_bssrdf_params *p, const char *model, void **state,
                                 ss_error *err) {
  ss_fwddip_state *st = calloc(1, sizeof *st);
  if (!st) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", model);
  }
  ss_status status = ss_fwddip_state_init(st, p, model, err);
  if (status != SS_OK) {
    free(st);
    return status;
  }
  *state = st;
  return SS_OK;
}

void ss_fwddip_channels(const ss_fwddip_state *st, ss_fwddip_channel_fn f, void *ctx, double scale,
                        double out[SS_BSSRDF_CHANNELS]) {
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = st->same_as[c] < c ? out[st->same_as[c]] : scale * fmax(0.0, f(ctx, c));
  }
}

int ss_fwddip_halfspace_beam(double eta, double cos_i, ss_vec3 *w_i, double *ft) {
  double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
  *ft = ss_ft_outside(cos_i, eta);
  return ss_refract(ss_vec3_make(-sin_i, 0.0, cos_i), ss_vec3_make(0, 0, 1), eta, w_i);
}
