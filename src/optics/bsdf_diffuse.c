/* Lambertian reflection, two-sided: it reflects on the side wo lies on. */
#include "subsurf/bsdf.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <string.h>

static ss_vec3 diffuse_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  if (wo.z * wi.z <= 0.0) {
    return ss_vec3_make(0.0, 0.0, 0.0);
  }
  return ss_vec3_scale(b->reflectance, SS_INV_PI);
}

static double diffuse_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  if (wo.z * wi.z <= 0.0) {
    return 0.0;
  }
  return ss_pdf_cosine_hemisphere(fabs(wi.z));
}

static int diffuse_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                          ss_bsdf_sample *s) {
  if (wo.z == 0.0) {
    return 0;
  }
  ss_vec3 wi = ss_sample_cosine_hemisphere(u1, u2);
  if (wo.z < 0.0) {
    wi.z = -wi.z;
  }
  double pdf = ss_pdf_cosine_hemisphere(fabs(wi.z));
  if (!(pdf > 0.0)) {
    return 0;
  }
  s->wi = wi;
  s->f = ss_vec3_scale(b->reflectance, SS_INV_PI);
  s->pdf = pdf;
  s->lobe = SS_BSDF_REFLECTION;
  s->eta = 1.0;
  return 1;
}

static const ss_bsdf_ops diffuse_ops = {"diffuse", diffuse_eval, diffuse_pdf, diffuse_sample};

ss_status ss_bsdf_diffuse_init(ss_bsdf *b, ss_vec3 reflectance, ss_error *err) {
  const double r[3] = {reflectance.x, reflectance.y, reflectance.z};
  for (int k = 0; k < 3; ++k) {
    if (!(r[k] >= 0.0 && r[k] <= 1.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "diffuse: reflectance (%g, %g, %g) out of range (expected [0, 1])", r[0],
                          r[1], r[2]);
    }
  }
  memset(b, 0, sizeof *b);
  b->ops = &diffuse_ops;
  b->lobes = SS_BSDF_REFLECTION;
  b->mode = SS_TRANSPORT_RADIANCE;
  b->eta = 1.0;
  b->mf.type = SS_MICROFACET_GGX;
  b->mf.alpha = 1.0;
  b->mf.alpha_v = 0.0;
  b->reflectance = reflectance;
  return SS_OK;
}
