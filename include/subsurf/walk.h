/* The random-walk kernel shared by the Monte Carlo references: free flights,
 * phase-function scattering, and Fresnel events at a smooth boundary. */
#ifndef SUBSURF_WALK_H
#define SUBSURF_WALK_H

#include "subsurf/fresnel.h"
#include "subsurf/phase.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

/* A free-flight distance with density sigma_t exp(-sigma_t t). 1 - u lies in
 * (0, 1] exactly, and log is several times faster than log1p in glibc. */
static inline double ss_walk_free_flight(ss_rng *rng, double sigma_t) {
  return -log(1.0 - ss_rng_uniform(rng)) / sigma_t;
}

/* New propagation direction after scattering. */
static inline ss_vec3 ss_walk_scatter(const ss_phase *phase, ss_vec3 dir, ss_rng *rng) {
  double cos_theta = ss_phase_sample_cos(phase, ss_rng_uniform(rng));
  double sin_theta = sqrt(1.0 - cos_theta * cos_theta > 0.0 ? 1.0 - cos_theta * cos_theta : 0.0);
  double cos_phi, sin_phi;
  ss_sample_uniform_azimuth(rng, &cos_phi, &sin_phi);
  ss_vec3 local = ss_vec3_make(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta);
  return ss_frame_to_world(ss_frame_from_normal(dir), local);
}

typedef enum { SS_WALK_REFLECTED, SS_WALK_TRANSMITTED } ss_walk_boundary_event;

/* Light travelling along `dir` meets a smooth dielectric whose outward normal
 * is `n` (dot(dir, n) > 0 when leaving the medium) and index ratio eta =
 * n_inside / n_outside. Chooses reflection with probability Fr, else
 * refraction (Fr = 1 under total internal reflection); updates dir. */
static inline ss_walk_boundary_event ss_walk_cross_boundary(ss_vec3 *dir, ss_vec3 n, double eta,
                                                            ss_rng *rng) {
  ss_vec3 w_i = ss_vec3_neg(*dir); /* toward where the light came from */
  double fr = ss_fresnel_dielectric(ss_vec3_dot(w_i, n), eta);
  if (fr > 0.0 && ss_rng_uniform(rng) < fr) {
    *dir = ss_reflect(w_i, n);
    return SS_WALK_REFLECTED;
  }
  ss_vec3 w_t;
  ss_refract(w_i, n, eta, &w_t);
  *dir = w_t;
  return SS_WALK_TRANSMITTED;
}

#endif
