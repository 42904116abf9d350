/* The `hybrid` integrator (Li2005): the
 * volumetric random walk of `volpath` until the path has penetrated
 * `depth` transport mean free paths below the surface it entered through,
 * then a hand-over to the material's radially symmetric diffusion model,
 * whose BSSRDF is evaluated at entry points sampled by probe rays (probe.h)
 * and the path continued from there as the `bssrdf` integrator continues
 * it (hybrid.c). The walk itself is volpath's (volpath.c); with no state or
 * an infinite depth it is volpath, bit for bit. Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_HYBRID_H
#define SUBSURF_RENDER_INTEGRATORS_HYBRID_H

#include "render/integrators/common.h"
#include "render/integrators/mnee.h"
#include "subsurf/bssrdf.h"

/* The default switch depth, in transport mean free paths l = 1 / min_c
 * sigma_t'_c: the depth of the classical dipole's own real source
 * (Jensen et al. 2001, eq. 5: z_r = 1 / sigma_t'), below which the
 * diffusion model describes the light it re-emits (docs/render.md). */
#define SS_HYBRID_DEFAULT_DEPTH 3.0

typedef struct {
  double depth; /* switch depth in transport mean free paths, >= 0, may be inf */
  size_t num_materials;
  const ss_bssrdf **kernel; /* per material: its radially symmetric model, or NULL */
} ss_hybrid_state;

/* Where the path last entered a translucent object: the surface hit, its
 * material and the transport mean free path of its most translucent channel. */
typedef struct {
  int valid;
  ss_hit hit; /* hit.ng: outward normal */
  const ss_material *m;
  double mfp;
} ss_hybrid_entry;

/* The depth of x below the tangent plane of the entry point. */
static inline double ss_hybrid_depth_below(const ss_hybrid_entry *e, ss_vec3 x) {
  return ss_vec3_dot(ss_vec3_sub(e->hit.p, x), e->hit.ng);
}

/* The hand-over at x (the entry point itself at depth 0, else a scattering
 * event, `scattered`): the diffusion model's estimate of all the light the
 * path would have gathered from x on, beta included (the path's
 * MIS-collapsed throughput times the radiance scaling of its refractions);
 * r: the path's channel density ratios (mean 1) and hero its hero channel,
 * for the media the continuation traces volumetrically. */
ss_rgb ss_hybrid_handover(const ss_scene *scene, const ss_hybrid_state *h, const ss_hybrid_entry *e,
                          ss_vec3 x, int scattered, ss_rgb beta, ss_rgb r, int hero, int depth,
                          ss_rng *rng, ss_path_stats *stats);

/* volpath's walk (volpath.c), with hand-overs when h is not NULL and
 * manifold next-event estimation as the options say (mnee.h). */
ss_rgb ss_volpath_walk(const ss_scene *scene, const ss_hybrid_state *h, const ss_mnee_options *mnee,
                       ss_ray ray, ss_rng *rng, ss_path_stats *stats);

#endif
