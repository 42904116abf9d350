/* Conductors: smooth (a delta reflection) and rough (the reflection half of
 * Walter et al. 2007 with visible-normal sampling, isotropic or
 * anisotropic), with the exact Fresnel reflectance of a complex index per
 * channel, and optionally the energy compensation of Kulla & Conty 2017
 * (conductor_ms.c). One-sided: they reflect light arriving from outside. */
#include "subsurf/bsdf.h"
#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"

#include <math.h>

static ss_vec3 black(void) { return ss_vec3_make(0.0, 0.0, 0.0); }

static ss_vec3 fresnel(const ss_bsdf *b, double cos_theta) {
  return ss_vec3_make(ss_fresnel_conductor(cos_theta, b->eta_c.x, b->k_c.x),
                      ss_fresnel_conductor(cos_theta, b->eta_c.y, b->k_c.y),
                      ss_fresnel_conductor(cos_theta, b->eta_c.z, b->k_c.z));
}

/* ---- Smooth. */

static ss_vec3 smooth_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) { return black(); }

static double smooth_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) { return 0.0; }

static int smooth_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                         ss_bsdf_sample *s) {
  if (!(wo.z > 0.0)) {
    return 0;
  }
  s->wi = ss_vec3_make(-wo.x, -wo.y, wo.z);
  s->f = ss_vec3_scale(fresnel(b, wo.z), 1.0 / wo.z);
  s->pdf = 1.0;
  s->lobe = SS_BSDF_REFLECTION | SS_BSDF_DELTA;
  s->eta = 1.0;
  return 1;
}

static const ss_bsdf_ops smooth_ops = {"conductor", smooth_eval, smooth_pdf, smooth_sample};

/* ---- Rough. */

/* The half vector of a reflection (Walter et al. 2007, eq. 13); 0 unless
 * both directions are outside. */
static int half_vector(ss_vec3 wo, ss_vec3 wi, ss_vec3 *wm) {
  if (!(wo.z > 0.0) || !(wi.z > 0.0)) {
    return 0;
  }
  ss_vec3 h = ss_vec3_add(wo, wi);
  double len2 = ss_vec3_length2(h);
  if (!(len2 > 0.0)) {
    return 0;
  }
  *wm = ss_vec3_scale(h, 1.0 / sqrt(len2));
  return 1;
}

/* Walter et al. 2007, eq. 20 with the conductor's Fresnel term. */
static ss_vec3 single_value(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, ss_vec3 wm) {
  double dg = ss_microfacet_d(&b->mf, wm) * ss_microfacet_g(&b->mf, wo, wi, wm);
  return ss_vec3_scale(fresnel(b, ss_vec3_dot(wo, wm)), dg / (4.0 * wo.z * wi.z));
}

/* Visible-normal density times the reflection Jacobian 1 / (4 |wo.wm|)
 * (Walter et al. 2007, eq. 14). */
static double single_density(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wm) {
  return ss_microfacet_pdf_visible(&b->mf, wo, wm) / (4.0 * fabs(ss_vec3_dot(wo, wm)));
}

/* KullaConty2017, the energy compensation lobe: the energy 1 - E(wo) that
 * the F = 1 single-scattering model loses, spread reciprocally as
 * (1 - E(wo)) (1 - E(wi)) / (pi (1 - E_avg)) and coloured by f_ms. */
static ss_vec3 compensation_value(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  double e_avg = ss_conductor_ms_average(b->cms);
  double v = (1.0 - ss_conductor_ms_albedo(b->cms, wo)) *
             (1.0 - ss_conductor_ms_albedo(b->cms, wi)) / (SS_PI * (1.0 - e_avg));
  return ss_vec3_scale(b->f_ms, v);
}

static ss_vec3 rough_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  ss_vec3 wm;
  if (!half_vector(wo, wi, &wm)) {
    return black();
  }
  ss_vec3 f = single_value(b, wo, wi, wm);
  return b->cms ? ss_vec3_add(f, compensation_value(b, wo, wi)) : f;
}

/* With compensation the single-scattering lobe is sampled with probability
 * E(wo) and the cosine-distributed compensation lobe otherwise. */
