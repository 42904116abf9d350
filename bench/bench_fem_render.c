/* The `fem` integrator: the render time of a scene split into
 * its parts: gmsh's meshing (wall clock), the boundary irradiance (wall
 * clock, all threads), assembly and solve (CPU, summed over the colour
 * channels) in the integrator's prepare step, and the shading of the
 * image (every camera sample through the prepared solution, wall clock on
 * one thread). With CACHE, the integrator's cache file (integrator.cache,
 * fem_cache.h): run once without it (or after removing it) for a cold
 * prepare, again for a warm one.
 * usage: bench_fem_render [SCENE.json [SPP [CACHE]]] (default scenes/fig9a_fem.json, 4). */
#include "bench_clock.h"
#include "bench_scene.h"
#include "render/integrators/fem.h"
#include "subsurf/progress.h"
#include "subsurf/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv) {
  char path[4096];
  const char *file = argc > 1 ? argv[1] : bench_scene_path(path, sizeof path, "fig9a_fem.json");
  int spp = argc > 2 ? atoi(argv[2]) : 4;
  ss_scene *s = bench_read_scene(file);
  if (!s || spp < 1) {
    return 2;
  }
  if (argc > 3) {
    snprintf(s->integrator.cache, sizeof s->integrator.cache, "%s", argv[3]);
  }
  const ss_integrator_ops *ops = ss_integrator_find("fem");
  void *state = NULL;
  ss_error err;
  double t0 = ss_seconds();
  if (ops->prepare(s, &state, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    ss_scene_destroy(s);
    return 2;
  }
  double prepare = ss_seconds() - t0;
  ss_fem_render_timings t;
  ss_fem_render_timings_of(state, &t);
  ss_path_stats stats;
  memset(&stats, 0, sizeof stats);
  int w = s->camera.width, h = s->camera.height;
  t0 = ss_seconds();
  for (int k = 0; k < spp; ++k) {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        ss_render_sample(s, ops, state, x, y, (uint32_t)k, 0, &stats);
      }
    }
  }
  double shade = ss_seconds() - t0;
  printf("scene %s: %zu tetrahedra, %d x %d pixels at %d spp\n", file, t.tets, w, h, spp);
  printf("prepare %.2f s wall: meshing %.2f s wall, irradiance %.2f s wall, assembly %.2f s CPU, "
         "solve %.2f s CPU (3 channels)\n",
         prepare, t.mesh_seconds, t.irradiance_seconds, t.assemble_seconds, t.solve_seconds);
  if (argc > 3) {
    printf("cache %s: %d of %d meshes and %d solutions read from it\n", argv[3], t.meshes_cached,
           t.objects, t.solutions_cached);
  }
  printf("shading %.2f s wall on one thread (%.3g samples/s)\n", shade,
         (double)spp * w * h / shade);
  ops->release(state);
  ss_scene_destroy(s);
  return 0;
}
