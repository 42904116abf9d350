/* Diffuse transmission (a lampshade, paper, leaves): Lambertian reflection
 * of R on the side wo lies on and Lambertian transmission of T to the
 * other; the lobe is chosen in proportion to the channels' mean R and T. */
#include "subsurf/bsdf.h"
#include "subsurf/sampling.h"

#include <math.h>

static double mean(ss_vec3 v) { return (v.x + v.y + v.z) / 3.0; }

/* The probability of sampling the reflection lobe. */
static double reflect_probability(const ss_bsdf *b) {
  double r = mean(b->reflectance), t = mean(b->transmittance);
  return r + t > 0.0 ? r / (r + t) : 0.0;
}

static ss_vec3 dt_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  if (wo.z == 0.0 || wi.z == 0.0) {
    return ss_vec3_make(0.0, 0.0, 0.0);
  }
  return ss_vec3_scale(wo.z * wi.z > 0.0 ? b->reflectance : b->transmittance, SS_INV_PI);
}

static double dt_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  if (wo.z == 0.0 || wi.z == 0.0) {
    return 0.0;
  }
  double pr = reflect_probability(b);
  return (wo.z * wi.z > 0.0 ? pr : 1.0 - pr) * ss_pdf_cosine_hemisphere(fabs(wi.z));
}

static int dt_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                     ss_bsdf_sample *s) {
  if (wo.z == 0.0) {
    return 0;
  }
  ss_vec3 wi = ss_sample_cosine_hemisphere(u1, u2);
  int reflect = uc < reflect_probability(b);
  if ((wo.z < 0.0) == reflect) {
    wi.z = -wi.z;
  }
  double pdf = dt_pdf(b, wo, wi);
  if (!(pdf > 0.0)) {
    return 0;
  }
  s->wi = wi;
  s->f = dt_eval(b, wo, wi);
  s->pdf = pdf;
  s->lobe = reflect ? SS_BSDF_REFLECTION : SS_BSDF_TRANSMISSION;
  s->eta = 1.0;
  return 1;
}

static const ss_bsdf_ops dt_ops = {"diffuse_transmission", dt_eval, dt_pdf, dt_sample};

ss_status ss_bsdf_diffuse_transmission_init(ss_bsdf *b, ss_vec3 reflectance, ss_vec3 transmittance,
                                            ss_error *err) {
  const double r[3] = {reflectance.x, reflectance.y, reflectance.z},
               t[3] = {transmittance.x, transmittance.y, transmittance.z};
  for (int c = 0; c < 3; ++c) {
    if (!(r[c] >= 0.0 && t[c] >= 0.0 && r[c] + t[c] <= 1.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "diffuse transmission: reflectance (%g, %g, %g) and transmittance (%g, "
                          "%g, %g) must be >= 0 with a sum <= 1 per channel",
                          r[0], r[1], r[2], t[0], t[1], t[2]);
    }
  }
  ss_status st = ss_bsdf_diffuse_init(b, reflectance, err);
  if (st != SS_OK) {
    return st;
  }
  b->ops = &dt_ops;
  b->lobes = SS_BSDF_REFLECTION | SS_BSDF_TRANSMISSION;
  b->transmittance = transmittance;
  return SS_OK;
}
