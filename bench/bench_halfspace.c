/* Throughput of the half-space light tracer: scattering events per second
 * per core, paths per second, and the 1 -> 2 thread speed-up, each the
 * median of several runs, measured side by side in one process.
 * usage: bench_halfspace [runs (default 5)] [paths per run (default 200000)] */
#include "subsurf/halfspace.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct {
  const char *name;
  double albedo, g;
  ss_phase_type phase;
  ss_flake_type flakes; /* micro-flake media: axis in the surface plane */
} config;

static int compare_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, compare_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv) {
  int runs = argc > 1 ? atoi(argv[1]) : 5;
  unsigned long long paths = argc > 2 ? strtoull(argv[2], NULL, 10) : 200000ull;
  if (runs < 1 || runs > 101 || paths == 0) {
    fprintf(stderr, "usage: bench_halfspace [runs 1..101] [paths >= 1]\n");
    return 2;
  }
  const config configs[] = {
      {"albedo 0.99, HG g 0.9", 0.99, 0.9, SS_PHASE_HG, SS_FLAKE_NONE},
      {"albedo 0.999, g 0", 0.999, 0.0, SS_PHASE_ISOTROPIC, SS_FLAKE_NONE},
      {"albedo 0.99, g 0", 0.99, 0.0, SS_PHASE_ISOTROPIC, SS_FLAKE_NONE},
      {"albedo 0.99, fiber p 20", 0.99, 0.0, SS_PHASE_ISOTROPIC, SS_FLAKE_FIBER},
      {"albedo 0.99, surface p 20", 0.99, 0.0, SS_PHASE_ISOTROPIC, SS_FLAKE_SURFACE},
  };
  int max_threads = omp_get_num_procs() < 2 ? 1 : 2;
  printf("%-26s %7s %14s %14s %12s\n", "configuration", "threads", "events/s/core", "paths/s",
         "events/path");
  for (size_t c = 0; c < sizeof configs / sizeof configs[0]; ++c) {
    double rate[3] = {0, 0, 0};
    for (int threads = 1; threads <= max_threads; ++threads) {
      double ev[101], ps[101], per_path = 0.0;
      for (int r = 0; r < runs; ++r) {
        ss_halfspace_params p;
        ss_halfspace_params_default(&p);
        p.medium.sigma_s = ss_rgb_gray(configs[c].albedo);
        p.medium.sigma_a = ss_rgb_gray(1.0 - configs[c].albedo);
        p.medium.g = ss_rgb_gray(configs[c].g);
        p.medium.phase = configs[c].phase;
        p.medium.flakes = (ss_medium_flakes){configs[c].flakes, 20.0, {1.0, 0.0, 0.0}, 0.0, 0.0};
        p.eta = 1.33;
        p.paths = paths;
        p.seed = (uint64_t)r;
        p.threads = threads;
        ss_halfspace_result *res;
        ss_error err;
        if (ss_halfspace_run(&p, &res, &err) != SS_OK) {
          fprintf(stderr, "bench_halfspace: %s\n", err.message);
          return 1;
        }
        ev[r] = (double)res->scatter_events / res->seconds / threads;
        ps[r] = (double)res->paths / res->seconds;
        per_path = (double)res->scatter_events / (double)res->paths;
        ss_halfspace_result_destroy(res);
      }
      double ev_med = median(ev, runs), ps_med = median(ps, runs);
      rate[threads] = ps_med;
      printf("%-26s %7d %14.3e %14.3e %12.1f\n", configs[c].name, threads, ev_med, ps_med,
             per_path);
    }
    if (max_threads == 2) {
      printf("%-26s speed-up 1 -> 2 threads: %.2fx\n", configs[c].name, rate[2] / rate[1]);
    }
  }
  return 0;
}
