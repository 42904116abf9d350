/* Ray query throughput of the Embree accelerator on a ~1.3M-triangle
 * icosphere: primary (camera) rays, shadow rays from their hits, and the
 * BSSRDF all-hits probe, with 1 and 2 OpenMP threads.
 * Usage: bench_accel [subdivisions (default 8)] [image side (default 1024)] */
#include "subsurf/accel.h"
#include "subsurf/mesh.h"
#include "subsurf/rng.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

typedef enum { Q_CAMERA, Q_SHADOW, Q_PROBE } query;

/* Pinhole camera at (0, 0, 3) looking down -z with a 40 degree field. */
static ss_ray camera_ray(int x, int y, int side) {
  double t = tan(0.5 * 40.0 * 3.14159265358979 / 180.0);
  double px = (2.0 * (x + 0.5) / side - 1.0) * t, py = (1.0 - 2.0 * (y + 0.5) / side) * t;
  ss_ray r = {ss_vec3_make(0, 0, 3), ss_vec3_normalize(ss_vec3_make(px, py, -1)), 0.0, INFINITY};
  return r;
}

static double run(const ss_accel *a, query q, int side, int threads, long *count) {
  long n = 0;
  double t0 = omp_get_wtime();
  const ss_vec3 light = ss_vec3_make(5, 5, 5), zero = ss_vec3_make(0, 0, 0);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : n)
  for (int y = 0; y < side; ++y) {
    ss_rng rng;
    ss_rng_seed(&rng, 1, (uint64_t)y);
    for (int x = 0; x < side; ++x) {
      ss_ray r = camera_ray(x, y, side);
      ss_hit h;
      if (q == Q_CAMERA) {
        ss_accel_intersect(a, &r, &h);
        ++n;
        continue;
      }
      /* Shadow and probe rays start at the visible surface point. */
      if (!ss_accel_intersect(a, &r, &h)) {
        continue;
      }
      if (q == Q_SHADOW) {
        ss_ray s = ss_ray_spawn_to(h.p, h.ng, light, zero);
        n += ss_accel_occluded(a, &s) >= 0;
      } else {
        /* A probe of length 0.2 along -ng through the hit, as a BSSRDF
         * sampler does with a radius of 0.1. */
        ss_vec3 o = ss_vec3_madd(h.p, h.ng, 0.1);
        ss_ray p = {o, ss_vec3_neg(h.ng), 0.0, 0.2};
        ss_hit one;
        n += ss_accel_intersect_sample(a, &p, 0, ss_rng_uniform(&rng), &one) > 0;
      }
    }
  }
  *count = n;
  return omp_get_wtime() - t0;
}

int main(int argc, char **argv) {
  unsigned subdiv = argc > 1 ? (unsigned)atoi(argv[1]) : 8;
  int side = argc > 2 ? atoi(argv[2]) : 1024;
  ss_mesh *m = NULL;
  ss_error err;
  if (ss_shape_icosphere(1.0, subdiv, &m, &err) != SS_OK) {
    fprintf(stderr, "bench_accel: %s\n", err.message);
    return 2;
  }
  const ss_mesh *ms[1] = {m};
  ss_accel *a = NULL;
  double t0 = omp_get_wtime();
  if (ss_accel_create(ms, 1, &a, &err) != SS_OK) {
    fprintf(stderr, "bench_accel: %s\n", err.message);
    ss_mesh_destroy(m);
    return 2;
  }
  double build = omp_get_wtime() - t0;
  printf("icosphere: %zu triangles, BVH build %.2f s (Embree's own threads)\n", m->num_triangles,
         build);
  printf("%-8s %8s %12s %10s %12s %9s\n", "query", "threads", "rays", "seconds", "Mrays/s",
         "speed-up");
  const char *names[3] = {"camera", "shadow", "probe"};
  for (int q = 0; q < 3; ++q) {
    double rate1 = 0.0;
    for (int threads = 1; threads <= 2; ++threads) {
      long n;
      run(a, (query)q, side / 4, threads, &n); /* warm-up */
      double secs = run(a, (query)q, side, threads, &n);
      /* Shadow and probe timings include the camera ray that found the start. */
      double rate = (double)n / secs / 1e6;
      if (threads == 1) {
        rate1 = rate;
      }
      printf("%-8s %8d %12ld %10.3f %12.3f %9.2f\n", names[q], threads, n, secs, rate,
             rate / rate1);
    }
  }
  printf("(shadow and probe rows include the primary ray that finds each start point)\n");
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
  return 0;
}
