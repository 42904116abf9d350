/* Anisotropic diffusion dipole for micro-flake media (Jakob2010
 * sec. 6.3, eq. 44-48).
 *
 * | option             | meaning                                              |
 * |--------------------|------------------------------------------------------|
 * | sigma_s, sigma_a   | the flakes' medium (microflake.h's convention: those |
 * |                    | of the same flakes oriented uniformly)               |
 * | g                  | without flakes only: sigma_s' = (1 - g) sigma_s      |
 * | eta                | n_inside / n_outside: Fresnel factors and A          |
 * | medium's flakes    | distribution, p, axis, albedo falloff (--flakes)     |
 * | flake_distribution | option, when the medium has none: uniform | surface  |
 * |                    | | fiber (default: the medium's; uniform without)     |
 * | flake_exponent     | option: p of those flakes                            |
 * | flake_axis         | option: their axis "x,y,z" (world space)             |
 *
 * With M the flakes' diffusion matrix (flake_diffusion.h), P = M^(1/2),
 * beta = sqrt(mu0 / (4 pi)) and n the entry point's normal, a unit beam
 * entering at x_i has the exitance (eq. 47)
 *   R(x_o) = alpha(n) det P / (4 pi) [C1 e^{-beta d_r} / d_r^3 + C2 e^{-beta d_v} / d_v^3]
 * with the sources of eq. 44-46 and d = |P (x_o - x_source)|; S =
 * Ft(w_i) R Ft(w_o) / pi as the classical dipole, which it equals for
 * uniform flakes. Entry points are drawn with the footprint's quadratic
 * form: a radial mixture in u = G^(1/2) (a, b), G = M restricted to the
 * sampling plane.
 *
 * The flakes' tables and M at unit density are built about +z and turned to
 * the axis (M = rho F M_z F^T, F the axis frame), so that a model created
 * with ss_bssrdf_params.base set to an aniso-dipole of the same flakes and
 * albedos (a gridded medium's exit point: another density and axis) borrows
 * them and costs no quadrature. */
#include "bssrdf/handle.h"
#include "bssrdf/radial_model.h"
#include "subsurf/flake_diffusion.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  ss_radial_model base;  /* Fresnel normalisation and the totals at n = +z */
  ss_medium_flakes spec; /* the flakes as resolved (axis as given) */
  ss_frame axis;         /* the flakes' axis as the frame's normal */
  /* The flakes about +z per channel (their tables depend on the albedo
   * only): in `own`, or borrowed from the base model. */
  ss_microflake *own;
  const ss_microflake *flakes[SS_BSSRDF_CHANNELS];
  ss_mat3 M_z[SS_BSSRDF_CHANNELS];  /* M about +z at unit density (eq. 31) */
  double mu0_1[SS_BSSRDF_CHANNELS]; /* mu0 at unit density (eq. 28) */
  int uniform;                      /* sigma(w) = 1/2 exactly */
  double A;
  double density[SS_BSSRDF_CHANNELS], beta[SS_BSSRDF_CHANNELS];
  ss_mat3 M[SS_BSSRDF_CHANNELS], M_inv[SS_BSSRDF_CHANNELS], P[SS_BSSRDF_CHANNELS];
  double det_P[SS_BSSRDF_CHANNELS];
  ss_radial_mix mix[SS_BSSRDF_CHANNELS]; /* over |u| = sqrt(x^T M x) */
  double max_r[SS_BSSRDF_CHANNELS];
} aniso_dipole;

/* The real and virtual sources for the tangent plane at x_i with normal n
 * (eq. 44-45): heights z_r below and z_v above, offsets from x_i. */
typedef struct {
  ss_vec3 to_r, to_v;
  double z_r, z_v, alpha;
} sources;

