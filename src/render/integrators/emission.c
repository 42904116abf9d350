/* Emission found by a path, MIS-weighted against light sampling (emission.h). */
#include "render/integrators/emission.h"

#include "render/integrators/common.h"

ss_rgb ss_emission_found(const ss_scene *scene, const ss_hit *hit, ss_vec3 d, ss_vec3 prev_p,
                         double *p_light) {
  if (!hit) {
    if (scene->environment < 0) {
      return ss_rgb_gray(0.0);
    }
    /* A map's radiance and density in one lookup, the same from any prev_p. */
    ss_rgb le = ss_light_environment_li(&scene->lights[scene->environment], d, p_light);
    *p_light *= ss_light_pmf(scene);
    return le;
  }
  ss_rgb le = ss_hit_emission(scene, hit, d);
  if (ss_rgb_is_black(le)) {
    return le;
  }
  const ss_light *l = &scene->lights[scene->shapes[hit->geom_id].light];
  *p_light = ss_light_pdf_li(l, prev_p, d, hit) * ss_light_pmf(scene);
  return le;
}

ss_rgb ss_path_emitted(const ss_scene *scene, const ss_path_state *s, const ss_hit *hit,
                       ss_vec3 d) {
  double p_light = 0.0;
  ss_rgb le = ss_emission_found(scene, hit, d, s->prev_p, &p_light);
  if (ss_rgb_is_black(le)) {
    return le;
  }
  /* Veach1997 eq. 9.13, the BSDF technique's weight. */
  double w = s->specular ? 1.0 : ss_power_heuristic(s->prev_pdf, p_light);
  return ss_rgb_scale(ss_rgb_mul(s->beta, le), w);
}
