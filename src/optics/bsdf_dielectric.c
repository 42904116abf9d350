/* Dielectric interfaces: smooth (Dirac reflection and refraction) and rough
 * (Walter et al. 2007, "Microfacet Models for Refraction through Rough
 * Surfaces", sampled by visible normals as in pbrt-v4's
 * DielectricBxDF). Local frame: +z is the outside; eta = n_in / n_out. */
#include "optics/dielectric_ms.h"
#include "subsurf/bsdf.h"
#include "subsurf/fresnel.h"

#include <math.h>

static ss_vec3 grey(double v) { return ss_vec3_make(v, v, v); }

/* n(wi side) / n(wo side) for a transmission leaving along wo. */
static double relative_eta(double eta, ss_vec3 wo) { return wo.z > 0.0 ? eta : 1.0 / eta; }

/* Radiance is compressed by 1/eta_rel^2 entering a denser medium (Veach 1997,
 * sec. 5.2); importance is not. */
static double transport_scale(const ss_bsdf *b, double etap) {
  return b->mode == SS_TRANSPORT_RADIANCE ? 1.0 / (etap * etap) : 1.0;
}

/* ---- Smooth interface. */

static ss_vec3 smooth_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) { return grey(0.0); }

static double smooth_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) { return 0.0; }

static int smooth_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                         ss_bsdf_sample *s) {
  if (wo.z == 0.0) {
    return 0;
  }
  double r = ss_fresnel_dielectric(wo.z, b->eta), t = 1.0 - r;
  if (uc < r) {
    s->wi = ss_vec3_make(-wo.x, -wo.y, wo.z);
    s->pdf = r;
    s->f = grey(r / fabs(wo.z));
    s->lobe = SS_BSDF_REFLECTION | SS_BSDF_DELTA;
    s->eta = 1.0;
    return 1;
  }
  ss_vec3 wi;
  if (!(t > 0.0) || !ss_refract(wo, ss_vec3_make(0.0, 0.0, 1.0), b->eta, &wi)) {
    return 0;
  }
  double etap = relative_eta(b->eta, wo);
  s->wi = wi;
  s->pdf = t;
  s->f = grey(t * transport_scale(b, etap) / fabs(wi.z));
  s->lobe = SS_BSDF_TRANSMISSION | SS_BSDF_DELTA;
  s->eta = etap;
  return 1;
}

static const ss_bsdf_ops smooth_ops = {"dielectric", smooth_eval, smooth_pdf, smooth_sample};

/* ---- Rough interface. */

/* The (generalised) half vector of Walter et al. 2007, eqs. 13 and 16, turned
 * into the upper hemisphere; 0 for configurations no microfacet produces. */
static int half_vector(double eta, ss_vec3 wo, ss_vec3 wi, ss_vec3 *wm, double *etap) {
  int reflect = wo.z * wi.z > 0.0;
  *etap = reflect ? 1.0 : relative_eta(eta, wo);
  ss_vec3 h = ss_vec3_add(ss_vec3_scale(wi, *etap), wo);
  double len2 = ss_vec3_length2(h);
  if (wo.z == 0.0 || wi.z == 0.0 || !(len2 > 0.0)) {
    return 0;
  }
  h = ss_vec3_scale(h, 1.0 / sqrt(len2));
  if (h.z < 0.0) {
    h = ss_vec3_neg(h);
  }
  /* Backfacing microfacets contribute nothing. */
  if (ss_vec3_dot(h, wi) * wi.z < 0.0 || ss_vec3_dot(h, wo) * wo.z < 0.0) {
    return 0;
  }
  *wm = h;
  return 1;
}