static double rough_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  ss_vec3 wm;
  if (!half_vector(wo, wi, &wm)) {
    return 0.0;
  }
  double p = single_density(b, wo, wm);
  if (!b->cms) {
    return p;
  }
  double q = ss_conductor_ms_albedo(b->cms, wo);
  return q * p + (1.0 - q) * ss_pdf_cosine_hemisphere(wi.z);
}

static int rough_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                        ss_bsdf_sample *s) {
  if (!(wo.z > 0.0)) {
    return 0;
  }
  ss_vec3 wi;
  if (b->cms && uc >= ss_conductor_ms_albedo(b->cms, wo)) {
    wi = ss_sample_cosine_hemisphere(u1, u2);
  } else {
    wi = ss_reflect(wo, ss_microfacet_sample_visible(&b->mf, wo, u1, u2));
  }
  double pdf = rough_pdf(b, wo, wi);
  if (!(pdf > 0.0) || !isfinite(pdf)) {
    return 0;
  }
  s->wi = wi;
  s->f = rough_eval(b, wo, wi);
  s->pdf = pdf;
  s->lobe = SS_BSDF_REFLECTION;
  s->eta = 1.0;
  return 1;
}

static const ss_bsdf_ops rough_ops = {"rough_conductor", rough_eval, rough_pdf, rough_sample};

/* KullaConty2017, the Fresnel term of the compensation: the average
 * Fresnel reflectance F_avg = 2 int_0^1 F(mu) mu dmu (64-point midpoint
 * rule) and F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)). */
static double fresnel_ms(double eta, double k, double e_avg) {
  enum { N = 64 };
  double f_avg = 0.0;
  for (int i = 0; i < N; ++i) {
    double mu = (i + 0.5) / N;
    f_avg += 2.0 * ss_fresnel_conductor(mu, eta, k) * mu / N;
  }
  return f_avg * f_avg * e_avg / (1.0 - f_avg * (1.0 - e_avg));
}

ss_status ss_bsdf_conductor_init(ss_bsdf *b, ss_vec3 eta, ss_vec3 k, const ss_microfacet *mf,
                                 int compensate, ss_error *err) {
  const double e[3] = {eta.x, eta.y, eta.z}, kk[3] = {k.x, k.y, k.z};
  for (int c = 0; c < 3; ++c) {
    if (!(e[c] > 0.0 && isfinite(e[c])) || !(kk[c] >= 0.0 && isfinite(kk[c]))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "conductor: eta (%g, %g, %g) must be > 0 and k (%g, %g, %g) >= 0", e[0],
                          e[1], e[2], kk[0], kk[1], kk[2]);
    }
  }
  b->ops = &smooth_ops;
  b->lobes = SS_BSDF_REFLECTION | SS_BSDF_DELTA;
  b->mode = SS_TRANSPORT_RADIANCE;
  b->eta = 1.0;
  b->mf.type = SS_MICROFACET_GGX;
  b->mf.alpha = 0.0;
  b->mf.alpha_v = 0.0;
  b->reflectance = black();
  b->ms.on = 0;
  b->eta_c = eta;
  b->k_c = k;
  b->cms = NULL;
  b->f_ms = black();
  if (!mf || (mf->alpha < 1e-3 && ss_microfacet_alpha_v(mf) < 1e-3)) {
    return SS_OK;
  }
  ss_status st = ss_microfacet_init_anisotropic(&b->mf, mf->type, fmax(mf->alpha, 1e-3),
                                                fmax(ss_microfacet_alpha_v(mf), 1e-3), err);
  if (st == SS_OK && compensate) {
    st = ss_conductor_ms_get(&b->mf, &b->cms, err);
  }
  if (st != SS_OK) {
    return st;
  }
  if (b->cms && !(ss_conductor_ms_average(b->cms) < 1.0 - 1e-9)) {
    b->cms = NULL; /* nothing (measurable) is lost */
  }
  if (b->cms) {
    double e_avg = ss_conductor_ms_average(b->cms);
    b->f_ms = ss_vec3_make(fresnel_ms(eta.x, k.x, e_avg), fresnel_ms(eta.y, k.y, e_avg),
                           fresnel_ms(eta.z, k.z, e_avg));
  }
  b->ops = &rough_ops;
  b->lobes = SS_BSDF_REFLECTION;
  return SS_OK;
}
