/* The state a path of the surface integrators carries from vertex to vertex
 * (path.c, bssrdf_pt.c, diffusion_path.c; volpath.c's walk adds its
 * channel ratios, spectral_mis.h). Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_PATH_STATE_H
#define SUBSURF_RENDER_INTEGRATORS_PATH_STATE_H

#include "subsurf/integrator.h"

typedef struct {
  ss_rgb beta;      /* throughput: f |cos| / pdf of every vertex so far */
  int specular;     /* no light was sampled for the last direction (the camera, a delta
                       lobe, a medium vertex without light samples): emission found next
                       takes no MIS weight */
  double prev_pdf;  /* the solid-angle density of the last direction */
  ss_vec3 prev_p;   /* the last vertex, origin of the light-pdf queries of MIS */
  double eta_scale; /* the radiance scaling of the refractions so far, undone by roulette */
} ss_path_state;

/* A camera path starting at `origin`. */
static inline ss_path_state ss_path_start(ss_vec3 origin) {
  ss_path_state s = {ss_rgb_gray(1.0), 1, 0.0, origin, 1.0};
  return s;
}

/* Veach1997 sec. 5.2: a refraction from n(wo side) into n(wi side) scales
 * radiance by eta^2 = (n(wi side) / n(wo side))^2, a factor the BSDF's
 * sample includes as 1 / eta^2 (bsdf.h); eta_scale collects eta^2 so that
 * roulette can act on the throughput without it (pbrt-v4's etaScale), and
 * paths inside dense dielectrics survive. eta: the sample's n(wi side) /
 * n(wo side) for a transmission, 1 for a reflection (ss_bsdf_sample). */
static inline void ss_path_refract(double *eta_scale, double eta) { *eta_scale *= eta * eta; }

#endif
