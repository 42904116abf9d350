/* The irradiance at the points of pass 1 (irradiance_points.h). */
#include "subsurf/irradiance_points.h"

#include "render/integrators/bssrdf_path.h"
#include "render/integrators/emission.h"
#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"
#include "subsurf/threads.h"

#include <math.h>
#include <string.h>

double ss_irradiance_fresnel_weight(double cos_theta, double eta) {
  return eta == 1.0 ? 1.0 : 1.0 - ss_fresnel_dielectric(cos_theta, eta);
}

/* The direction into the object of light arriving from w (pointing away
 * from the surface): -n where it is not transmitted (its weight Ft is 0). */
static ss_vec3 refracted(ss_vec3 w, ss_vec3 n, double eta) {
  ss_vec3 w_t;
  return ss_refract(w, n, eta, &w_t) ? w_t : ss_vec3_neg(n);
}

/* Light sampled from the point: Ft cos L / p_light, MIS-weighted against the
 * cosine sampling of the continuation (Veach 1997, eq. 9.13) when `mis`;
 * *w_t its refracted direction. */
static ss_rgb direct(const ss_scene *scene, const ss_irradiance_point *pt, double eta, int mis,
                     ss_rng *rng, ss_vec3 *w_t, ss_path_stats *stats) {
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
  *w_t = refracted(ls.wi, pt->n, eta);
  ss_rgb tr = ss_shadow_transmittance(scene, pt->p, pt->n, -1, &ls, 0, stats);
  double p_light = ls.pdf * pmf;
  double w = ls.delta || !mis ? 1.0 : ss_power_heuristic(p_light, ss_pdf_cosine_hemisphere(cos_l));
  double f = ss_irradiance_fresnel_weight(cos_l, eta) * cos_l;
  return ss_rgb_scale(ss_rgb_mul(tr, ls.li), f * w / p_light);
}

/* The radiance arriving along a cosine-sampled direction, Ft cos L / pdf:
 * the `bssrdf` integrator's estimate of the ray, with the emission it finds
 * at the first hit (counted in full, as for a camera ray) MIS-weighted
 * against light sampling instead; *w_t its refracted direction. */
static ss_rgb indirect(const ss_scene *scene, const ss_irradiance_point *pt, double eta,
                       ss_rng *rng, ss_vec3 *w_t, ss_path_stats *stats) {
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_vec3 wl = ss_sample_cosine_hemisphere(u1, u2);
  if (!(wl.z > 0.0)) {
    return ss_rgb_gray(0.0);
  }
  ss_vec3 w = ss_frame_to_world(ss_frame_from_normal(pt->n), wl);
  *w_t = refracted(w, pt->n, eta);
  ss_ray ray = ss_ray_spawn(pt->p, pt->n, w);
  ss_hit hit;
  int found = ss_accel_intersect(scene->accel, &ray, &hit);
  stats->extension_rays++;
  double p_light = 0.0;
  ss_rgb le = ss_emission_found(scene, found ? &hit : NULL, w, pt->p, &p_light);
  double pdf = ss_pdf_cosine_hemisphere(wl.z);
  double w_mis = ss_power_heuristic(pdf, p_light);
  ss_rgb L = ss_bssrdf_path_li(scene, SS_BSSRDF_DEFAULT_ALL_HITS, ray, rng, stats);
  L = ss_rgb_sub(L, ss_rgb_scale(le, 1.0 - w_mis));
  return ss_rgb_scale(L, ss_irradiance_fresnel_weight(wl.z, eta) * wl.z / pdf);
}

/* Adds e w_t per channel to the flux vector. */
static void add_flux(ss_irradiance_flux *f, ss_rgb e, ss_vec3 w_t) {
  for (int c = 0; c < 3; ++c) {
    f->c[c] = ss_vec3_madd(f->c[c], w_t, e.c[c]);
  }
}

/* Both estimates (with_indirect) or the direct one alone; the flux vectors
 * when `flux` is not NULL, from the same samples. */
static void compute(const ss_scene *scene, ss_irradiance_point *points, size_t n,
                    const double *eta_of_shape, int samples, uint64_t seed, int threads,
                    int with_indirect, ss_irradiance_flux *flux, ss_path_stats *stats) {
  ss_path_stats total;
  memset(&total, 0, sizeof total);
  int nt = ss_threads_team(threads);
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
      ss_irradiance_flux f;
      memset(&f, 0, sizeof f);
      for (int s = 0; s < samples; ++s) {
        ss_vec3 wd = ss_vec3_neg(pt->n), wi = wd;
        ss_rgb ed = direct(scene, pt, eta, with_indirect, &rng, &wd, &local), e = ed;
        ss_rgb ei = ss_rgb_gray(0.0);
        if (with_indirect) {
          ei = indirect(scene, pt, eta, &rng, &wi, &local);
          e = ss_rgb_add(e, ei);
        }
        if (ss_rgb_is_finite(e)) { /* a NaN/Inf sample is dropped, as the film does */
          sum = ss_rgb_add(sum, e);
          add_flux(&f, ed, wd);
          add_flux(&f, ei, wi);
        }
      }
      pt->E = ss_rgb_scale(sum, 1.0 / samples);
      pt->power = ss_rgb_scale(pt->E, pt->area);
      if (flux) {
        for (int c = 0; c < 3; ++c) {
          flux[i].c[c] = ss_vec3_scale(f.c[c], 1.0 / samples);
        }
      }
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
                                  int threads, ss_irradiance_flux *flux, ss_path_stats *stats) {
  compute(scene, points, n, eta_of_shape, samples, seed, threads, 1, flux, stats);
}

void ss_irradiance_points_direct(const ss_scene *scene, ss_irradiance_point *points, size_t n,
                                 const double *eta_of_shape, int samples, uint64_t seed,
                                 int threads, ss_irradiance_flux *flux, ss_path_stats *stats) {
  compute(scene, points, n, eta_of_shape, samples, seed, threads, 0, flux, stats);
}
