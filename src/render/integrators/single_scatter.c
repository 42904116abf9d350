/* Single scattering below a translucent surface, the way Jensen et al. 2001
 * (sec. 2.2-2.4) estimate it; see bssrdf_vertex.h. The geometry of the
 * estimate (single_scatter.h) is shared with the tracked variant for grids
 * and micro-flakes (volume_single_scatter.c). */
#include "render/integrators/single_scatter.h"
#include "render/integrators/bssrdf_vertex.h"

#include "subsurf/fresnel.h"
#include "subsurf/volume.h"

#include <math.h>

int ss_single_scatter_refract_in(ss_vec3 w, ss_vec3 n, double eta, ss_vec3 *w_t) {
  if (eta == 1.0) {
    *w_t = ss_vec3_neg(w);
    return 1;
  }
  return ss_refract(w, n, eta, w_t);
}

int ss_single_scatter_exit(const ss_scene *scene, unsigned geom_id, ss_vec3 x, ss_vec3 wi,
                           ss_hit *hit, ss_path_stats *stats) {
  ss_ray ray = {x, wi, 0.0, INFINITY};
  stats->shadow_rays++;
  return ss_accel_intersect(scene->accel, &ray, hit) && hit->geom_id == geom_id &&
         ss_vec3_dot(wi, hit->ng) > 0.0;
}

/* Jensen et al. 2001, eq. 4-6 (single_scatter.h): the refracted distance
 * and direction from xi to x and Ft(cos_i) cos_i / cos_i'. */
static double entry_factor(ss_vec3 wi, const ss_hit *xi, ss_vec3 x, double eta, double *s_in,
                           ss_vec3 *d_in) {
  double cos_i = ss_vec3_dot(wi, xi->ng);
  ss_vec3 w_t;
  if (!(cos_i > 0.0) || !ss_single_scatter_refract_in(wi, xi->ng, eta, &w_t)) {
    return 0.0;
  }
  double cos_t = -ss_vec3_dot(w_t, xi->ng);
  double depth = ss_vec3_dot(ss_vec3_sub(xi->p, x), xi->ng);
  if (!(cos_t > 0.0) || !(depth > 0.0)) {
    return 0.0;
  }
  *s_in = depth / cos_t;
  *d_in = w_t;
  return (1.0 - ss_fresnel_dielectric(cos_i, eta)) * cos_i / cos_t;
}

int ss_single_scatter_light_sample(const ss_scene *scene, unsigned geom_id, ss_vec3 x, double eta,
                                   ss_rng *rng, ss_single_scatter_light *l, ss_path_stats *stats) {
  if (!ss_sample_light(scene, x, rng, &l->ls, &l->pmf) ||
      !ss_single_scatter_exit(scene, geom_id, x, l->ls.wi, &l->xi, stats) ||
      (isfinite(l->ls.dist) && l->xi.t >= l->ls.dist)) {
    return 0;
  }
  l->entry = entry_factor(l->ls.wi, &l->xi, x, eta, &l->s_in, &l->d_in);
  return l->entry > 0.0;
}

ss_rgb ss_single_scatter(const ss_scene *scene, const ss_material *m, const ss_hit *hit, ss_vec3 d,
                         ss_rng *rng, ss_path_stats *stats) {
  const ss_medium *med = &scene->media[m->medium];
  if (ss_medium_is_volume(med)) {
    return ss_volume_single_scatter(scene, m, hit, d, rng, stats);
  }
  double eta = ss_single_scatter_eta(m);
  ss_vec3 w_o = ss_vec3_neg(ss_vec3_normalize(d)), w_t;
  double cos_o = ss_vec3_dot(w_o, hit->ng);
  ss_rgb zero = ss_rgb_gray(0.0);
  if (!(cos_o > 0.0) || !ss_single_scatter_refract_in(w_o, hit->ng, eta, &w_t)) {
    return zero;
  }
  /* The scattering point: distance by one channel's extinction, one-sample
   * MIS (balance) over the channels. */
  int hero = ss_volume_uniform_hero(ss_rng_uniform(rng));
  double s = ss_sample_exponential(ss_rng_uniform(rng), med->sigma_t.c[hero]), pdf_s = 0.0;
  for (int c = 0; c < 3; ++c) {
    pdf_s += med->sigma_t.c[c] * exp(-med->sigma_t.c[c] * s) / 3.0;
  }
  ss_vec3 origin = ss_offset_ray_origin(hit->p, hit->ng, w_t);
  ss_hit far;
  if (!ss_single_scatter_exit(scene, hit->geom_id, origin, w_t, &far, stats) || s >= far.t) {
    return zero;
  }
  ss_vec3 x = ss_vec3_madd(origin, w_t, s);
  ss_single_scatter_light l;
  if (!ss_single_scatter_light_sample(scene, hit->geom_id, x, eta, rng, &l, stats)) {
    return zero;
  }
  ss_rgb tr = ss_shadow_transmittance(scene, l.xi.p, l.xi.ng, -1, &l.ls, 0, stats);
  if (ss_rgb_is_black(tr)) {
    return zero;
  }
  /* The phase function between the refracted light direction and the
   * propagation toward x_o; Ft(cos_o) / eta^2 on leaving (docs/models.md). */
  double ph = ss_phase_eval(&med->phase, ss_vec3_dot(l.d_in, ss_vec3_neg(w_t)));
  double k = l.entry * ph * (1.0 - ss_fresnel_dielectric(cos_o, eta)) / (eta * eta) /
             (pdf_s * l.pmf * l.ls.pdf);
  ss_rgb L;
  for (int c = 0; c < 3; ++c) {
    L.c[c] = k * med->optics.sigma_s.c[c] * exp(-med->sigma_t.c[c] * (s + l.s_in)) * tr.c[c] *
             l.ls.li.c[c];
  }
  return L;
}
