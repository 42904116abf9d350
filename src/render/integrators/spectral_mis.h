/* Spectral MIS over the RGB channels (Wilkie2014, "hero wavelength"; the
 * r_u / r_l bookkeeping of pbrt-v4's VolPathIntegrator): free-flight
 * distances are sampled with one hero channel's extinction and the three
 * channels combined by the one-sample balance heuristic over the channels'
 * sampling techniques. For a path x with hero h, the estimate of channel k
 * is
 *     f_k(x) / (sum_i pmf_i (p_i^uni(x) + p_i^nee(x)))
 * where p_i are the densities with which channel i's technique (distance
 * sampling with sigma_t[i]) would produce x by unidirectional sampling or by
 * next-event estimation. beta = f / p_h^uni, r_u[i] = 3 pmf_i p_i^uni /
 * p_h^uni and r_l[i] = 3 pmf_i p_i^nee / p_h^uni are tracked along the path
 * and renormalised to mean(r_u) = 1 at every vertex (the ratios are
 * invariant to that). Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_SPECTRAL_MIS_H
#define SUBSURF_RENDER_INTEGRATORS_SPECTRAL_MIS_H

#include "subsurf/integrator.h"

typedef struct {
  ss_rgb r_u, r_l;
  int hero;      /* -1 until chosen (ss_spectral_choose_hero) */
  double hero_u; /* the uniform number that chooses it */
} ss_spectral;

/* Fresh ratios, the hero to be chosen from the uniform hero_u. */
static inline ss_spectral ss_spectral_start(double hero_u) {
  ss_spectral sp = {ss_rgb_gray(1.0), ss_rgb_gray(1.0), -1, hero_u};
  return sp;
}

/* Divides beta, r_u and r_l by mean(r_u) (no change when it is 0 or not
 * finite). */
void ss_spectral_renormalise(ss_rgb *beta, ss_spectral *sp);

/* Chooses the hero, once, with the probabilities of medium `med` (NULL:
 * uniform), scaling the ratios by 3 pmf_i (spectral_mis.c). */
void ss_spectral_choose_hero(ss_spectral *sp, const ss_medium *med);

/* The hero, the uniform choice from hero_u when none was chosen yet. */
int ss_spectral_hero(const ss_spectral *sp);

/* Radiance `le` reached by unidirectional sampling with throughput beta;
 * p_light is the density light sampling would have used from the previous
 * vertex, ignored when `mis` is 0 (after a delta lobe). */
ss_rgb ss_spectral_emitted(ss_rgb beta, const ss_spectral *sp, ss_rgb le, double p_light, int mis);

#endif