/* Walter et al. 2007, eq. 20 (reflection) and eq. 21 (transmission). */
static double rough_value(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, ss_vec3 wm, double etap) {
  double d = ss_microfacet_d(&b->mf, wm), g = ss_microfacet_g(&b->mf, wo, wi, wm);
  double f = ss_fresnel_dielectric(ss_vec3_dot(wo, wm), b->eta);
  double cos_o = fabs(wo.z), cos_i = fabs(wi.z);
  if (wo.z * wi.z > 0.0) {
    return d * g * f / (4.0 * cos_i * cos_o);
  }
  double dot_i = ss_vec3_dot(wi, wm), dot_o = ss_vec3_dot(wo, wm);
  double denom = dot_i + dot_o / etap;
  denom *= denom;
  return d * g * (1.0 - f) * fabs(dot_i * dot_o / (cos_i * cos_o * denom)) *
         transport_scale(b, etap);
}

/* Density of wi: visible-normal pdf times the Jacobian of the half-vector
 * map (Walter et al. 2007, eqs. 14 and 17), times the lobe probability. */
static double rough_density(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, ss_vec3 wm, double etap) {
  double r = ss_fresnel_dielectric(ss_vec3_dot(wo, wm), b->eta), t = 1.0 - r;
  double dv = ss_microfacet_pdf_visible(&b->mf, wo, wm);
  if (wo.z * wi.z > 0.0) {
    return dv / (4.0 * fabs(ss_vec3_dot(wo, wm))) * r;
  }
  double dot_i = ss_vec3_dot(wi, wm), denom = dot_i + ss_vec3_dot(wo, wm) / etap;
  return dv * fabs(dot_i) / (denom * denom) * t;
}

static ss_vec3 rough_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  ss_vec3 wm;
  double etap;
  if (!half_vector(b->eta, wo, wi, &wm, &etap)) {
    return grey(0.0);
  }
  return grey(rough_value(b, wo, wi, wm, etap));
}

static double rough_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  ss_vec3 wm;
  double etap;
  if (!half_vector(b->eta, wo, wi, &wm, &etap)) {
    return 0.0;
  }
  return rough_density(b, wo, wi, wm, etap);
}

static int rough_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                        ss_bsdf_sample *s) {
  if (wo.z == 0.0) {
    return 0;
  }
  ss_vec3 wm = ss_microfacet_sample_visible(&b->mf, wo, u1, u2);
  double r = ss_fresnel_dielectric(ss_vec3_dot(wo, wm), b->eta);
  ss_vec3 wi;
  unsigned lobe;
  if (uc < r) {
    wi = ss_reflect(wo, wm);
    lobe = SS_BSDF_REFLECTION;
    if (wo.z * wi.z <= 0.0) {
      return 0;
    }
  } else {
    if (!ss_refract(wo, wm, b->eta, &wi)) {
      return 0;
    }
    lobe = SS_BSDF_TRANSMISSION;
    if (wo.z * wi.z >= 0.0) {
      return 0;
    }
  }
  /* Re-deriving wm from (wo, wi) keeps sample() consistent with eval/pdf. */
  double etap;
  if (!half_vector(b->eta, wo, wi, &wm, &etap)) {
    return 0;
  }
  double pdf = rough_density(b, wo, wi, wm, etap);
  if (!(pdf > 0.0) || !isfinite(pdf)) {
    return 0;
  }
  s->wi = wi;
  s->pdf = pdf;
  s->f = grey(rough_value(b, wo, wi, wm, etap));
  s->lobe = lobe;
  s->eta = etap;
  return 1;
}

static const ss_bsdf_ops rough_ops = {"rough_dielectric", rough_eval, rough_pdf, rough_sample};

/* ---- Rough interface with energy compensation (dielectric_ms.h): the sums
 * of the single-scattering and compensation lobes' values and densities. */

static ss_vec3 rough_ms_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  return ss_dielectric_ms_eval(b, wo, wi, rough_eval(b, wo, wi));
}

static double rough_ms_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  return ss_dielectric_ms_pdf(b, wo, wi, rough_pdf(b, wo, wi));
}

