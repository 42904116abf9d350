/* Options, media and boundary of the forward scattering dipole models
 * (fwddip_model.h). */
#include "bssrdf/fwddip_model.h"

#include "subsurf/fresnel.h"

#include <math.h>
#include <stdlib.h>

/* The options of fwddip; fwddip-brdf declares the same without reciprocal. */
#define S_RTOL_OPTION                                                                              \
  {                                                                                                \
    .name = "s_rtol", .type = SS_OPTION_DOUBLE, .def = "1e-3", .lo = 1e-9, .hi = 0.1,              \
    .help = "relative accuracy of the integral over path length s (adaptive Gauss-Kronrod in "     \
            "log s, see docs/fwddip.md)"                                                           \
  }
#define IMAGE_A_OPTION                                                                             \
  {                                                                                                \
    .name = "image_a", .type = SS_OPTION_CHOICE, .def = "fresnel", .choices = "fresnel|one",       \
    .help =                                                                                        \
        "image source at 2 A d_e: A from the Fresnel moments (internal reflection folded in), "    \
        "or 1 (the paper's absorbing boundary)"                                                    \
  }

/* The rough dielectric boundary, under the scene's rough dielectric keys. */
#define ROUGH_OPTIONS                                                                              \
  {.name = "alpha",                                                                                \
   .type = SS_OPTION_DOUBLE,                                                                       \
   .def = "0",                                                                                     \
   .lo = 0.0,                                                                                      \
   .hi = 1.0,                                                                                      \
   .help = "roughness of a rough dielectric boundary (the microfacet alpha of src/optics) "        \
           "through which light enters and leaves; 0 (or below 1e-3, or eta 1): smooth"},          \
      {.name = "distribution",                                                                     \
       .type = SS_OPTION_CHOICE,                                                                   \
       .def = "beckmann",                                                                          \
       .choices = "beckmann|ggx",                                                                  \
       .help = "microfacet distribution of the rough boundary"},                                   \
  {                                                                                                \
    .name = "rough_nodes", .type = SS_OPTION_INT, .def = "3", .lo = 1.0, .hi = 8.0,                \
    .help = "the rough boundary's fixed rule: N x 2N visible microfacet normals at each end "      \
            "(docs/fwddip.md)"                                                                     \
  }

const ss_option ss_fwddip_options[] = {
    S_RTOL_OPTION,
    {.name = "reciprocal",
     .type = SS_OPTION_BOOL,
     .def = "false",
     .help = "the reciprocal propagator of eq. 15 instead of eq. 14"},
    IMAGE_A_OPTION,
    {.name = "ballistic",
     .type = SS_OPTION_DOUBLE,
     .def = "0.5",
     .lo = 0.0,
     .hi = 1.0,
     .help = "the bssrdf integrator's probability of the ballistic entry strategy (a ray back "
             "along the refracted exit direction, eq. 10), one-sample MIS with the probe rays"},
    ROUGH_OPTIONS,
    {0},
};

const ss_option ss_fwddip_brdf_options[] = {S_RTOL_OPTION, IMAGE_A_OPTION, ROUGH_OPTIONS, {0}};

/* Every option of fwddip and fwddip-brdf is read here (an option a model
 * does not declare cannot be set on it, so it reads as its default). */
static void config_read(const ss_bssrdf_params *p, ss_fwddip_config *cfg) {
  cfg->s_rtol = ss_bssrdf_params_double(p, &ss_fwddip_options[0]);
  cfg->reciprocal = ss_bssrdf_params_bool(p, &ss_fwddip_options[1]);
  cfg->image_a = ss_bssrdf_params_choice(p, &ss_fwddip_options[2]);
  cfg->ballistic = ss_bssrdf_params_double(p, &ss_fwddip_options[3]);
  cfg->alpha = ss_bssrdf_params_double(p, &ss_fwddip_options[4]);
  cfg->distribution = ss_bssrdf_params_choice(p, &ss_fwddip_options[5]);
  cfg->rough_nodes = ss_bssrdf_params_int(p, &ss_fwddip_options[6]);
}

/* Gauss-Legendre 8-point panels in cos_t on [lo, hi], midpoints in phi;
 * weight mu Ft dw with Ft the transmitted share leaving from inside. */
static int direction_panels(ss_fwddip_state *st, const ss_fwddip_rough *fine, double lo, double hi,
                            int panels, int n) {
  double half = 0.5 * (hi - lo) / panels;
  for (int panel = 0; panel < panels; ++panel) {
    for (int a = 0; a < SS_GL8_N; ++a) {
      double mu = lo + half * (2 * panel + 1 + ss_gl8_x[a]);
      double ft = st->rough.on ? ss_fwddip_rough_leaving_share(fine, st->eta, mu)
                               : ss_ft_inside(mu, st->eta);
      double w = half * ss_gl8_w[a] * mu * ft * 2.0 * SS_PI / SS_FWDDIP_DIR_PHI;
      for (int b = 0; b < SS_FWDDIP_DIR_PHI; ++b) {
        st->dir[n] = ss_spherical_direction(mu, 2.0 * SS_PI * (b + 0.5) / SS_FWDDIP_DIR_PHI);
        st->dir_weight[n++] = w;
      }
    }
  }
  return n;
}

