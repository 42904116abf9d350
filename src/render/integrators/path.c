/* `path`: unidirectional path tracing of surfaces (media are ignored:
 * interfaces act as clear dielectrics), with next-event estimation and
 * multiple importance sampling of BSDF and light sampling by the power
 * heuristic (Veach 1997, ch. 9; pbrt-v4's PathIntegrator). */
#include "render/integrators/common.h"

#include <math.h>

/* Direct light at a surface vertex by light sampling, MIS-weighted against
 * BSDF sampling. */
static ss_rgb direct_light(const ss_scene *scene, const ss_bsdf *bsdf, ss_frame frame,
                           ss_vec3 wo_local, const ss_hit *hit, ss_rng *rng, ss_path_stats *stats) {
  double pmf;
  ss_light_sample ls;
  if (!ss_sample_light(scene, hit->p, rng, &ls, &pmf)) {
    return ss_rgb_gray(0.0);
  }
  ss_vec3 wi_local = ss_frame_to_local(frame, ls.wi);
  ss_rgb f = ss_rgb_from_vec3(ss_bsdf_eval(bsdf, wo_local, wi_local));
  f = ss_rgb_scale(f, fabs(wi_local.z));
  if (ss_rgb_is_black(f) || ss_rgb_is_black(ls.li)) {
    return ss_rgb_gray(0.0);
  }
  ss_rgb tr = ss_shadow_transmittance(scene, hit->p, hit->ng, -1, &ls, 0, stats);
  if (ss_rgb_is_black(tr)) {
    return tr;
  }
  double p_light = ls.pdf * pmf;
  double w = ls.delta ? 1.0 : ss_power_heuristic(p_light, ss_bsdf_pdf(bsdf, wo_local, wi_local));
  return ss_rgb_scale(ss_rgb_mul(f, ls.li), w / p_light);
}

static ss_rgb path_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                      ss_path_stats *stats) {
  (void)state;
  ss_rgb L = ss_rgb_gray(0.0), beta = ss_rgb_gray(1.0);
  int specular = 1, depth = 0, crossings = 0;
  double prev_pdf = 0.0, eta_scale = 1.0;
  ss_vec3 prev_p = ray.o;
  const int max_depth = scene->integrator.max_depth, rr_depth = scene->integrator.rr_depth;
  for (;;) {
    ss_hit hit;
    if (!ss_accel_intersect(scene->accel, &ray, &hit)) {
      if (scene->environment >= 0) {
        const ss_light *env = &scene->lights[scene->environment];
        double w = 1.0;
        if (!specular) {
          w = ss_power_heuristic(prev_pdf,
                                 ss_light_pdf_li(env, prev_p, ray.d, NULL) * ss_light_pmf(scene));
        }
        L = ss_rgb_add(L, ss_rgb_scale(ss_rgb_mul(beta, env->value), w));
      }
      break;
    }
    ss_rgb le = ss_hit_emission(scene, &hit, ray.d);
    if (!ss_rgb_is_black(le)) {
      double w = 1.0;
      if (!specular) {
        const ss_light *l = &scene->lights[scene->shapes[hit.geom_id].light];
        w = ss_power_heuristic(prev_pdf,
                               ss_light_pdf_li(l, prev_p, ray.d, &hit) * ss_light_pmf(scene));
      }
      L = ss_rgb_add(L, ss_rgb_scale(ss_rgb_mul(beta, le), w));
    }
    const ss_material *m = ss_scene_hit_material(scene, &hit);
    if (!m) {
      break;
    }
    if (ss_material_is_null(m)) {
      if (!ss_cross_null_interface(&hit, &ray, &crossings, stats)) {
        break;
      }
      continue;
    }
    if (depth++ >= max_depth) {
      break;
    }
    ss_frame frame = ss_hit_frame(m, &hit);
    ss_vec3 wo_local = ss_frame_to_local(frame, ss_vec3_neg(ray.d));
    ss_bsdf local;
    const ss_bsdf *bsdf = ss_material_bsdf_at(m, ss_hit_texcoord(&hit), &local);
    if (!(bsdf->lobes & SS_BSDF_DELTA)) {
      ss_rgb d = direct_light(scene, bsdf, frame, wo_local, &hit, rng, stats);
      L = ss_rgb_add(L, ss_rgb_mul(beta, d));
    }
    ss_bsdf_sample bs;
    ss_vec3 wi;
    if (!ss_sample_surface(bsdf, frame, wo_local, ray.d, &hit, rng, &bs, &wi)) {
      break;
    }
    beta = ss_rgb_mul(beta, ss_rgb_scale(ss_rgb_from_vec3(bs.f), fabs(bs.wi.z) / bs.pdf));
    specular = (bs.lobe & SS_BSDF_DELTA) != 0;
    prev_pdf = bs.pdf;
    prev_p = hit.p;
    if (bs.lobe & SS_BSDF_TRANSMISSION) {
      eta_scale *= bs.eta * bs.eta;
    }
    ray = ss_ray_spawn(hit.p, hit.ng, wi);
    stats->extension_rays++;
    /* Russian roulette on the throughput without the radiance scaling of
     * refraction (pbrt-v4), so paths inside dense dielectrics survive. */
    double survival = ss_roulette(ss_rgb_max(beta) * eta_scale, depth, rr_depth, rng);
    if (survival == 0.0) {
      break;
    }
    beta = ss_rgb_scale(beta, survival);
    if (ss_rgb_is_black(beta)) {
      break;
    }
  }
  return L;
}

static ss_status path_check(const ss_scene *scene, ss_error *err) {
  return ss_refuse_nested_media(scene, "path", err);
}

static ss_status path_prepare(const ss_scene *scene, void **state, ss_error *err) {
  *state = NULL;
  return path_check(scene, err);
}

const ss_integrator_ops ss_integrator_path = {
    .name = "path",
    .summary = "surface path tracing, BSDF and light sampling with MIS (Veach 1997)",
    .options = NULL,
    .check = path_check,
    .prepare = path_prepare,
    .release = NULL,
    .li = path_li,
};
