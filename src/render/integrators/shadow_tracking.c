/* Shadow rays from a vertex inside a homogeneous medium toward a delta light:
 * the transmittance to the medium's boundary is estimated by
 * tracking (a sampled free flight, Novak et al. 2014, "Residual Ratio
 * Tracking for Estimating Attenuation in Participating Media", sec. 3), so
 * the query stops at the sampled distance, and the boundary's hit record is
 * the distance-only one (accel.h). */
#include "render/integrators/shadow_tracking.h"

#include "subsurf/volume.h"

#include <math.h>

ss_rgb ss_shadow_transmittance_sampled(const ss_scene *scene, ss_vec3 p, const ss_medium *med,
                                       const ss_light_sample *ls, double rate,
                                       const ss_tracking *tk, ss_path_stats *stats) {
  double lambda = INFINITY;
  for (int c = 0; c < 3; ++c) {
    lambda = fmin(lambda, med->sigma_t.c[c]);
  }
  lambda *= rate;
  /* Free flight s ~ lambda exp(-lambda s): P(s > d) = exp(-lambda d). */
  double u = ss_rng_uniform(tk->rng);
  double s = lambda > 0.0 ? ss_sample_exponential(u, lambda) : INFINITY;
  int finite = isfinite(ls->dist);
  ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
  ss_ray ray = finite ? ss_ray_spawn_to(p, zero, ls->p, ls->n) : ss_ray_spawn(p, zero, ls->wi);
  double dl = ss_vec3_length(ray.d);
  int cut = s / dl < ray.tmax;
  ray.tmax = fmin(ray.tmax, s / dl);
  ss_hit hit;
  stats->shadow_rays++;
  int found = ss_accel_intersect_distance(scene->accel, &ray, &hit);
  if (!found && (cut || !finite)) {
    return ss_rgb_gray(0.0); /* absorbed by the free flight, or a leak */
  }
  /* The medium's part of the way: exp(-sigma_t d) / P(s > d) per channel. */
  double d = found ? hit.t * dl : ss_vec3_length(ss_vec3_sub(ls->p, ray.o));
  ss_rgb tr;
  for (int c = 0; c < 3; ++c) {
    tr.c[c] = exp(-(med->sigma_t.c[c] - lambda) * d);
  }
  if (!found) {
    return tr; /* the light inside the medium */
  }
  const ss_material *m = ss_scene_hit_material(scene, &hit);
  if (!m || !ss_material_is_null(m)) {
    return ss_rgb_gray(0.0);
  }
  /* Beyond the boundary: the general walk, from the medium entered if any. */
  const ss_medium *beyond = NULL;
  ss_medium local;
  if (ss_vec3_dot(ray.d, hit.ng) < 0.0 && m->medium >= 0) {
    ss_accel_hit_complete(scene->accel, &hit);
    beyond = &scene->media[m->medium];
    if (ss_material_optics_at(m, beyond, ss_hit_texcoord(&hit), &local)) {
      beyond = &local;
    }
  }
  return ss_rgb_mul(
      tr, ss_shadow_transmittance_tracked(scene, hit.p, hit.ng, beyond, ls, 1, tk, stats));
}
