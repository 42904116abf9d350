/* Light selection, shadow-ray transmittance and index-matched crossings,
 * shared by the integrators. */
#include "render/integrators/common.h"

#include "subsurf/volume.h"

#include <math.h>

int ss_pick_light(const ss_scene *scene, double u, double *pmf) {
  if (scene->num_lights == 0) {
    *pmf = 0.0;
    return -1;
  }
  size_t i = (size_t)(u * (double)scene->num_lights);
  if (i >= scene->num_lights) {
    i = scene->num_lights - 1;
  }
  *pmf = 1.0 / (double)scene->num_lights;
  return (int)i;
}

int ss_sample_light(const ss_scene *scene, ss_vec3 p, ss_rng *rng, ss_light_sample *ls,
                    double *pmf) {
  int li = ss_pick_light(scene, ss_rng_uniform(rng), pmf);
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  return li >= 0 && ss_light_sample_li(&scene->lights[li], p, u1, u2, ls);
}

/* The attenuation over `dist` along the ray in a medium (NULL: vacuum):
 * Beer-Lambert with sigma_t along the ray, or ratio tracking in a grid. */
static ss_rgb attenuate(ss_rgb tr, const ss_medium *med, const ss_ray *ray, double dist,
                        const ss_tracking *tk) {
  if (!med) {
    return tr;
  }
  ss_vec3 d = ss_vec3_normalize(ray->d);
  return ss_rgb_mul(tr, ss_volume_transmittance(med, ray->o, d, dist, tk ? tk->hero : 0,
                                                tk ? tk->rng : NULL, tk ? tk->a_l : NULL));
}

ss_rgb ss_shadow_transmittance(const ss_scene *scene, ss_vec3 p, ss_vec3 n, int medium,
                               const ss_light_sample *ls, int with_media, ss_path_stats *stats) {
  const ss_medium *med = with_media && medium >= 0 ? &scene->media[medium] : NULL;
  return ss_shadow_transmittance_in(scene, p, n, med, ls, with_media, stats);
}

ss_rgb ss_shadow_transmittance_in(const ss_scene *scene, ss_vec3 p, ss_vec3 n, const ss_medium *med,
                                  const ss_light_sample *ls, int with_media, ss_path_stats *stats) {
  return ss_shadow_transmittance_tracked(scene, p, n, med, ls, with_media, NULL, stats);
}

ss_rgb ss_shadow_transmittance_tracked(const ss_scene *scene, ss_vec3 p, ss_vec3 n,
                                       const ss_medium *med, const ss_light_sample *ls,
                                       int with_media, const ss_tracking *tk,
                                       ss_path_stats *stats) {
  ss_rgb tr = ss_rgb_gray(1.0);
  ss_medium local;
  int finite = isfinite(ls->dist);
  ss_ray ray = finite ? ss_ray_spawn_to(p, n, ls->p, ls->n) : ss_ray_spawn(p, n, ls->wi);
  for (int crossing = 0; crossing < SS_MAX_NULL_CROSSINGS; ++crossing) {
    if (!med || !with_media) {
      /* Outside the media, or when they are ignored, only the blockers
       * matter: one occlusion query that sees through index-matched
       * boundaries settles the ray unless it entered a medium on the way. */
      int passed = 0;
      stats->shadow_rays++;
      if (ss_accel_occluded_passing(scene->accel, &ray, scene->see_through, &passed)) {
        return ss_rgb_gray(0.0);
      }
      if (!passed || !with_media) {
        return tr;
      }
    }
    ss_hit hit;
    stats->shadow_rays++;
    if (!ss_accel_intersect(scene->accel, &ray, &hit)) {
      if (with_media && med) {
        if (!finite) {
          return ss_rgb_gray(0.0); /* a leak out of a closed mesh: no light */
        }
        tr = attenuate(tr, med, &ray, ss_vec3_length(ss_vec3_sub(ls->p, ray.o)), tk);
      }
      return tr;
    }
    const ss_material *m = ss_scene_hit_material(scene, &hit);
    if (!m || !ss_material_is_null(m)) {
      return ss_rgb_gray(0.0);
    }
    if (with_media) {
      tr = attenuate(tr, med, &ray, hit.t * ss_vec3_length(ray.d), tk);
      int entering = ss_vec3_dot(ray.d, hit.ng) < 0.0 && m->medium >= 0;
      med = entering ? &scene->media[m->medium] : NULL;
      if (entering && ss_material_optics_at(m, med, ss_hit_texcoord(&hit), &local)) {
        med = &local; /* entry-point coefficients, as volpath's paths take them */
      }
    }
    ray =
        finite ? ss_ray_spawn_to(hit.p, hit.ng, ls->p, ls->n) : ss_ray_spawn(hit.p, hit.ng, ls->wi);
  }
  return ss_rgb_gray(0.0);
}

ss_status ss_refuse_nested_media(const ss_scene *scene, const char *integrator, ss_error *err) {
  if (scene->nested_material < 0) {
    return SS_OK;
  }
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "the %s integrator cannot render nested or touching media (material '%s' "
                      "touches or contains another); use volpath",
                      integrator, scene->materials[scene->nested_material].name);
}

ss_status ss_refuse_varying_media(const ss_scene *scene, const char *integrator,
                                  const char *instead, ss_error *err) {
  for (size_t i = 0; i < scene->num_materials; ++i) {
    const ss_material *m = &scene->materials[i];
    if (m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0 && ss_material_varies(m)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "%s: material '%s': a textured albedo or mfp is not supported; %s",
                          integrator, m->name, instead);
    }
  }
  return SS_OK;
}

int ss_cross_null_interface(const ss_hit *hit, ss_ray *ray, int *crossings, ss_path_stats *stats) {
  if (++*crossings > SS_MAX_NULL_CROSSINGS) {
    return 0;
  }
  *ray = ss_ray_spawn(hit->p, hit->ng, ray->d);
  stats->extension_rays++;
  return 1;
}
