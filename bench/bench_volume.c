/* Oriented and gridded media: sigma_t(w) lookups (homogeneous
 * fibre flakes, and at a grid point with a voxel axis: density, axis frame
 * and table), delta tracking's tentative collisions per second in a 256^3
 * grid (the procedural wood in a cube: growth rings, latewood 3x denser,
 * fibre flakes along the grain; random rays from random points of the box,
 * one thread, CPU time), and the grid's bytes per voxel.
 * Usage: bench_volume [resolution (default 256)] [lookups (default 4000000)] */
#include "subsurf/grid.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/volume.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static ss_vec3 random_dir(ss_rng *rng) {
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  return ss_sample_uniform_sphere(u1, u2);
}

/* ns per sigma_t(w) lookup at the point q (a fixed point for homogeneous
 * media, else a random point each time: ss_volume_at included). */
static double lookup_ns(const ss_medium *m, long n, int at_points, double *sink) {
  ss_rng rng;
  ss_rng_seed(&rng, 3, 0);
  ss_volume_point q = ss_volume_at(m, ss_vec3_make(0, 0, 0));
  double sum = 0.0, t0 = cpu_seconds();
  for (long k = 0; k < n; ++k) {
    if (at_points) {
      q = ss_volume_at(m, ss_vec3_make(1.8 * ss_rng_uniform(&rng) - 0.9,
                                       1.8 * ss_rng_uniform(&rng) - 0.9,
                                       1.8 * ss_rng_uniform(&rng) - 0.9));
    }
    sum += ss_volume_sigma_t(m, &q, random_dir(&rng)).c[0];
  }
  *sink += sum;
  return 1e9 * (cpu_seconds() - t0) / (double)n;
}

int main(int argc, char **argv) {
  int res = argc > 1 ? atoi(argv[1]) : 256;
  long n = argc > 2 ? atol(argv[2]) : 4000000;
  ss_error err;
  ss_medium m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "bench");
  m.optics.sigma_s = ss_rgb_gray(8.0);
  m.optics.sigma_a = ss_rgb_make(0.05, 0.25, 0.8);
  m.optics.flakes = (ss_medium_flakes){SS_FLAKE_FIBER, 20.0, ss_vec3_make(1, 0, 0), 0.0, 1.0};
  if (ss_medium_init(&m, &err) != SS_OK || ss_medium_prepare_volume(&m, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  double sink = 0.0;
  printf("sigma_t(w) lookup, homogeneous fibre flakes: %.1f ns\n", lookup_ns(&m, n, 0, &sink));
  ss_wood_params wp = {res, ss_vec3_make(1.8, 1.8, 1.8), 0.15, 3.0, 0.4};
  double t0 = cpu_seconds();
  if (ss_grid_wood(&wp, &m.grid, &err) != SS_OK || ss_medium_prepare_volume(&m, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  const ss_grid *g = m.grid;
  printf("wood grid %d x %d x %d: generated in %.1f s CPU, %zu bytes per voxel (%.0f MB)\n",
         g->n[0], g->n[1], g->n[2], cpu_seconds() - t0, ss_grid_bytes_per_voxel(g),
         ss_grid_bytes_per_voxel(g) * (double)ss_grid_voxels(g) / 1e6);
  printf("sigma_t(w) lookup at a grid point (trilinear density, voxel axis frame): %.1f ns\n",
         lookup_ns(&m, n, 1, &sink));
  /* Delta tracking: rays from random points of the box in random directions. */
  ss_rng rng;
  ss_rng_seed(&rng, 5, 0);
  uint64_t tentative = 0, real = 0;
  long rays = n / 8;
  t0 = cpu_seconds();
  for (long k = 0; k < rays; ++k) {
    ss_vec3 o = ss_vec3_make(1.8 * ss_rng_uniform(&rng) - 0.9, 1.8 * ss_rng_uniform(&rng) - 0.9,
                             1.8 * ss_rng_uniform(&rng) - 0.9);
    ss_rgb beta = ss_rgb_gray(1.0), r_u = beta, r_l = beta;
    ss_volume_weights w = {&beta, &r_u, &r_l};
    double t;
    real += ss_volume_segment(&m, o, random_dir(&rng), INFINITY, 10.0, (int)(k % 3), &rng, w, &t,
                              &tentative) > 0;
    sink += beta.c[0];
  }
  double dt = cpu_seconds() - t0;
  printf("delta tracking: %.3g tentative collisions/s (%.3g rays/s, %.2f tentative and %.2f real "
         "per ray, majorant %.3g x sigma_t)\n",
         (double)tentative / dt, rays / dt, (double)tentative / rays, (double)real / rays,
         m.majorant);
  ss_medium_release_volume(&m);
  return sink == 42.0;
}
