/* The `fem` integrator's prepare-step timings and cache use (fem.c), for
 * bench/bench_fem_render.c and the tests. Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_FEM_H
#define SUBSURF_RENDER_INTEGRATORS_FEM_H

#include <stddef.h>

typedef struct {
  double mesh_seconds;       /* gmsh, wall clock */
  double irradiance_seconds; /* boundary sources, wall clock */
  double assemble_seconds;   /* CPU, summed over the channels */
  double solve_seconds;      /* CPU, summed over the channels */
  size_t tets;               /* tetrahedra of all objects */
  int objects;               /* translucent shapes solved */
  int meshes_cached;         /* of them, meshes read from the cache (fem_cache.h) */
  int solutions_cached;      /* of them, solutions read from the cache */
} ss_fem_render_timings;

/* The timings of a state made by the integrator's prepare. */
void ss_fem_render_timings_of(const void *state, ss_fem_render_timings *t);

#endif
