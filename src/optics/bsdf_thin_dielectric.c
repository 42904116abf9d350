/* A thin dielectric sheet (a window pane) between two regions of the same
 * medium: light reflects off the front face or enters the sheet and then
 * bounces between its parallel faces, each exit leaving either straight on
 * (the faces are parallel, so without a lateral offset for a sheet of no
 * thickness) or back along the mirror direction. Summing the bounces: with
 * R the Fresnel reflectance of one face and T = 1 - R,
 *   R' = R + T^2 R (1 + R^2 + R^4 + ...) = R + T^2 R / (1 - R^2) = 2R / (1 + R),
 *   T' = T^2 (1 + R^2 + ...) = T^2 / (1 - R^2) = 1 - R'. */
#include "subsurf/bsdf.h"
#include "subsurf/fresnel.h"

#include <math.h>

static ss_vec3 grey(double v) { return ss_vec3_make(v, v, v); }

static ss_vec3 thin_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) { return grey(0.0); }

static double thin_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) { return 0.0; }

static int thin_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                       ss_bsdf_sample *s) {
  if (wo.z == 0.0) {
    return 0;
  }
  double r = ss_fresnel_dielectric(fabs(wo.z), b->eta_sheet);
  double reflect = 2.0 * r / (1.0 + r), c = fabs(wo.z);
  if (uc < reflect) {
    s->wi = ss_vec3_make(-wo.x, -wo.y, wo.z);
    s->pdf = reflect;
    s->f = grey(reflect / c);
    s->lobe = SS_BSDF_REFLECTION | SS_BSDF_DELTA;
  } else {
    s->wi = ss_vec3_neg(wo);
    s->pdf = 1.0 - reflect;
    s->f = grey((1.0 - reflect) / c);
    s->lobe = SS_BSDF_TRANSMISSION | SS_BSDF_DELTA;
  }
  s->eta = 1.0;
  return s->pdf > 0.0;
}

static const ss_bsdf_ops thin_ops = {"thin_dielectric", thin_eval, thin_pdf, thin_sample};

ss_status ss_bsdf_thin_dielectric_init(ss_bsdf *b, double eta, ss_error *err) {
  if (!(eta > 0.0) || !isfinite(eta)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "thin dielectric: eta = %g must be positive and finite", eta);
  }
  ss_status st = ss_bsdf_diffuse_init(b, grey(0.0), err);
  if (st != SS_OK) {
    return st;
  }
  b->ops = &thin_ops;
  b->lobes = SS_BSDF_REFLECTION | SS_BSDF_TRANSMISSION | SS_BSDF_DELTA;
  b->eta_sheet = eta;
  return SS_OK;
}
