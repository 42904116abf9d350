/* Single scattering below a translucent surface whose medium is a grid or
 * micro-flakes (single_scatter.h): Jensen2001's estimate
 * (sec. 2.2-2.4) with the first event and the transmittances tracked as
 * volpath tracks them (volume.h), so that with an index-matched boundary it
 * is volpath's next-event estimate at the paths' first scattering event.
 *
 * For a camera path refracted into the medium along w_t, with its first
 * event at x (hero channel h, volpath's weights beta and r_u after the
 * tracking: beta = sigma_s(x, w_t) T / p_h for the real event, r_u the
 * channels' density ratios, null collisions included), and a light sample
 * entering at xi whose refracted segment of length s_in reaches x along
 * d_in (ss_single_scatter_light), channel k's estimate is volpath's
 * one-sample spectral MIS over the channels' distance sampling with light
 * sampling as the only technique at x (nothing continues from it):
 *   L_k = beta_k f_p(x; w_t -> -d_in) entry T_k(x -> xi) T_k(xi -> light) Li_k
 *         Ft(cos_o) / (eta^2 pmf p_light mean_i(r_u[i] a_l[i])),
 * a_l the light technique's ratio of ratio tracking (volume.h). */
#include "render/integrators/single_scatter.h"

#include "subsurf/fresnel.h"
#include "subsurf/volume.h"

#include <math.h>

ss_rgb ss_volume_single_scatter(const ss_scene *scene, const ss_material *m, const ss_hit *hit,
                                ss_vec3 d, ss_rng *rng, ss_path_stats *stats) {
  const ss_medium *med = &scene->media[m->medium];
  double eta = ss_single_scatter_eta(m);
  ss_vec3 w_o = ss_vec3_neg(ss_vec3_normalize(d)), w_t;
  double cos_o = ss_vec3_dot(w_o, hit->ng);
  const ss_rgb zero = ss_rgb_gray(0.0);
  if (!(cos_o > 0.0) || !ss_single_scatter_refract_in(w_o, hit->ng, eta, &w_t)) {
    return zero;
  }
  ss_vec3 origin = ss_offset_ray_origin(hit->p, hit->ng, w_t);
  ss_hit far;
  if (!ss_single_scatter_exit(scene, hit->geom_id, origin, w_t, &far, stats)) {
    return zero;
  }
  /* The first event: the hero chosen uniformly (volpath's choice for gray
   * media; any choice without a zero is unbiased), its free flight by delta
   * tracking up to the far side (volume.h). */
  int hero = ss_volume_uniform_hero(ss_rng_uniform(rng));
  ss_rgb beta = ss_rgb_gray(1.0), r_u = beta, r_l = beta;
  ss_volume_weights w = {&beta, &r_u, &r_l};
  double t_pre = ss_volume_sample_distance(med, w_t, hero, rng), t;
  if (ss_volume_segment(med, origin, w_t, t_pre, far.t, hero, rng, w, &t, NULL) <= 0) {
    return zero;
  }
  stats->scatter_events++;
  ss_vec3 x = ss_vec3_madd(origin, w_t, t);
  ss_single_scatter_light l;
  if (!ss_single_scatter_light_sample(scene, hit->geom_id, x, eta, rng, &l, stats)) {
    return zero;
  }
  ss_volume_point q = ss_volume_at(med, x);
  ss_vec3 to_light = ss_vec3_neg(l.d_in);
  double ph = ss_volume_phase_eval(med, &q, w_t, to_light);
  ss_rgb a_l = ss_rgb_gray(1.0);
  ss_rgb tr = ss_volume_transmittance(med, x, to_light, l.s_in, hero, rng, &a_l);
  if (ss_rgb_is_black(tr) || !(ph > 0.0)) {
    return zero;
  }
  ss_tracking tk = {hero, rng, &a_l};
  tr = ss_rgb_mul(
      tr, ss_shadow_transmittance_tracked(scene, l.xi.p, l.xi.ng, NULL, &l.ls, 1, &tk, stats));
  if (ss_rgb_is_black(tr)) {
    return zero;
  }
  /* Ft(cos_o) / eta^2 on leaving, as ss_single_scatter (docs/models.md). */
  double k = l.entry * ph * (1.0 - ss_fresnel_dielectric(cos_o, eta)) / (eta * eta) /
             (l.pmf * l.ls.pdf * ss_rgb_average(ss_rgb_mul(r_u, a_l)));
  return ss_rgb_scale(ss_rgb_mul(ss_rgb_mul(beta, tr), l.ls.li), k);
}