static sources place_sources(const aniso_dipole *d, int c, ss_vec3 n) {
  sources s;
  ss_vec3 local = ss_frame_to_local(d->axis, n);
  double sigma = d->uniform ? 0.5 : ss_microflake_sigma_t(d->flakes[c], local);
  s.z_r = 1.0 / (d->density[c] * sigma);
  s.alpha = ss_microflake_collision_albedo(d->flakes[c], local);
  ss_vec3 m_inv_n = ss_mat3_apply(d->M_inv[c], n);
  double n_m_inv_n = ss_vec3_dot(n, m_inv_n);
  /* Jakob et al. 2010, eq. 44-45: d_p = 2 A n^T M^-1 n; mirroring x_r in
   * the extrapolated plane in the space transformed by P moves it along
   * P^-1 (p1 x p2) ~ M^-1 n, which simplifies the paper's quotient. */
  double d_p = 2.0 * d->A * n_m_inv_n;
  s.to_r = ss_vec3_scale(n, -s.z_r);
  s.to_v = ss_vec3_madd(s.to_r, m_inv_n, 2.0 * (s.z_r + d_p) / n_m_inv_n);
  s.z_v = s.z_r + 2.0 * d_p;
  return s;
}

/* Jakob et al. 2010, eq. 47-48 per unit power: one source of height z at
 * offset `to` from the entry point, seen from x = x_o - x_i. */
static double source_term(const aniso_dipole *d, int c, ss_vec3 x, ss_vec3 to, double z) {
  double dist = ss_vec3_length(ss_mat3_apply(d->P[c], ss_vec3_sub(x, to)));
  double bd = d->beta[c] * dist;
  return z * (bd + 1.0) * exp(-bd) / (dist * dist * dist);
}

/* R(x_o) for a unit beam entering at x_i with normal n, x = x_o - x_i. */
static double exitance_at(const aniso_dipole *d, int c, ss_vec3 n, ss_vec3 x) {
  sources s = place_sources(d, c, n);
  return s.alpha * d->det_P[c] / (4.0 * SS_PI) *
         (source_term(d, c, x, s.to_r, s.z_r) + source_term(d, c, x, s.to_v, s.z_v));
}

/* The exitance integrated over the tangent plane: each source's flux through
 * the plane is e^{-beta h} / 2 with h its distance to the plane in the space
 * transformed by P, z / sqrt(n^T M^-1 n) (Gauss's theorem there). */
static double plane_total(const aniso_dipole *d, int c, ss_vec3 n) {
  sources s = place_sources(d, c, n);
  double k = d->beta[c] / sqrt(ss_vec3_dot(n, ss_mat3_apply(d->M_inv[c], n)));
  return 0.5 * s.alpha * (exp(-k * s.z_r) + exp(-k * s.z_v));
}

static const ss_option aniso_options[] = {
    {.name = "flake_distribution",
     .type = SS_OPTION_CHOICE,
     .def = "medium",
     .choices = "medium|uniform|surface|fiber",
     .help = "the flakes when the medium has none (medium: the medium's, uniform without)"},
    {.name = "flake_exponent",
     .type = SS_OPTION_DOUBLE,
     .def = "20",
     .lo = 0.0,
     .hi = 1000.0,
     .help = "p of D ~ |cos|^p (surface) or |sin|^p (fiber) about the axis"},
    {.name = "flake_axis",
     .type = SS_OPTION_STRING,
     .def = "0,0,1",
     .help = "the flakes' axis x,y,z in world space (any length)",
     .meta = "X,Y,Z"},
    {0},
};

/* The flakes: the medium's, or the options' when the medium has none. */
static ss_status resolve_flakes(const ss_bssrdf_params *p, ss_medium_flakes *f, ss_error *err) {
  int choice = ss_bssrdf_params_choice(p, &aniso_options[0]);
  for (int i = 0; i < p->n_options && choice == 0; ++i) {
    if (strcmp(p->options[i].name, aniso_options[0].name) != 0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "aniso-dipole: %s: only with flake_distribution uniform, surface or "
                          "fiber",
                          p->options[i].name);
    }
  }
  if (choice == 0) {
    *f = p->medium.flakes;
    if (f->type == SS_FLAKE_NONE) {
      *f = (ss_medium_flakes){.type = SS_FLAKE_UNIFORM, .axis = {0.0, 0.0, 1.0}};
    }
    return SS_OK;
  }
  if (p->medium.flakes.type != SS_FLAKE_NONE) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "aniso-dipole: flake_distribution: the medium already has flakes (%s); "
                        "give them in one place",
                        ss_flake_type_name(p->medium.flakes.type));
  }
  static const ss_flake_type types[] = {SS_FLAKE_UNIFORM, SS_FLAKE_SURFACE, SS_FLAKE_FIBER};
  const char *axis = ss_bssrdf_params_string(p, &aniso_options[2]);
  double x, y, z;
  char tail;
  if (sscanf(axis, "%lf , %lf , %lf %c", &x, &y, &z, &tail) != 3 ||
      !isfinite(sqrt(x * x + y * y + z * z)) || !(sqrt(x * x + y * y + z * z) > 1e-12)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "aniso-dipole: flake_axis: expected x,y,z, finite and not all zero, got "
                        "'%s'",
                        axis);
  }
  *f = (ss_medium_flakes){.type = types[choice - 1],
                          .p = ss_bssrdf_params_double(p, &aniso_options[1]),
                          .axis = {x, y, z}};
  ss_status st = ss_medium_flakes_check(f, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "aniso-dipole: ");
  }
  return st;
}

