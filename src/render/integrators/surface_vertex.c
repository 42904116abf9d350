/* The scattering vertex: evaluation, sampling, next-event estimation and
 * the step to the next vertex (surface_vertex.h). */
#include "render/integrators/surface_vertex.h"

#include "render/integrators/roulette.h"
#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <string.h>

/* A reflection sampled from a dielectric with its lobe choice forced: the
 * sampler reports pdf = Fr(wo.wm) x (density of wi); the density of the
 * forced sample is pdf / Fr(wo.wm), wm the reflection half vector. */
static double reflection_density(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, double pdf) {
  ss_vec3 wm = ss_vec3_normalize(ss_vec3_add(wo, wi));
  if (wm.z < 0.0) {
    wm = ss_vec3_neg(wm);
  }
  double fr = ss_fresnel_dielectric(ss_vec3_dot(wo, wm), b->eta);
  return fr > 0.0 ? pdf / fr : 0.0;
}

static ss_rgb entry_value(const ss_vertex *v, ss_vec3 wi, double cos_i) {
  ss_bssrdf_query q = v->query;
  q.w_i = wi;
  double s[SS_BSSRDF_CHANNELS];
  ss_bssrdf_eval(v->bssrdf, &q, s);
  return ss_rgb_scale(ss_rgb_make(s[0], s[1], s[2]), cos_i * v->scale);
}

/* The point source at x = query.x_o, z = source_depth below the entry
 * plane, seen from the surface point x_i: the half-space's exitance at the
 * lateral distance r_i = sqrt(|x_i - x|^2 - z^2) that puts x_i at its 3-D
 * distance from the real source, d_r = |x_i - x| (on a flat boundary the
 * lateral distance along it; elsewhere the far side of a thin part or of a
 * curved one is as far as it is, and a point nearer than z counts as r = 0). */
static ss_rgb source_value(const ss_vertex *v, double cos_i) {
  ss_vec3 d = ss_vec3_sub(v->query.x_i, v->query.x_o);
  double z = v->source_depth;
  double r = sqrt(fmax(0.0, ss_vec3_dot(d, d) - z * z));
  double s[SS_BSSRDF_CHANNELS];
  ss_bssrdf_point_source_radiance(v->bssrdf, z, r, cos_i, s);
  return ss_rgb_scale(ss_rgb_make(s[0], s[1], s[2]), cos_i * v->scale);
}

static ss_rgb brdf_value(const ss_vertex *v, ss_vec3 wi_local) {
  double f[SS_BSSRDF_CHANNELS];
  ss_bssrdf_brdf(v->bssrdf, wi_local, v->wo_local, f);
  return ss_rgb_scale(ss_rgb_make(f[0], f[1], f[2]), wi_local.z * v->scale);
}

ss_rgb ss_vertex_f(const ss_vertex *v, ss_vec3 wi, double *pdf) {
  if (v->kind == SS_VERTEX_PHASE) {
    *pdf = ss_phase_eval(v->phase, ss_vec3_dot(v->d, wi));
    return ss_rgb_gray(*pdf * v->scale);
  }
  ss_vec3 wl = ss_frame_to_local(v->frame, wi);
  *pdf = 0.0;
  if (v->kind == SS_VERTEX_ENTRY || v->kind == SS_VERTEX_SOURCE || v->kind == SS_VERTEX_BRDF) {
    double cos_i = ss_vec3_dot(wi, v->ng);
    if (!(cos_i > 0.0) || !(wl.z > 0.0)) {
      return ss_rgb_gray(0.0);
    }
    *pdf = ss_pdf_cosine_hemisphere(wl.z);
    return v->kind == SS_VERTEX_ENTRY    ? entry_value(v, wi, cos_i)
           : v->kind == SS_VERTEX_SOURCE ? source_value(v, cos_i)
                                         : brdf_value(v, wl);
  }
  if (v->kind == SS_VERTEX_REFLECTION && !(wl.z > 0.0 && ss_vec3_dot(wi, v->ng) > 0.0)) {
    return ss_rgb_gray(0.0);
  }
  *pdf = ss_bsdf_pdf(v->bsdf, v->wo_local, wl);
  if (v->kind == SS_VERTEX_REFLECTION) {
    *pdf = reflection_density(v->bsdf, v->wo_local, wl, *pdf);
  }
  return ss_rgb_scale(ss_rgb_from_vec3(ss_bsdf_eval(v->bsdf, v->wo_local, wl)),
                      fabs(wl.z) * v->scale);
}

static int sample_cosine(const ss_vertex *v, ss_rng *rng, ss_vec3 *wi, ss_rgb *weight,
                         double *pdf) {
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_vec3 wl = ss_sample_cosine_hemisphere(u1, u2);
  *wi = ss_frame_to_world(v->frame, wl);
  ss_rgb f = ss_vertex_f(v, *wi, pdf);
  if (!(*pdf > 0.0)) {
    return 0;
  }
  *weight = ss_rgb_scale(f, 1.0 / *pdf);
  return !ss_rgb_is_black(*weight);
}

/* Samples the BSDF with the uniforms given (uc picks the lobe). */
static int sample_lobe(const ss_bsdf *bsdf, ss_frame frame, ss_vec3 wo_local, ss_vec3 d, ss_vec3 ng,
                       double uc, double u1, double u2, ss_bsdf_sample *bs, ss_vec3 *wi) {
  if (!ss_bsdf_sample_dir(bsdf, wo_local, uc, u1, u2, bs) || !(bs->pdf > 0.0)) {
    return 0;
  }
  *wi = ss_frame_to_world(frame, bs->wi);
  int same_side = (ss_vec3_dot(*wi, ng) > 0.0) == (ss_vec3_dot(d, ng) < 0.0);
  return same_side == ((bs->lobe & SS_BSDF_REFLECTION) != 0);
}