/* The cone that leaves (cos_t above the critical cosine) in two panels; a
 * rough boundary also lets light out below it (a third panel). Its share
 * leaving is computed once per direction, so with the finest rule. */
static void direction_rule(ss_fwddip_state *st) {
  double mu_c = st->eta > 1.0 ? sqrt(1.0 - 1.0 / (st->eta * st->eta)) : 0.0;
  ss_fwddip_rough fine = st->rough;
  if (st->rough.on) {
    ss_fwddip_config cfg = st->cfg;
    cfg.rough_nodes = SS_FWDDIP_ROUGH_MAX_NODES;
    ss_fwddip_rough_init(&fine, &cfg, st->eta, "", NULL);
  }
  int n = direction_panels(st, &fine, mu_c, 1.0, 2, 0);
  if (st->rough.on && mu_c > 0.0) {
    n = direction_panels(st, &fine, 0.0, mu_c, 1, n);
  }
  st->n_dir = n;
}

ss_status ss_fwddip_state_init(ss_fwddip_state *st, const ss_bssrdf_params *p, const char *model,
                               ss_error *err) {
  static const char ch[] = "RGB";
  config_read(p, &st->cfg);
  st->eta = p->eta;
  ss_status rs = ss_fwddip_rough_init(&st->rough, &st->cfg, p->eta, model, err);
  if (rs != SS_OK) {
    return rs;
  }
  /* Frisvad2014 eq. 16-17 (A = 1 when index matched); Frederickx2017
   * eq. 13 uses A = 1 for its absorbing boundary. */
  double A =
      st->cfg.image_a ? 1.0 : (1.0 - ss_fresnel_c_e(p->eta)) / (2.0 * ss_fresnel_c_phi(p->eta));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k =
        ss_bssrdf_coeffs_make(p->medium.sigma_s.c[c], p->medium.sigma_a.c[c], p->medium.g.c[c]);
    if (!(k.sigma_s_prime > 0.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "%s: sigma_s[%c] must be > 0 (the propagator's scale is sigma_s'/2), "
                          "got %g",
                          model, ch[c], p->medium.sigma_s.c[c]);
    }
    st->m[c] = ss_fwddip_medium_make(k.sigma_s_prime, p->medium.sigma_a.c[c]);
    /* Frederickx2017 eq. 13: z_v = 2 A d_e, d_e = 2.131 D / sqrt(alpha'). */
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

static void single_node(ss_fwddip_nodes *nodes, ss_vec3 d) {
  nodes->n = 1;
  nodes->d[0] = d;
  nodes->w[0] = 1.0;
}

int ss_fwddip_pairs(const ss_fwddip_state *st, ss_vec3 w_i, ss_vec3 n_i, ss_vec3 w_o, ss_vec3 n_o,
                    ss_fwddip_nodes *in, ss_fwddip_nodes *out, double *factor) {
  if (!st->rough.on) {
    ss_vec3 wi_e, wo_e;
    if (!ss_fwddip_boundary(st->eta, w_i, n_i, w_o, n_o, &wi_e, &wo_e, factor)) {
      return 0;
    }
    single_node(in, wi_e);
    single_node(out, wo_e);
    return 1;
  }
  if (!(ss_vec3_dot(w_i, n_i) > 0.0) || !(ss_vec3_dot(w_o, n_o) > 0.0)) {
    return 0;
  }
  ss_fwddip_rough_enter(&st->rough, st->eta, w_i, n_i, 1.0, in);
  ss_fwddip_rough_leave(&st->rough, st->eta, w_o, n_o, out);
  *factor = 1.0;
  return in->n > 0 && out->n > 0;
}

int ss_fwddip_beam_nodes(const ss_fwddip_state *st, double cos_i, ss_fwddip_nodes *in,
                         double *factor) {
  if (!st->rough.on) {
    ss_vec3 w_i;
    if (!ss_fwddip_halfspace_beam(st->eta, cos_i, &w_i, factor)) {
      return 0;
    }
    single_node(in, w_i);
    return 1;
  }
  if (!(cos_i > 0.0)) {
    return 0;
  }
  double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
  ss_fwddip_rough_enter(&st->rough, st->eta, ss_vec3_make(-sin_i, 0.0, cos_i),
                        ss_vec3_make(0, 0, 1), 1.0, in);
  *factor = 1.0;
  return in->n > 0;
}
