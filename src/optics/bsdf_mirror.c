/* A perfect mirror: one-sided delta reflection of a constant reflectance. */
#include "subsurf/bsdf.h"

#include <math.h>

static ss_vec3 mirror_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  return ss_vec3_make(0.0, 0.0, 0.0);
}

static double mirror_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) { return 0.0; }

static int mirror_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                         ss_bsdf_sample *s) {
  if (!(wo.z > 0.0)) {
    return 0;
  }
  s->wi = ss_vec3_make(-wo.x, -wo.y, wo.z);
  s->f = ss_vec3_scale(b->reflectance, 1.0 / wo.z);
  s->pdf = 1.0;
  s->lobe = SS_BSDF_REFLECTION | SS_BSDF_DELTA;
  s->eta = 1.0;
  return 1;
}

static const ss_bsdf_ops mirror_ops = {"mirror", mirror_eval, mirror_pdf, mirror_sample};

ss_status ss_bsdf_mirror_init(ss_bsdf *b, ss_vec3 reflectance, ss_error *err) {
  ss_status st = ss_bsdf_diffuse_init(b, reflectance, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "mirror: ");
    return st;
  }
  b->ops = &mirror_ops;
  b->lobes = SS_BSDF_REFLECTION | SS_BSDF_DELTA;
  return SS_OK;
}