int ss_sample_surface(const ss_bsdf *bsdf, ss_frame frame, ss_vec3 wo_local, ss_vec3 d, ss_vec3 ng,
                      ss_rng *rng, ss_bsdf_sample *bs, ss_vec3 *wi) {
  double uc = ss_rng_uniform(rng), u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  return sample_lobe(bsdf, frame, wo_local, d, ng, uc, u1, u2, bs, wi);
}

int ss_vertex_sample(const ss_vertex *v, ss_rng *rng, ss_vec3 *wi, ss_rgb *weight, double *pdf,
                     int *delta, double *eta) {
  *delta = 0;
  *eta = 1.0;
  if (v->kind == SS_VERTEX_ENTRY || v->kind == SS_VERTEX_SOURCE || v->kind == SS_VERTEX_BRDF) {
    return sample_cosine(v, rng, wi, weight, pdf);
  }
  double uc = ss_rng_uniform(rng), u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  /* The reflection kind forces the reflection lobe (the sampler picks it
   * for uc < Fr). */
  int reflection = v->kind == SS_VERTEX_REFLECTION;
  ss_bsdf_sample bs;
  if (!sample_lobe(v->bsdf, v->frame, v->wo_local, v->d, v->ng, reflection ? 0.0 : uc, u1, u2, &bs,
                   wi) ||
      (reflection && !(bs.lobe & SS_BSDF_REFLECTION))) {
    return 0;
  }
  *pdf = reflection ? reflection_density(v->bsdf, v->wo_local, bs.wi, bs.pdf) : bs.pdf;
  *delta = (bs.lobe & SS_BSDF_DELTA) != 0;
  if (bs.lobe & SS_BSDF_TRANSMISSION) {
    *eta = bs.eta;
  }
  if (!(*pdf > 0.0)) {
    return 0;
  }
  *weight = ss_rgb_scale(ss_rgb_from_vec3(bs.f), fabs(bs.wi.z) * v->scale / *pdf);
  return !ss_rgb_is_black(*weight);
}

ss_rgb ss_vertex_direct(const ss_scene *scene, const ss_vertex *v, ss_rng *rng,
                        ss_path_stats *stats) {
  double pmf;
  ss_light_sample ls;
  if (!ss_sample_light(scene, v->p, rng, &ls, &pmf)) {
    return ss_rgb_gray(0.0);
  }
  double p_dir;
  ss_rgb f = ss_vertex_f(v, ls.wi, &p_dir);
  if (ss_rgb_is_black(f) || ss_rgb_is_black(ls.li)) {
    return ss_rgb_gray(0.0);
  }
  int in_medium = v->kind == SS_VERTEX_PHASE;
  ss_rgb tr = ss_shadow_transmittance(scene, v->p, v->ng, in_medium ? v->medium : -1, &ls,
                                      in_medium, stats);
  if (ss_rgb_is_black(tr)) {
    return tr;
  }
  double p_light = ls.pdf * pmf;
  double w = ls.delta ? 1.0 : ss_power_heuristic(p_light, p_dir);
  return ss_rgb_scale(ss_rgb_mul(ss_rgb_mul(f, tr), ls.li), w / p_light);
}

void ss_vertex_at_bsdf(ss_vertex *v, const ss_material *m, const ss_hit *hit, ss_vec3 d) {
  memset(v, 0, sizeof *v);
  v->kind = SS_VERTEX_BSDF;
  v->p = hit->p;
  v->ng = hit->ng;
  v->frame = ss_hit_frame(m, hit);
  v->bsdf = ss_material_bsdf_at(m, ss_hit_texcoord(hit), &v->local);
  v->d = d;
  v->wo_local = ss_frame_to_local(v->frame, ss_vec3_neg(d));
  v->scale = 1.0;
}

static int is_delta(const ss_vertex *v) {
  return (v->kind == SS_VERTEX_BSDF || v->kind == SS_VERTEX_REFLECTION) &&
         (v->bsdf->lobes & SS_BSDF_DELTA);
}

int ss_path_advance(const ss_scene *scene, ss_path_state *s, ss_vertex *v, int depth, ss_ray *ray,
                    ss_rgb *L, ss_rng *rng, ss_path_stats *stats) {
  if (!is_delta(v) && !v->lit) {
    *L = ss_rgb_add(*L, ss_rgb_mul(s->beta, ss_vertex_direct(scene, v, rng, stats)));
  }
  ss_vec3 wi;
  ss_rgb weight;
  double eta;
  int sampled = ss_vertex_sample(v, rng, &wi, &weight, &s->prev_pdf, &s->specular, &eta);
  ss_vertex_release(v);
  if (!sampled) {
    return 0;
  }
  s->beta = ss_rgb_mul(s->beta, weight);
  s->prev_p = v->p;
  ss_path_refract(&s->eta_scale, eta);
  *ray = ss_ray_spawn(v->p, v->ng, wi);
  stats->extension_rays++;
  return ss_path_survives(&s->beta, ss_rgb_max(s->beta) * s->eta_scale, depth,
                          scene->integrator.rr_depth, rng);
}
