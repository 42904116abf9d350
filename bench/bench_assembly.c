/* Scene assembly: reading and committing a JSON scene of n cubes on a grid
 * (spacing 1, side 0.5), of a dielectric (each cube bounds a region whose
 * overlaps the scene checks) or of a diffuse material. Prints the wall
 * clock and the process's CPU time of ss_scene_parse_json, median of runs.
 * Usage: bench_assembly [n (default 100000)] [runs (default 3)] */
#include "bench_clock.h"
#include "subsurf/scene_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *scene_text(long n, const char *material) {
  long side = (long)ceil(cbrt((double)n));
  size_t size = 512 + (size_t)n * 160;
  char *t = malloc(size);
  if (!t) {
    return NULL;
  }
  size_t used = (size_t)snprintf(t, size,
                                 "{\"camera\": {\"position\": [-5, -5, -5], \"target\": [0, 0, 0], "
                                 "\"resolution\": [8, 8]},\n \"materials\": [%s],\n \"shapes\": [",
                                 material);
  for (long i = 0; i < n; ++i) {
    used += (size_t)snprintf(t + used, size - used,
                             "%s{\"name\": \"c%ld\", \"type\": \"cube\", \"size\": 0.5, "
                             "\"material\": \"m\", \"transform\": {\"translate\": [%ld, %ld, "
                             "%ld]}}",
                             i ? ",\n" : "", i, i % side, i / side % side, i / (side * side));
  }
  snprintf(t + used, size - used,
           "],\n \"lights\": [{\"name\": \"sky\", \"type\": \"environment\"}]}\n");
  return t;
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, compare_doubles);
  return v[n / 2];
}

int main(int argc, char **argv) {
  long n = argc > 1 ? atol(argv[1]) : 100000;
  int runs = argc > 2 ? atoi(argv[2]) : 3;
  if (n < 1 || n > 10000000 || runs < 1 || runs > 99) {
    fprintf(stderr, "usage: bench_assembly [n in 1..1e7] [runs in 1..99]\n");
    return 2;
  }
  static const char *kinds[2][2] = {
      {"dielectric", "{\"name\": \"m\", \"type\": \"dielectric\", \"eta\": 1.5}"},
      {"diffuse", "{\"name\": \"m\", \"type\": \"diffuse\"}"}};
  for (int k = 0; k < 2; ++k) {
    char *text = scene_text(n, kinds[k][1]);
    if (!text) {
      fprintf(stderr, "bench_assembly: out of memory\n");
      return 1;
    }
    double wall[99], cpu[99];
    for (int r = 0; r < runs; ++r) {
      ss_scene *s = NULL;
      ss_error err;
      struct timespec t0, t1;
      double c0 = process_seconds();
      clock_gettime(CLOCK_MONOTONIC, &t0);
      ss_status st = ss_scene_parse_json(text, "bench.json", NULL, &s, &err);
      clock_gettime(CLOCK_MONOTONIC, &t1);
      cpu[r] = process_seconds() - c0;
      wall[r] = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
      ss_scene_destroy(s);
      if (st != SS_OK) {
        fprintf(stderr, "bench_assembly: %s\n", err.message);
        free(text);
        return 1;
      }
    }
    printf("%ld %s cubes: %.3f s wall, %.3f s CPU (median of %d)\n", n, kinds[k][0],
           median(wall, runs), median(cpu, runs), runs);
    free(text);
  }
  return 0;
}
