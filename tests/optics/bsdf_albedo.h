/* The Monte Carlo directional albedo of a BSDF, shared by the energy
 * compensation tests. */
#ifndef SUBSURF_TESTS_OPTICS_BSDF_ALBEDO_H
#define SUBSURF_TESTS_OPTICS_BSDF_ALBEDO_H

#include "subsurf/bsdf.h"
#include "subsurf/rng.h"
#include "subsurf/stats.h"

#include <math.h>

/* Albedo of wo in channel c (0..2): the mean of the n sample weights
 * f |cos| / pdf, with independent random numbers. */
static inline void albedo_dir(const ss_bsdf *b, ss_vec3 wo, int c, int n, uint64_t seed,
                              ss_running_stats *st) {
  ss_rng rng;
  ss_rng_seed(&rng, seed, 5);
  ss_running_stats_init(st);
  for (int i = 0; i < n; ++i) {
    double uc = ss_rng_uniform(&rng), u1 = ss_rng_uniform(&rng), u2 = ss_rng_uniform(&rng);
    ss_bsdf_sample s;
    double w = 0.0;
    if (ss_bsdf_sample_dir(b, wo, uc, u1, u2, &s)) {
      const double f[3] = {s.f.x, s.f.y, s.f.z};
      w = f[c] * fabs(s.wi.z) / s.pdf;
    }
    ss_running_stats_add(st, w);
  }
}

/* Albedo of wo (cosine mu, sign of the side, azimuth 0) in the first channel. */
static inline void albedo(const ss_bsdf *b, double mu, double sign, int n, uint64_t seed,
                          ss_running_stats *st) {
  albedo_dir(b, ss_vec3_make(sqrt(1.0 - mu * mu), 0.0, sign * mu), 0, n, seed, st);
}

#endif