static int rough_ms_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                           ss_bsdf_sample *s) {
  if (wo.z == 0.0) {
    return 0;
  }
  ss_vec3 wi;
  if (!ss_dielectric_ms_pick(b, wo, &uc, u1, u2, &wi)) {
    if (!rough_sample(b, wo, uc, u1, u2, s)) {
      return 0;
    }
    wi = s->wi;
  }
  double pdf = rough_ms_pdf(b, wo, wi);
  if (wi.z == 0.0 || !(pdf > 0.0) || !isfinite(pdf)) {
    return 0;
  }
  int reflect = wo.z * wi.z > 0.0;
  s->wi = wi;
  s->pdf = pdf;
  s->f = rough_ms_eval(b, wo, wi);
  s->lobe = reflect ? SS_BSDF_REFLECTION : SS_BSDF_TRANSMISSION;
  s->eta = reflect ? 1.0 : relative_eta(b->eta, wo);
  return 1;
}

static const ss_bsdf_ops rough_ms_ops = {"rough_dielectric_ms", rough_ms_eval, rough_ms_pdf,
                                         rough_ms_sample};

static ss_status check_eta(double eta, ss_error *err) {
  if (!(eta > 0.0) || !isfinite(eta)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "dielectric: eta = %g must be positive and finite", eta);
  }
  return SS_OK;
}

ss_status ss_bsdf_dielectric_init(ss_bsdf *b, double eta, ss_transport_mode mode, ss_error *err) {
  ss_status st = check_eta(eta, err);
  if (st != SS_OK) {
    return st;
  }
  b->ops = &smooth_ops;
  b->lobes = SS_BSDF_REFLECTION | SS_BSDF_TRANSMISSION | SS_BSDF_DELTA;
  b->mode = mode;
  b->eta = eta;
  b->mf.type = SS_MICROFACET_GGX;
  b->mf.alpha = 0.0;
  b->mf.alpha_v = 0.0;
  b->reflectance = grey(0.0);
  b->ms.on = 0;
  return SS_OK;
}

ss_status ss_bsdf_rough_dielectric_init(ss_bsdf *b, double eta, const ss_microfacet *mf,
                                        ss_transport_mode mode, ss_error *err) {
  ss_status st = check_eta(eta, err);
  if (st != SS_OK) {
    return st;
  }
  /* Without roughness, or without an index step, microfacets do nothing. */
  if (mf->alpha < 1e-3 || eta == 1.0) {
    return ss_bsdf_dielectric_init(b, eta, mode, err);
  }
  ss_microfacet checked;
  st = ss_microfacet_init(&checked, mf->type, mf->alpha, err);
  if (st != SS_OK) {
    return st;
  }
  b->ops = &rough_ops;
  b->lobes = SS_BSDF_REFLECTION | SS_BSDF_TRANSMISSION;
  b->mode = mode;
  b->eta = eta;
  b->mf = checked;
  b->reflectance = grey(0.0);
  b->ms.on = 0;
  return SS_OK;
}

ss_status ss_bsdf_rough_dielectric_ms_init(ss_bsdf *b, double eta, const ss_microfacet *mf,
                                           ss_transport_mode mode, ss_error *err) {
  ss_status st = ss_bsdf_rough_dielectric_init(b, eta, mf, mode, err);
  if (st != SS_OK || b->ops != &rough_ops) {
    return st; /* smooth: nothing is lost */
  }
  ss_dielectric_ms_build(&b->ms, b);
  if (b->ms.on) {
    b->ops = &rough_ms_ops;
  }
  return SS_OK;
}

ss_status ss_bsdf_rough_dielectric_ms_at(ss_bsdf *b, double eta, const ss_microfacet *mf,
                                         ss_transport_mode mode, const ss_dielectric_ms_alpha *t,
                                         ss_error *err) {
  ss_status st = ss_bsdf_rough_dielectric_init(b, eta, mf, mode, err);
  if (st != SS_OK || b->ops != &rough_ops) {
    return st;
  }
  ss_dielectric_ms_alpha_at(t, mf->alpha, &b->ms);
  if (b->ms.on) {
    b->ops = &rough_ms_ops;
  }
  return SS_OK;
}
