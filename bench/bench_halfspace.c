/* Throughput of the half-space light tracer: scattering events per second
 * per core, paths per second, and the 1 -> 2 thread speed-up, each the
 * median of several runs, measured side by side in one process: run r of
 * every configuration before run r + 1 of any, so that a change of the
 * machine's load falls on all of them. One thread is timed by the thread's
 * CPU time (insensitive to other processes taking the core), two by the
 * wall clock; the micro-flake rows give their rate relative to the
 * isotropic walk "albedo 0.99, g 0" (the target: at least 0.5). The run's
 * time includes its set-up (the micro-flake tables, about 30 ms): with one
 * thread the set-up is also timed alone, by ss_halfspace_bytes (it builds
 * the same tracer), in the same round, and "walk vs iso" is the ratio with
 * it subtracted.
 * usage: bench_halfspace [runs (default 5)] [paths per run (default 200000)]
 *        [max threads: 1 or 2 (default)] */
#include "bench_clock.h"
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

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, compare_doubles);
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
  enum { NC = sizeof configs / sizeof configs[0], ISO = 2 };
  int max_threads = omp_get_num_procs() < 2 || (argc > 3 && atoi(argv[3]) == 1) ? 1 : 2;
  printf("%-26s %7s %14s %14s %12s %9s %9s %8s\n", "configuration", "threads", "events/s/core",
         "paths/s", "events/path", "vs iso", "walk/iso", "set-up");
  static double ev[3][NC][101], ps[3][NC][101], walk[NC][101], setup[NC][101], per_path[NC];
  for (int threads = 1; threads <= max_threads; ++threads) {
    for (int r = 0; r < runs; ++r) {
      for (size_t c = 0; c < NC; ++c) {
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
        double t0 = thread_seconds();
        if (threads == 1) {
          volatile double bytes = ss_halfspace_bytes(&p);
          (void)bytes;
          setup[c][r] = thread_seconds() - t0;
          t0 = thread_seconds();
        }
        if (ss_halfspace_run(&p, &res, &err) != SS_OK) {
          fprintf(stderr, "bench_halfspace: %s\n", err.message);
          return 1;
        }
        double secs = threads == 1 ? thread_seconds() - t0 : res->seconds;
        ev[threads][c][r] = (double)res->scatter_events / secs / threads;
        if (threads == 1) {
          walk[c][r] = (double)res->scatter_events / (secs - setup[c][r]);
        }
        ps[threads][c][r] = (double)res->paths / secs;
        per_path[c] = (double)res->scatter_events / (double)res->paths;
        ss_halfspace_result_destroy(res);
      }
    }
  }
  /* vs iso: the ratio of the medians of runs side by side. */
  for (size_t c = 0; c < NC; ++c) {
    double rate[3] = {0, 0, 0};
    for (int threads = 1; threads <= max_threads; ++threads) {
      double ev_med = median(ev[threads][c], runs), ps_med = median(ps[threads][c], runs);
      rate[threads] = ps_med;
      printf("%-26s %7d %14.3e %14.3e %12.1f %9.2f", configs[c].name, threads, ev_med, ps_med,
             per_path[c], ev_med / median(ev[threads][ISO], runs));
      if (threads == 1) {
        printf(" %9.2f %6.1fms", median(walk[c], runs) / median(walk[ISO], runs),
               1e3 * median(setup[c], runs));
      }
      printf("\n");
    }
    if (max_threads == 2) {
      printf("%-26s speed-up 1 -> 2 threads: %.2fx\n", configs[c].name, rate[2] / rate[1]);
    }
  }
  return 0;
}
