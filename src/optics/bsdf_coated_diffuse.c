/* Coated diffuse (a smooth plastic, Mitsuba's "plastic", pbrt-v4's
 * coateddiffuse with a smooth interface): a smooth dielectric coat of
 * index eta over a Lambertian base of reflectance R in optical contact,
 * with nothing absorbing between them.
 *
 * The coat is a layer stack of two: the interface (delta reflection F(mu)
 * from outside, transmission 1 - F(mu), and from inside the hemispherical
 * reflectance F_int = 2 int_0^1 F(-mu) mu dmu of the diffuse light the base
 * sends up) and the base. Light refracted in reaches the base as irradiance
 * (1 - F(mu_i)) cos(theta_i) dw_i per unit incident radiance; the base and
 * the coat's underside exchange diffuse light, the geometric series
 * R (1 + R F_int + (R F_int)^2 + ...) = R / (1 - R F_int) (the adding
 * equations of HanrahanKrueger1993 / Jakob2014 for a Lambertian layer under
 * an interface, in which diffuse light stays diffuse), and the radiance
 * inside leaves through 1 - F(mu_o), spread over eta^2 times the solid
 * angle. So
 *   f(wo, wi) = F(mu_o) delta_mirror
 *             + R / (1 - R F_int) (1 - F(mu_i)) (1 - F(mu_o)) / (pi eta^2).
 * The diffuse part is reciprocal; with R = 1 the albedo is
 *   F(mu_o) + (1 - F(mu_o)) (1 - F_avg) / (eta^2 (1 - F_int)) = 1,
 * since 1 - F_int = (1 - F_avg) / eta^2 (energy balance across the
 * interface, F_avg = 2 int_0^1 F(mu) mu dmu from outside).
 *
 * The stack's three operators (the interface's reflection and
 * transmission, the base's reflection) are what the layer library's
 * adding-doubling (src/transport/layer_*.c) combines for arbitrary
 * layers: this closed form is the case it can replace (rough coats,
 * absorbing coats, non-Lambertian bases).
 *
 * Sampling: the mirror lobe with probability F(mu_o) / (F(mu_o) + d),
 * d the diffuse part's mean albedo over the channels, else a cosine lobe. */
#include "subsurf/bsdf.h"
#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"

#include <math.h>

static double mean(ss_vec3 v) { return (v.x + v.y + v.z) / 3.0; }

/* The diffuse part's albedo from mu_o: (1 - F_o) R' (1 - F_avg) / eta^2. */
static double diffuse_albedo(const ss_bsdf *b, double f_o) {
  return (1.0 - f_o) * mean(b->coated_base) * (1.0 - b->coat_f_avg) / (b->eta_sheet * b->eta_sheet);
}

static double specular_probability(const ss_bsdf *b, double f_o) {
  double d = diffuse_albedo(b, f_o);
  return f_o + d > 0.0 ? f_o / (f_o + d) : 1.0;
}

static ss_vec3 coated_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  if (!(wo.z > 0.0) || !(wi.z > 0.0)) {
    return ss_vec3_make(0.0, 0.0, 0.0);
  }
  double t = (1.0 - ss_fresnel_dielectric(wo.z, b->eta_sheet)) *
             (1.0 - ss_fresnel_dielectric(wi.z, b->eta_sheet));
  return ss_vec3_scale(b->coated_base, t / (SS_PI * b->eta_sheet * b->eta_sheet));
}

static double coated_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  if (!(wo.z > 0.0) || !(wi.z > 0.0)) {
    return 0.0;
  }
  double p_s = specular_probability(b, ss_fresnel_dielectric(wo.z, b->eta_sheet));
  return (1.0 - p_s) * ss_pdf_cosine_hemisphere(wi.z);
}

static int coated_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                         ss_bsdf_sample *s) {
  if (!(wo.z > 0.0)) {
    return 0;
  }
  double f_o = ss_fresnel_dielectric(wo.z, b->eta_sheet), p_s = specular_probability(b, f_o);
  if (uc < p_s) {
    s->wi = ss_vec3_make(-wo.x, -wo.y, wo.z);
    s->f = ss_vec3_make(f_o / wo.z, f_o / wo.z, f_o / wo.z);
    s->pdf = p_s;
    s->lobe = SS_BSDF_REFLECTION | SS_BSDF_DELTA;
  } else {
    s->wi = ss_sample_cosine_hemisphere(u1, u2);
    s->f = coated_eval(b, wo, s->wi);
    s->pdf = coated_pdf(b, wo, s->wi);
    s->lobe = SS_BSDF_REFLECTION;
  }
  s->eta = 1.0;
  return s->pdf > 0.0;
}

static const ss_bsdf_ops coated_ops = {"coated_diffuse", coated_eval, coated_pdf, coated_sample};

ss_status ss_bsdf_coated_diffuse_init(ss_bsdf *b, ss_vec3 reflectance, double eta, ss_error *err) {
  if (!(eta > 1.0) || !isfinite(eta)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "coated diffuse: eta = %g must be > 1 and finite", eta);
  }
  ss_status st = ss_bsdf_diffuse_init(b, reflectance, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "coated diffuse: ");
    return st;
  }
  /* Internal hemispherical reflectance 2 C_1 and, by the balance, the
   * external one. */
  double f_int = 2.0 * ss_fresnel_moment(1, eta);
  double base[3] = {reflectance.x, reflectance.y, reflectance.z};
  for (int c = 0; c < 3; ++c) {
    base[c] /= 1.0 - base[c] * f_int;
  }
  b->ops = &coated_ops;
  b->lobes = SS_BSDF_REFLECTION;
  b->eta_sheet = eta;
  b->coated_base = ss_vec3_make(base[0], base[1], base[2]);
  b->coat_f_avg = 1.0 - eta * eta * (1.0 - f_int);
  return SS_OK;
}
