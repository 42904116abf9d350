/* The irradiance at the points of pass 1 (irradiance_points.h). */
#include "subsurf/irradiance_points.h"

#include "render/integrators/common.h"
#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <omp.h>
#include <string.h>

double ss_irradiance_fresnel_weight(double cos_theta, double eta) {
  return eta == 1.0 ? 1.0 : 1.0 - ss_fresnel_dielectric(cos_theta, eta);
}

/* Light sampled from the point: Ft cos L / p_light, MIS-weighted against the
 * cosine sampling of the continuation (Veach 1997, eq. 9.13) when `mis`. */
static ss_rgb direct(const ss_scene *scene, const ss_irradiance_point *pt, double eta, int mis,
                     ss_rng *rng, ss_path_stats *stats) {
  double pmf;
  int li = ss_pick_light(scene, ss_rng_uniform(rng), &pmf);
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_light_sample ls;
  if (li < 0 || !ss_light_sample_li(&scene->lights[li], pt->p, u1, u2, &ls) ||
      ss_rgb_is_black(ls.li)) {
    return ss_rgb_gray(0.0);
  }
  double cos_l = ss_vec3_dot(ls.wi, pt->n);
  if (!(cos_l > 0.0)) {
    return ss_rgb_gray(0.0);
  }
  ss_rgb tr = ss_shadow_transmittance(scene, pt->p, pt->n, -1, &ls, 0, stats);
  double p_light = ls.pdf * pmf;
  double w = ls.delta || !mis ? 1.0 : ss_power_heuristic(p_light, ss_pdf_cosine_hemisphere(cos_l));
  double f = ss_irradiance_fresnel_weight(cos_l, eta) * cos_l;
  return ss_rgb_scale(ss_rgb_mul(tr, ls.li), f * w / p_light);
}

/* The radiance arriving along a cosine-sampled direction, Ft cos L / pdf:
 * the `bssrdf` integrator's estimate of the ray, with the emission it finds
 * at the first hit (counted in full, as for a camera ray) MIS-weighted
 * against light sampling instead. */
static ss_rgb indirect(const ss_scene *scene, const ss_integrator_ops *li_ops,
                       const ss_irradiance_point *pt, double eta, ss_rng *rng,
                       ss_path_stats *stats) {
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_vec3 wl = ss_sample_cosine_hemisphere(u1, u2);
  if (!(wl.z > 0.0)) {
    return ss_rgb_gray(0.0);
  }
  ss_vec3 w = ss_frame_to_world(ss_frame_from_normal(pt->n), wl);
  ss_ray ray = ss_ray_spawn(pt->p, pt->n, w);
  ss_hit hit;
  int found = ss_accel_intersect(scene->accel, &ray, &hit);
  stats->extension_rays++;
  ss_rgb le = ss_rgb_gray(0.0);
  double p_light = 0.0;
  if (!found && scene->environment >= 0) {
    const ss_light *env = &scene->lights[scene->environment];
    le = env->value;
    p_light = ss_light_pdf_li(env, pt->p, w, NULL);
  } else if (found) {
    le = ss_hit_emission(scene, &hit, w);
    if (!ss_rgb_is_black(le)) {
      const ss_light *l = &scene->lights[scene->shapes[hit.geom_id].light];
      p_light = ss_light_pdf_li(l, pt->p, w, &hit);
    }
  }
  double pdf = ss_pdf_cosine_hemisphere(wl.z);
  double w_mis = ss_power_heuristic(pdf, p_light * ss_light_pmf(scene));
  ss_rgb L = li_ops->li(scene, NULL, ray, rng, stats);
  L = ss_rgb_sub(L, ss_rgb_scale(le, 1.0 - w_mis));
  return ss_rgb_scale(L, ss_irradiance_fresnel_weight(wl.z, eta) * wl.z / pdf);
}

/* Both estimates (with_indirect) or the direct one alone. */
static void compute(const ss_scene *scene, ss_irradiance_point *points, size_t n,
                    const double *eta_of_shape, int samples, uint64_t seed, int threads,
                    int with_indirect, ss_path_stats *stats) {
  const ss_integrator_ops *li_ops = ss_integrator_find("bssrdf");
  ss_path_stats total;
  memset(&total, 0, sizeof total);
  int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel num_threads(nt)
  {
    ss_path_stats local;
    memset(&local, 0, sizeof local);
#pragma omp for schedule(dynamic, 16)
    for (size_t i = 0; i < n; ++i) {
      ss_irradiance_point *pt = &points[i];
      double eta = eta_of_shape[pt->shape];
      ss_rng rng;
      ss_rng_seed_item(&rng, seed, i);
      ss_rgb sum = ss_rgb_gray(0.0);
      for (int s = 0; s < samples; ++s) {
        ss_rgb e = direct(scene, pt, eta, with_indirect, &rng, &local);
        if (with_indirect) {
          e = ss_rgb_add(e, indirect(scene, li_ops, pt, eta, &rng, &local));
        }
        if (ss_rgb_is_finite(e)) { /* a NaN/Inf sample is dropped, as the film does */
          sum = ss_rgb_add(sum, e);
        }
      }
      pt->E = ss_rgb_scale(sum, 1.0 / samples);
      pt->power = ss_rgb_scale(pt->E, pt->area);
      local.paths++;
    }
#pragma omp critical(ss_irradiance_stats)
    ss_path_stats_add(&total, &local);
  }
  if (stats) {
    *stats = total;
  }
}

void ss_irradiance_points_compute(const ss_scene *scene, ss_irradiance_point *points, size_t n,
                                  const double *eta_of_shape, int samples, uint64_t seed,
                                  int threads, ss_path_stats *stats) {
  compute(scene, points, n, eta_of_shape, samples, seed, threads, 1, stats);
}

void ss_irradiance_points_direct(const ss_scene *scene, ss_irradiance_point *points, size_t n,
                                 const double *eta_of_shape, int samples, uint64_t seed,
                                 int threads, ss_path_stats *stats) {
  compute(scene, points, n, eta_of_shape, samples, seed, threads, 0, stats);
}
