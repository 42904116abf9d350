/* Evaluation, sampling and next-event estimation at the vertices of the
 * `bssrdf` integrator (see bssrdf_vertex.h). */
#include "render/integrators/bssrdf_vertex.h"

#include "subsurf/fresnel.h"
#include "subsurf/fwddip_entry.h"
#include "subsurf/sampling.h"

#include <math.h>

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

int ss_vertex_sample(const ss_vertex *v, ss_rng *rng, ss_vec3 *wi, ss_rgb *weight, double *pdf,
                     int *delta) {
  *delta = 0;
  if (v->kind == SS_VERTEX_ENTRY || v->kind == SS_VERTEX_SOURCE || v->kind == SS_VERTEX_BRDF) {
    return sample_cosine(v, rng, wi, weight, pdf);
  }
  double uc = ss_rng_uniform(rng), u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_bsdf_sample bs;
  if (v->kind == SS_VERTEX_REFLECTION) {
    uc = 0.0; /* forces the reflection lobe (the sampler picks it for uc < Fr) */
  }
  if (!ss_bsdf_sample_dir(v->bsdf, v->wo_local, uc, u1, u2, &bs) || !(bs.pdf > 0.0)) {
    return 0;
  }
  int reflect = (bs.lobe & SS_BSDF_REFLECTION) != 0;
  if (v->kind == SS_VERTEX_REFLECTION && !reflect) {
    return 0;
  }
  *wi = ss_frame_to_world(v->frame, bs.wi);
  int same_side = (ss_vec3_dot(*wi, v->ng) > 0.0) == (ss_vec3_dot(v->d, v->ng) < 0.0);
  if (same_side != reflect) {
    return 0;
  }
  *pdf = v->kind == SS_VERTEX_REFLECTION ? reflection_density(v->bsdf, v->wo_local, bs.wi, bs.pdf)
                                         : bs.pdf;
  *delta = (bs.lobe & SS_BSDF_DELTA) != 0;
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

/* The 5 uniforms of a probe sample (probe.h). */
static void uniforms(ss_rng *rng, double u[5]) {
  for (int k = 0; k < 5; ++k) {
    u[k] = ss_rng_uniform(rng);
  }
}

/* Moves v (an ENTRY or SOURCE vertex) to hit. */
static void entry_at(ss_vertex *v, const ss_hit *hit) {
  v->p = hit->p;
  v->ng = hit->ng;
  v->frame = ss_frame_from_normal(hit->ng);
  v->query.x_i = hit->p;
  v->query.n_i = hit->ng;
}

double ss_vertex_sample_entry(const ss_scene *scene, const ss_probe *probe, const ss_hit *surface,
                              ss_rng *rng, ss_vertex *v, ss_path_stats *stats) {
  double u[5];
  uniforms(rng, u);
  ss_probe_sample ps;
  unsigned long long queries = 0;
  int ok = ss_fwddip_entry_sample(probe, u, &ps, &queries);
  stats->probe_rays += queries;
  if (!ok) {
    return 0.0;
  }
  v->kind = SS_VERTEX_ENTRY;
  entry_at(v, &ps.hit);
  v->query.thickness =
      ss_bssrdf_uses_thickness(probe->bssrdf) ? ss_local_thickness(scene, surface, stats) : 0.0;
  return ps.pdf;
}

int ss_vertex_sample_entries(const ss_scene *scene, const ss_probe *probe, const ss_hit *surface,
                             ss_rgb beta, ss_rng *rng, ss_vertex *v, ss_rgb *L,
                             ss_path_stats *stats) {
  double u[5];
  uniforms(rng, u);
  ss_probe_hits ph;
  unsigned long long queries = 0;
  size_t n = ss_probe_sample_hits(probe, u, &ph, &queries);
  stats->probe_rays += queries;
  if (n == 0) {
    return 0;
  }
  v->query.thickness =
      ss_bssrdf_uses_thickness(probe->bssrdf) ? ss_local_thickness(scene, surface, stats) : 0.0;
  double scale = v->scale;
  for (size_t j = 0; j < n; ++j) {
    entry_at(v, &ph.hit[j]);
    v->scale = scale / ph.pdf[j];
    *L = ss_rgb_add(*L, ss_rgb_mul(beta, ss_vertex_direct(scene, v, rng, stats)));
  }
  size_t j = (size_t)(ss_rng_uniform(rng) * (double)n);
  j = j < n ? j : n - 1;
  entry_at(v, &ph.hit[j]);
  v->scale = scale * (double)n / ph.pdf[j];
  v->lit = 1;
  return 1;
}
