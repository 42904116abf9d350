/* The `hierarchical` integrator: per point count on the Marble
 * sphere (scenes/marble_sphere_mm.json, dipole kernel), pass 1's points/s
 * on 1 and 2 threads (irradiance_samples 16), the octree's build time and
 * bytes per point, and pass 2's lookups: kernel evaluations per lookup at
 * the default epsilon (it should grow about logarithmically with the point
 * count) and lookups/s on 1 and 2 threads. Wall-clock medians of 3 runs;
 * beside each 1 -> 2 thread speed-up, the process CPU time of the 1-thread
 * run over the 2-thread run's (1: no extra work from the second thread) and
 * the 2-thread run's CPU time over its wall time (the cores it got: 2 on an
 * idle machine), so that a loaded machine's figures can be read; and the
 * lookups/s on 1 thread through the tabulated kernel (hierarchical_table.c)
 * beside the model's, measured alternately in the same runs.
 * usage: bench_hierarchical [COUNT...] (default 10000 40000 160000). */
#include "bench_clock.h"
#include "bench_scene.h"
#include "render/integrators/hierarchical.h"
#include "subsurf/progress.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RUNS 3
#define LOOKUPS 4000

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v) {
  qsort(v, RUNS, sizeof *v, cmp);
  return v[RUNS / 2];
}

/* Pass 1 and the octree; the process CPU seconds they took in *cpu. */
static ss_hier_state *build(const ss_scene *s, size_t points, int threads, double *cpu) {
  ss_hier_options o;
  ss_error err;
  ss_hier_state *h = NULL;
  if (ss_hier_options_read(s, &o, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    exit(1);
  }
  o.points = points;
  o.irradiance_samples = 16;
  double c0 = process_seconds();
  if (ss_hier_build(s, &o, threads, NULL, &h, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    exit(1);
  }
  *cpu = process_seconds() - c0;
  return h;
}

/* Seconds for LOOKUPS diffusion sums at points of the cloud on `threads`
 * threads, through the model's kernel or (table 1) the tabulated one;
 * kernel evaluations per lookup in *evals, process CPU seconds in *cpu. */
static double lookups(const ss_hier_state *h, int threads, int table, double *evals, double *cpu) {
  uint64_t total = 0;
  double t0 = ss_seconds(), c0 = process_seconds();
#pragma omp parallel for num_threads(threads) reduction(+ : total) schedule(dynamic, 64)
  for (int i = 0; i < LOOKUPS; ++i) {
    const ss_irradiance_point *x = &h->points[((size_t)i * 7919u) % h->num_points];
    ss_hier_kernel_ctx k = {.b = h->kernel[x->shape], .x_o = x->p, .n_o = x->n, .w_o = x->n};
    k.inv_ft_normal = 1.0 / ss_irradiance_fresnel_weight(1.0, h->eta[x->shape]);
    uint64_t e = 0;
    const ss_hier_table *t = &h->table[x->shape];
    if (table && t->n) {
      ss_hier_table_ctx tk = {.table = t, .x_o = x->p};
      ss_hier_table_angular(t, &k, tk.a);
      ss_irradiance_octree_sum(&h->trees[x->shape], x->p, h->opt.epsilon, ss_hier_kernel_tabulated,
                               &tk, &e);
    } else {
      ss_irradiance_octree_sum(&h->trees[x->shape], x->p, h->opt.epsilon, ss_hier_kernel, &k, &e);
    }
    total += e;
  }
  *evals = (double)total / LOOKUPS;
  *cpu = process_seconds() - c0;
  return ss_seconds() - t0;
}

int main(int argc, char **argv) {
  char path[4096];
  ss_scene *s = bench_read_scene(bench_scene_path(path, sizeof path, "marble_sphere_mm.json"));
  if (!s) {
    return 1;
  }
  ss_error err;
  snprintf(s->materials[0].bssrdf, sizeof s->materials[0].bssrdf, "dipole");
  s->materials[0].lod = SS_LOD_BSSRDF;
  ss_subsurface_destroy(s->subsurface);
  if (ss_subsurface_create(s, &s->subsurface, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  size_t def[] = {10000, 40000, 160000};
  int n = argc > 1 ? argc - 1 : 3;
  printf("| points | pass 1 points/s (1 thr) | (2 thr) | speed-up | CPU 1/2 thr | cores got | "
         "octree ms | octree+points bytes/point | evals/lookup | lookups/s (1 thr) | (2 thr) | "
         "speed-up | CPU 1/2 thr | cores got | table lookups/s (1 thr) | table speed-up |\n");
  printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int k = 0; k < n; ++k) {
    size_t count = argc > 1 ? (size_t)atof(argv[k + 1]) : def[k];
    double p1[RUNS], p2[RUNS], oct[RUNS], l1[RUNS], l2[RUNS], evals = 0.0, bytes = 0.0;
    double pc[RUNS], pg[RUNS], lc[RUNS], lg[RUNS]; /* CPU 1 thr / 2 thr; cores got at 2 */
    double tl[RUNS], ts[RUNS];                     /* table lookups/s; over the model's */
    size_t got = 0;
    for (int r = 0; r < RUNS; ++r) {
      double ca, cb, la, lb;
      ss_hier_state *a = build(s, count, 1, &ca), *b = build(s, count, 2, &cb);
      got = a->num_points;
      pc[r] = ca / cb;
      pg[r] = cb / (b->pass1_seconds + b->octree_seconds);
      p1[r] = a->num_points / a->pass1_seconds;
      p2[r] = b->num_points / b->pass1_seconds;
      oct[r] = a->octree_seconds * 1e3;
      bytes =
          (double)(ss_irradiance_octree_bytes(&a->trees[0]) + a->num_points * sizeof *a->points) /
          a->num_points;
      l1[r] = LOOKUPS / lookups(a, 1, 0, &evals, &la);
      double tev, tc;
      tl[r] = LOOKUPS / lookups(a, 1, 1, &tev, &tc);
      ts[r] = tl[r] / l1[r];
      double w2 = lookups(a, 2, 0, &evals, &lb);
      l2[r] = LOOKUPS / w2;
      lc[r] = la / lb;
      lg[r] = lb / w2;
      ss_hier_destroy(a);
      ss_hier_destroy(b);
    }
    double m1 = median(p1), m2 = median(p2), q1 = median(l1), q2 = median(l2);
    printf("| %zu | %.0f | %.0f | %.2fx | %.2f | %.2f | %.1f | %.0f | %.0f | %.0f | %.0f | %.2fx | "
           "%.2f | %.2f | %.0f | %.2fx |\n",
           got, m1, m2, m2 / m1, median(pc), median(pg), median(oct), bytes, evals, q1, q2, q2 / q1,
           median(lc), median(lg), median(tl), median(ts));
    fflush(stdout);
  }
  ss_scene_destroy(s);
  return 0;
}
