/* A one-sided BSDF seen from both sides: from inside, both directions are
 * mirrored through the surface (z -> -z) into the front's frame. */
#include "subsurf/bsdf.h"

#include <string.h>

static ss_vec3 flip(ss_vec3 w) { return ss_vec3_make(w.x, w.y, -w.z); }

static ss_vec3 two_sided_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  return wo.z < 0.0 ? ss_bsdf_eval(b->part[0], flip(wo), flip(wi))
                    : ss_bsdf_eval(b->part[0], wo, wi);
}

static double two_sided_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi) {
  return wo.z < 0.0 ? ss_bsdf_pdf(b->part[0], flip(wo), flip(wi)) : ss_bsdf_pdf(b->part[0], wo, wi);
}

static int two_sided_sample(const ss_bsdf *b, ss_vec3 wo, double uc, double u1, double u2,
                            ss_bsdf_sample *s) {
  if (!(wo.z < 0.0)) {
    return ss_bsdf_sample_dir(b->part[0], wo, uc, u1, u2, s);
  }
  if (!ss_bsdf_sample_dir(b->part[0], flip(wo), uc, u1, u2, s)) {
    return 0;
  }
  s->wi = flip(s->wi);
  return 1;
}

static const ss_bsdf_ops two_sided_ops = {"two_sided", two_sided_eval, two_sided_pdf,
                                          two_sided_sample};

ss_status ss_bsdf_two_sided_init(ss_bsdf *b, const ss_bsdf *front, ss_error *err) {
  ss_status st = ss_bsdf_diffuse_init(b, ss_vec3_make(0.0, 0.0, 0.0), err);
  if (st != SS_OK) {
    return st;
  }
  b->ops = &two_sided_ops;
  b->lobes = front->lobes;
  b->part[0] = front;
  return SS_OK;
}