/* The coefficients of channel c: density, M, P, beta and the sampler. */
static ss_status init_channel(aniso_dipole *d, int c, double sigma_s, double sigma_a,
                              ss_error *err) {
  d->density[c] = ss_flake_medium_density(sigma_s, sigma_a);
  /* M scales with the density (eq. 31) and turns with the axis. */
  const ss_frame *f = &d->axis;
  ss_mat3 frame = {{{f->s.x, f->t.x, f->n.x}, {f->s.y, f->t.y, f->n.y}, {f->s.z, f->t.z, f->n.z}}};
  d->M[c] = ss_mat3_scale(ss_mat3_mul(frame, ss_mat3_mul(d->M_z[c], ss_mat3_transpose(frame))),
                          d->density[c]);
  /* P = M^(1/2) = Q D^(1/2) Q^T (Jakob et al. 2010, eq. 41). */
  if (!ss_mat3_sym_power(d->M[c], 0.5, &d->P[c]) || !ss_mat3_inverse(d->M[c], &d->M_inv[c])) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "aniso-dipole: the diffusion matrix is not positive definite");
  }
  d->det_P[c] = ss_mat3_det(d->P[c]);
  /* eq. 43: beta = sqrt(mu0[sigma_a] / (4 pi)). */
  d->beta[c] = sqrt(d->mu0_1[c] * d->density[c] / (4.0 * SS_PI));
  double lambda[3];
  ss_mat3 q;
  ss_mat3_sym_eigen(d->M[c], lambda, &q);
  /* In u = P x the isotropic dipole's rates sigma_tr and sigma_t' are beta
   * and sqrt(sigma_t' / 3) = sqrt(tr M / 9). */
  ss_radial_mix_init_diffusion(&d->mix[c], d->beta[c],
                               sqrt((lambda[0] + lambda[1] + lambda[2]) / 9.0));
  d->max_r[c] = ss_radial_mix_max_radius(&d->mix[c]) / sqrt(lambda[0]);
  d->base.total[c] = plane_total(d, c, ss_vec3_make(0.0, 0.0, 1.0));
  return SS_OK;
}

/* The base model whose tables this one may borrow: an aniso-dipole of the
 * same flake distribution (any axis) and the same albedos (to rounding). */
static const aniso_dipole *tables_from(const ss_bssrdf_params *p, const ss_medium_flakes *f,
                                       const double albedo[SS_BSSRDF_CHANNELS]) {
  if (!p->base || strcmp(p->base->ops->name, "aniso-dipole") != 0) {
    return NULL;
  }
  const aniso_dipole *b = p->base->state;
  if (b->spec.type != f->type || b->spec.p != f->p || b->spec.albedo_falloff != f->albedo_falloff ||
      b->spec.albedo_exponent != f->albedo_exponent) {
    return NULL;
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    /* A density scales sigma_s and sigma_a alike: the albedo to rounding. */
    if (!(fabs(b->flakes[c]->albedo.alpha1 - albedo[c]) <= 1e-12 * albedo[c])) {
      return NULL;
    }
  }
  return b;
}

/* The flakes about +z of each channel, built or borrowed, with M and mu0 at
 * unit density. */
