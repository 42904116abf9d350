/* Guided random walks for volpath: Dwivedi sampling (Krivanek & d'Eon 2014,
 * "A zero-variance-based sampling scheme for Monte Carlo subsurface
 * scattering"; Meng et al. 2016 per colour channel). The importance of a
 * point x of a homogeneous medium lit from the direction g is approximated
 * by the asymptotic diffusion mode exp(kappa sigma_t (x . g)), kappa = 1/v0
 * the root of albedo atanh(kappa) = kappa (the discrete eigenvalue of
 * one-speed transport with isotropic scattering); sampling the product of
 * that importance with the walk's kernel gives (mu = the cosine of the
 * direction to g)
 *     direction: D(mu) = kappa / (4 pi atanh(kappa) (1 - kappa mu))
 *     distance:  sigma_t' exp(-sigma_t' t), sigma_t' = sigma_t (1 - kappa mu).
 * volpath mixes this technique with the classical one (phase function and
 * sigma_t) with probability q per scattering vertex and weighs every
 * segment by the mixture's exact density (one-sample balance heuristic),
 * per channel for its spectral MIS, so the image stays unbiased. */
#ifndef SUBSURF_RENDER_INTEGRATORS_GUIDED_WALK_H
#define SUBSURF_RENDER_INTEGRATORS_GUIDED_WALK_H

#include "subsurf/rgb.h"
#include "subsurf/scene.h"
#include "subsurf/volume.h"

/* Largest kappa used: the direction density stays within a factor
 * (1 + SS_GUIDE_MAX_KAPPA) / (1 - SS_GUIDE_MAX_KAPPA) of uniform. */
#define SS_GUIDE_MAX_KAPPA 0.99

/* kappa = 1/v0 for single-scattering albedo a: the root in [0, 1) of
 * a atanh(kappa) = kappa (0 when a >= 1), capped at SS_GUIDE_MAX_KAPPA. */
double ss_dwivedi_kappa(double albedo);

/* D(mu), the solid-angle density of Dwivedi direction sampling. */
double ss_dwivedi_pdf(double kappa, double mu);

/* The cosine mu to the guide of a direction drawn from D, from u in [0, 1). */
double ss_dwivedi_sample_mu(double kappa, double u);

/* The guide of a scene: toward its only light when that is a point, spot,
 * directional or beam light (no light sampling then weighs a path by the
 * density of its directions, so the walk may change them freely). */
typedef struct {
  double q;   /* probability of the guided technique; 0: off */
  int toward; /* 1: toward `target`, a position; 0: along it, a unit direction */
  ss_vec3 target;
  ss_rgb *kappa; /* per medium of the scene */
} ss_guide;

/* Sets up g for scene with probability q; g->q = 0 (off) when the scene has
 * no such light or q is 0. Returns SS_ERR_NO_MEMORY on failure. */
ss_status ss_guide_init(ss_guide *g, const ss_scene *scene, double q, ss_error *err);
void ss_guide_free(ss_guide *g);

/* The unit guide direction at p. */
ss_vec3 ss_guide_direction(const ss_guide *g, ss_vec3 p);

/* A segment sampled by the mixture: the classical direction density a
 * (phase function) and each channel's Dwivedi density b, the cosine mu of
 * the direction to the guide, kappa per channel and the technique drawn
 * (1: guided). */
typedef struct {
  int guided;
  double a, mu;
  ss_rgb b, kappa;
} ss_guided_segment;

/* Samples the segment's direction at a medium vertex (incoming direction d,
 * guide direction gdir) and records it in seg. */
ss_vec3 ss_guided_sample_direction(const ss_guide *g, const ss_medium *med,
                                   const ss_volume_point *q, ss_vec3 d, ss_vec3 gdir, ss_rgb kappa,
                                   int hero, ss_rng *rng, ss_guided_segment *seg);

/* The free-flight distance of the segment for the hero channel (sigma_t st). */
double ss_guided_sample_distance(const ss_guided_segment *seg, ss_rgb st, int hero, ss_rng *rng);

/* The weights of the segment (extinction st, scattering ss, mixture
 * probability q) ending in a scattering event at t_pre < tmax (returns 1) or
 * reaching tmax (returns 0); -1 when the hero's density is 0. As
 * homogeneous_segment of volume_tracking.c, with the phase function's value
 * over the mixture's joint density of direction and distance. */
int ss_guided_segment_weights(const ss_guided_segment *seg, double q, ss_rgb st, ss_rgb ss,
                              double t_pre, double tmax, int hero, ss_volume_weights w, double *t);

#endif
