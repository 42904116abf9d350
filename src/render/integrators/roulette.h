/* Russian roulette, shared by the path integrators (Veach1997 sec. 2.5;
 * the throughput test of pbrt-v4). Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_ROULETTE_H
#define SUBSURF_RENDER_INTEGRATORS_ROULETTE_H

#include "subsurf/integrator.h"

/* Past rr_depth a path whose throughput weight rr is below 1 survives with
 * probability rr. Returns the factor that keeps the survivor's throughput
 * unbiased (1 when no roulette was played), or 0 when the path ends. */
static inline double ss_roulette(double rr, int depth, int rr_depth, ss_rng *rng) {
  if (depth > rr_depth && rr < 1.0) {
    double q = 1.0 - rr;
    return ss_rng_uniform(rng) < q ? 0.0 : 1.0 / (1.0 - q);
  }
  return 1.0;
}

/* Roulette on the weight rr (the caller's measure of beta: its largest
 * channel, refraction's radiance scaling undone, channel ratios collapsed)
 * with the survivor's beta scaled. Returns 0 when the path ends: roulette
 * ended it, or beta is black or not finite. */
static inline int ss_path_survives(ss_rgb *beta, double rr, int depth, int rr_depth, ss_rng *rng) {
  double survival = ss_roulette(rr, depth, rr_depth, rng);
  if (survival == 0.0 || !ss_rgb_is_finite(*beta)) {
    return 0;
  }
  *beta = ss_rgb_scale(*beta, survival);
  return !ss_rgb_is_black(*beta) && ss_rgb_is_finite(*beta);
}

#endif