static ss_status init_flakes(aniso_dipole *d, const ss_bssrdf_params *p,
                             const double albedo[SS_BSSRDF_CHANNELS], ss_error *err) {
  const aniso_dipole *b = tables_from(p, &d->spec, albedo);
  if (b) {
    memcpy(d->flakes, b->flakes, sizeof d->flakes);
    memcpy(d->M_z, b->M_z, sizeof d->M_z);
    memcpy(d->mu0_1, b->mu0_1, sizeof d->mu0_1);
    return SS_OK;
  }
  d->own = malloc(SS_BSSRDF_CHANNELS * sizeof *d->own);
  if (!d->own) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "aniso-dipole: out of memory");
  }
  ss_medium_flakes about_z = d->spec;
  about_z.axis = ss_vec3_make(0.0, 0.0, 1.0);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    if (c > 0 && albedo[c] == d->flakes[c - 1]->albedo.alpha1 && about_z.albedo_falloff == 0.0) {
      d->flakes[c] = d->flakes[c - 1]; /* the tables depend on the albedo only */
    } else {
      ss_status st = ss_microflake_init_medium(&d->own[c], &about_z, albedo[c], err);
      if (st != SS_OK) {
        return st;
      }
      d->flakes[c] = &d->own[c];
    }
    d->M_z[c] = ss_flake_diffusion_matrix(d->flakes[c], 1.0);
    d->mu0_1[c] = ss_flake_diffusion_mu0(d->flakes[c], 1.0);
  }
  return SS_OK;
}

static void aniso_destroy(void *state) {
  aniso_dipole *d = state;
  if (d) {
    free(d->own);
    free(d);
  }
}

static ss_status aniso_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  ss_medium_flakes flakes;
  ss_status st = resolve_flakes(p, &flakes, err);
  if (st != SS_OK) {
    return st;
  }
  aniso_dipole *d = calloc(1, sizeof *d);
  if (!d) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "aniso-dipole: out of memory");
  }
  ss_radial_model_init(&d->base, p->eta, SS_RADIAL_EXIT_FRESNEL, NULL);
  d->spec = flakes;
  d->axis = ss_frame_from_normal(ss_vec3_normalize(flakes.axis));
  d->uniform = flakes.type == SS_FLAKE_UNIFORM;
  /* Jensen et al. 2001 / Jakob et al. 2010, eq. 26: A = (1 + Fdr)/(1 - Fdr). */
  d->A = ss_fresnel_A(p->eta);
  double sigma_s[SS_BSSRDF_CHANNELS], albedo[SS_BSSRDF_CHANNELS];
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    /* Without flakes, g enters by similarity: the uniform flakes of sigma_s'. */
    double g = p->medium.flakes.type == SS_FLAKE_NONE ? p->medium.g.c[c] : 0.0;
    sigma_s[c] = (1.0 - g) * p->medium.sigma_s.c[c];
    albedo[c] = sigma_s[c] / (sigma_s[c] + p->medium.sigma_a.c[c]);
  }
  st = init_flakes(d, p, albedo, err);
  for (int c = 0; c < SS_BSSRDF_CHANNELS && st == SS_OK; ++c) {
    st = init_channel(d, c, sigma_s[c], p->medium.sigma_a.c[c], err);
  }
  if (st != SS_OK) {
    aniso_destroy(d);
    return st;
  }
  *state = d;
  return SS_OK;
}

/* On curved geometry x_o leaves the tangent plane at x_i: the offset is
 * turned into that plane about x_i, keeping its length (the classical
 * dipole's R_d(|x_o - x_i|)) and its direction's projection. */
static ss_vec3 tangent_offset(ss_vec3 n, ss_vec3 x) {
  double len = ss_vec3_length(x);
  ss_vec3 t = ss_vec3_madd(x, n, -ss_vec3_dot(x, n));
  double tl = ss_vec3_length(t);
  if (!(tl > 1e-12 * len)) {
    return ss_vec3_scale(ss_frame_from_normal(n).s, len);
  }
  return tl == len ? x : ss_vec3_scale(t, len / tl);
}

static void aniso_eval(const void *state, const ss_bssrdf_query *q, double s[SS_BSSRDF_CHANNELS]) {
  const aniso_dipole *d = state;
  double f = ss_ft_outside(ss_vec3_dot(q->w_i, q->n_i), d->base.eta) *
             ss_ft_outside(ss_vec3_dot(q->w_o, q->n_o), d->base.eta) * d->base.s_scale;
  ss_vec3 x = tangent_offset(q->n_i, ss_vec3_sub(q->x_o, q->x_i));
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    s[c] = f == 0.0 ? 0.0 : f * exitance_at(d, c, q->n_i, x);
  }
}

