/* The `hybrid` integrator (Li2005): the
 * volumetric random walk of `volpath` until the path has penetrated
 * `depth` transport mean free paths below the surface it entered through,
 * then a hand-over to the material's radially symmetric diffusion model,
 * whose BSSRDF is evaluated at entry points sampled by probe rays (probe.h)
 * and the path continued from there as the `bssrdf` integrator continues
 * it (hybrid.c). The walk is the medium walk (medium_walk.h), which the
 * hybrid reacts to; at an infinite depth it is volpath, bit for bit.
 * Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_HYBRID_H
#define SUBSURF_RENDER_INTEGRATORS_HYBRID_H

#include "render/integrators/common.h"

/* The default switch depth, in transport mean free paths l = 1 / min_c
 * sigma_t'_c: the depth of the classical dipole's own real source
 * (Jensen et al. 2001, eq. 5: z_r = 1 / sigma_t'), below which the
 * diffusion model describes the light it re-emits (docs/render.md). */
#define SS_HYBRID_DEFAULT_DEPTH 3.0

#endif
