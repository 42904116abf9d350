/* A mix of two BSDFs by weight: f = w f_a + (1 - w) f_b, and the same for
 * the density. Sampling picks a part with probability w or 1 - w; a
 * non-delta sample then carries the mix's f and pdf in its direction (so
 * MIS sees the density of the whole mix), a delta sample its part's value
 * and probability times the part's weight. */
#include "subsurf/bsdf.h"

#include <math.h>

static ss_vec3 mix_eval(const ss_bsdf *m, ss_vec3 wo, ss_vec3 wi) {
  ss_vec3 a = ss_bsdf_eval(m->part[0], wo, wi), b = ss_bsdf_eval(m->part[1], wo, wi);
  return ss_vec3_add(ss_vec3_scale(a, m->weight), ss_vec3_scale(b, 1.0 - m->weight));
}

static double mix_pdf(const ss_bsdf *m, ss_vec3 wo, ss_vec3 wi) {
  return m->weight * ss_bsdf_pdf(m->part[0], wo, wi) +
         (1.0 - m->weight) * ss_bsdf_pdf(m->part[1], wo, wi);
}

static int mix_sample(const ss_bsdf *m, ss_vec3 wo, double uc, double u1, double u2,
                      ss_bsdf_sample *s) {
  int first = uc < m->weight;
  double w = first ? m->weight : 1.0 - m->weight;
  if (!(w > 0.0)) {
    return 0;
  }
  double u = first ? uc / w : (uc - m->weight) / w;
  if (!ss_bsdf_sample_dir(m->part[first ? 0 : 1], wo, fmin(u, nextafter(1.0, 0.0)), u1, u2, s)) {
    return 0;
  }
  if (s->lobe & SS_BSDF_DELTA) {
    s->f = ss_vec3_scale(s->f, w);
    s->pdf *= w;
    return 1;
  }
  s->f = mix_eval(m, wo, s->wi);
  s->pdf = mix_pdf(m, wo, s->wi);
  return s->pdf > 0.0;
}

static const ss_bsdf_ops mix_ops = {"mix", mix_eval, mix_pdf, mix_sample};

ss_status ss_bsdf_mix_init(ss_bsdf *m, const ss_bsdf *a, const ss_bsdf *b, double weight,
                           ss_error *err) {
  if (!(weight >= 0.0 && weight <= 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "mix: weight = %g must be in [0, 1]", weight);
  }
  ss_status st = ss_bsdf_diffuse_init(m, ss_vec3_make(0.0, 0.0, 0.0), err);
  if (st != SS_OK) {
    return st;
  }
  m->ops = &mix_ops;
  /* Delta only when both parts are (bsdf.h). */
  m->lobes = (a->lobes | b->lobes) & ~(unsigned)SS_BSDF_DELTA;
  m->lobes |= a->lobes & b->lobes & SS_BSDF_DELTA;
  m->part[0] = a;
  m->part[1] = b;
  m->weight = weight;
  return SS_OK;
}
