/* The path tracer of the diffusion-term integrators (diffusion_path.h),
 * moved here from hierarchical.c unchanged. */
#include "render/integrators/diffusion_path.h"
#include "render/integrators/bssrdf_vertex.h"

#include <string.h>

/* Emission found by the path, MIS-weighted against light sampling at the
 * previous vertex (weight 1 after a delta lobe or the camera). */
static ss_rgb emitted(const ss_scene *scene, const ss_hit *hit, ss_vec3 d, ss_vec3 prev_p,
                      double prev_pdf, int specular) {
  const ss_light *l;
  ss_rgb le;
  if (!hit) {
    if (scene->environment < 0) {
      return ss_rgb_gray(0.0);
    }
    l = &scene->lights[scene->environment];
    le = l->value;
  } else {
    le = ss_hit_emission(scene, hit, d);
    if (ss_rgb_is_black(le)) {
      return le;
    }
    l = &scene->lights[scene->shapes[hit->geom_id].light];
  }
  double p_light = ss_light_pdf_li(l, prev_p, d, hit) * ss_light_pmf(scene);
  return ss_rgb_scale(le, specular ? 1.0 : ss_power_heuristic(prev_pdf, p_light));
}

static int is_translucent(const ss_material *m) {
  return m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0;
}

/* The vertex at a surface hit: a translucent one (diffusion and single
 * scattering added to *L, the reflection lobe continues) or any other BSDF. */
static int surface_vertex(const ss_scene *scene, ss_diffusion_term_fn term, const void *ctx,
                          const ss_material *m, const ss_hit *hit, ss_vec3 d, ss_rgb beta,
                          ss_rng *rng, ss_rgb *L, ss_vertex *v, ss_path_stats *stats) {
  memset(v, 0, sizeof *v);
  v->p = hit->p;
  v->ng = hit->ng;
  v->d = d;
  v->bsdf = &m->bsdf;
  v->scale = 1.0;
  v->kind = SS_VERTEX_BSDF;
  v->frame = ss_hit_frame(m, hit);
  if (is_translucent(m)) {
    if (!(ss_vec3_dot(d, hit->ng) < 0.0)) {
      return 0;
    }
    ss_rgb t = term(ctx, hit, d, stats);
    if (m->bssrdf_single) {
      t = ss_rgb_add(t, ss_single_scatter(scene, m, hit, d, rng, stats));
    }
    *L = ss_rgb_add(*L, ss_rgb_mul(beta, t));
    if (ss_material_is_null(m)) {
      return 0;
    }
    v->kind = SS_VERTEX_REFLECTION;
    v->frame = ss_frame_from_normal(hit->ng);
  }
  v->wo_local = ss_frame_to_local(v->frame, ss_vec3_neg(d));
  return 1;
}

ss_rgb ss_diffusion_path_li(const ss_scene *scene, ss_diffusion_term_fn term, const void *ctx,
                            ss_ray ray, ss_rng *rng, ss_path_stats *stats) {
  ss_rgb L = ss_rgb_gray(0.0), beta = ss_rgb_gray(1.0);
  int specular = 1, depth = 0, crossings = 0;
  double prev_pdf = 0.0, eta_scale = 1.0;
  ss_vec3 prev_p = ray.o;
  const int max_depth = scene->integrator.max_depth, rr_depth = scene->integrator.rr_depth;
  for (;;) {
    ss_hit hit;
    ss_vec3 d = ss_vec3_normalize(ray.d);
    int found = ss_accel_intersect(scene->accel, &ray, &hit);
    L = ss_rgb_add(
        L, ss_rgb_mul(beta, emitted(scene, found ? &hit : NULL, d, prev_p, prev_pdf, specular)));
    const ss_material *m = found ? ss_scene_hit_material(scene, &hit) : NULL;
    if (!m) {
      break;
    }
    if (ss_material_is_null(m) && !is_translucent(m)) {
      if (!ss_cross_null_interface(&hit, &ray, &crossings, stats)) {
        break;
      }
      continue;
    }
    ss_vertex v;
    if (depth++ >= max_depth ||
        !surface_vertex(scene, term, ctx, m, &hit, d, beta, rng, &L, &v, stats)) {
      break;
    }
    int delta = (v.bsdf->lobes & SS_BSDF_DELTA) != 0;
    if (!delta) {
      L = ss_rgb_add(L, ss_rgb_mul(beta, ss_vertex_direct(scene, &v, rng, stats)));
    }
    ss_vec3 wi;
    ss_rgb weight;
    if (!ss_vertex_sample(&v, rng, &wi, &weight, &prev_pdf, &specular)) {
      break;
    }
    beta = ss_rgb_mul(beta, weight);
    prev_p = v.p;
    if (ss_vec3_dot(wi, v.ng) * ss_vec3_dot(d, v.ng) > 0.0) {
      /* a transmission: undo the radiance scaling n(wi side)^2 / n(wo side)^2 */
      double e2 = v.bsdf->eta * v.bsdf->eta;
      eta_scale *= ss_vec3_dot(wi, v.ng) < 0.0 ? e2 : 1.0 / e2;
    }
    ray = ss_ray_spawn(v.p, v.ng, wi);
    stats->extension_rays++;
    /* Russian roulette on the throughput without refraction's radiance scaling */
    double survival = ss_roulette(ss_rgb_max(beta) * eta_scale, depth, rr_depth, rng);
    if (survival == 0.0 || !ss_rgb_is_finite(beta)) {
      break;
    }
    beta = ss_rgb_scale(beta, survival);
    if (ss_rgb_is_black(beta)) {
      break;
    }
  }
  return L;
}