static void aniso_exitance(const void *state, double cos_i, double x, double y,
                           double out[SS_BSSRDF_CHANNELS]) {
  const aniso_dipole *d = state;
  double f = ss_ft_outside(cos_i, d->base.eta) * d->base.m_scale;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = f * exitance_at(d, c, ss_vec3_make(0, 0, 1), ss_vec3_make(x, y, 0.0));
  }
}

/* Not radial: the profile reported is R averaged over the circle of radius
 * r at normal incidence (what the half-space's radial bins see). */
#define PROFILE_PHI 64
static void aniso_profile(const void *state, int channel, double r, ss_bssrdf_profile_value *out) {
  const aniso_dipole *d = state;
  double sum = 0.0;
  for (int k = 0; k < PROFILE_PHI; ++k) {
    double phi = 2.0 * SS_PI * (k + 0.5) / PROFILE_PHI;
    sum += exitance_at(d, channel, ss_vec3_make(0, 0, 1),
                       ss_vec3_make(r * cos(phi), r * sin(phi), 0.0));
  }
  memset(out, 0, sizeof *out);
  out->value = out->ms = sum / PROFILE_PHI;
}

/* The footprint's quadratic form in the sampling plane: G = [s t]^T M [s t]. */
static void footprint_form(const aniso_dipole *d, int c, const ss_frame *f, double g[3]) {
  ss_vec3 ms = ss_mat3_apply(d->M[c], f->s), mt = ss_mat3_apply(d->M[c], f->t);
  g[0] = ss_vec3_dot(f->s, ms);
  g[1] = ss_vec3_dot(f->s, mt);
  g[2] = ss_vec3_dot(f->t, mt);
}

static int aniso_sample_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                              double u1, double u2, ss_bssrdf_entry *e) {
  const aniso_dipole *d = state;
  double g[3];
  footprint_form(d, channel, &ctx->frame, g);
  ss_bssrdf_entry u;
  ss_radial_mix_sample(&d->mix[channel], u1, u2, &u);
  /* (a, b) = G^(-1/2) u, with the 2 x 2 square root
   * G^(1/2) = (G + sqrt(det G) I) / sqrt(tr G + 2 sqrt(det G)). */
  double det = g[0] * g[2] - g[1] * g[1], sd = sqrt(det), k = sqrt(g[0] + g[2] + 2.0 * sd);
  double h0 = (g[0] + sd) / k, h1 = g[1] / k, h2 = (g[2] + sd) / k, hdet = h0 * h2 - h1 * h1;
  double ux = u.r * cos(u.phi), uy = u.r * sin(u.phi);
  double a = (h2 * ux - h1 * uy) / hdet, b = (h0 * uy - h1 * ux) / hdet;
  e->r = hypot(a, b);
  e->phi = atan2(b, a);
  if (e->phi < 0.0) {
    e->phi += 2.0 * SS_PI;
  }
  e->pdf = ss_radial_mix_pdf(&d->mix[channel], u.r) * sd;
  return isfinite(e->r) && e->pdf > 0.0;
}

static double aniso_pdf_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                              double r, double phi) {
  const aniso_dipole *d = state;
  double g[3], a = r * cos(phi), b = r * sin(phi);
  footprint_form(d, channel, &ctx->frame, g);
  double q = g[0] * a * a + 2.0 * g[1] * a * b + g[2] * b * b;
  return ss_radial_mix_pdf(&d->mix[channel], sqrt(fmax(0.0, q))) * sqrt(g[0] * g[2] - g[1] * g[1]);
}

static double aniso_max_radius(const void *state, int channel) {
  return ((const aniso_dipole *)state)->max_r[channel];
}

const ss_bssrdf_ops ss_bssrdf_model_aniso_dipole = {
    .name = "aniso-dipole",
    .summary = "anisotropic diffusion dipole for micro-flake media (Jakob et al. 2010)",
    .flags = SS_BSSRDF_FLAKES | SS_BSSRDF_ORIENTED | SS_BSSRDF_TABULATED,
    .options = aniso_options,
    .create = aniso_create,
    .destroy = aniso_destroy,
    .eval = aniso_eval,
    .sample_entry = aniso_sample_entry,
    .pdf_entry = aniso_pdf_entry,
    .max_radius = aniso_max_radius,
    .total_reflectance = ss_radial_model_total_reflectance,
    .rd = ss_radial_model_rd,
    .profile = aniso_profile,
    .exitance = aniso_exitance,
    .brdf = ss_radial_model_brdf,
};
