/* Manifold next-event estimation's efficiency per colour channel on the
 * central view of bundled scenes: scenes whose camera sees glass
 * first (liquid_glass.json), which `subsurf compare` cannot measure (it
 * needs translucent pixels), and a close view of skin_flesh_sphere.json's
 * front. Each scene's camera narrowed to 4 x 4 pixels and an 18 deg field
 * of view (the view of tests/io/test_mnee_scenes.c), with the high-quality
 * BVH of a long render; volpath with MNEE off (`"mnee": 0`), toward every
 * light at every vertex (`"mnee_solid_angle": 100`, volpath before the rate
 * toward area lights) and by default, RUNS interleaved runs of SAMPLES
 * samples each (seeds 1..RUNS) on one thread. Per run: the thread's CPU
 * time of the sample loop and the per-sample variance per channel;
 * efficiency = 1 / (CPU per sample x variance). Prints per variant the
 * medians and each channel's median efficiency over MNEE off's median
 * (the range over the runs in brackets).
 * usage: bench_mnee [SAMPLES (default 20000)] [RUNS (default 5)] [SCENE.json ...]
 * (default: liquid_glass.json skin_flesh_sphere.json, under
 * $SUBSURF_SOURCE_DIR/scenes). */
#include "bench_clock.h"
#include "bench_scene.h"
#include "render/integrators/mnee.h"
#include "subsurf/accel.h"
#include "subsurf/integrator.h"
#include "subsurf/render.h"
#include "subsurf/stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_RUNS 25
#define VARIANTS 3

static const char *const variant_names[VARIANTS] = {"mnee 0", "every vertex", "default"};

typedef struct {
  double seconds[MAX_RUNS], var[3][MAX_RUNS], mean[3][MAX_RUNS];
} runs;

static double median(const double *x, int n) {
  double y[MAX_RUNS];
  memcpy(y, x, (size_t)n * sizeof *x);
  qsort(y, (size_t)n, sizeof *y, compare_doubles);
  return n % 2 ? y[n / 2] : 0.5 * (y[n / 2 - 1] + y[n / 2]);
}

/* One run of n samples over the 4 x 4 pixels with the scene's options. */
static int run(const ss_scene *s, long n, uint64_t seed, runs *r, int k) {
  const ss_integrator_ops *ops = ss_integrator_find("volpath");
  void *state = NULL;
  ss_error err;
  if (ops->prepare(s, &state, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 0;
  }
  ss_running_stats st[3];
  for (int c = 0; c < 3; ++c) {
    ss_running_stats_init(&st[c]);
  }
  ss_path_stats ps;
  memset(&ps, 0, sizeof ps);
  int w = s->camera.width, h = s->camera.height;
  double t0 = thread_seconds();
  for (long i = 0; i < n; ++i) {
    ss_rgb v = ss_render_sample(s, ops, state, (int)(i % w), (int)((i / w) % h),
                                (uint32_t)(i / (w * h)), seed, &ps);
    for (int c = 0; c < 3; ++c) {
      ss_running_stats_add(&st[c], v.c[c]);
    }
  }
  r->seconds[k] = thread_seconds() - t0;
  for (int c = 0; c < 3; ++c) {
    r->var[c][k] = ss_running_stats_variance(&st[c]);
    r->mean[c][k] = st[c].mean;
  }
  ops->release(state);
  return 1;
}

static double efficiency(const runs *r, int c, int k, long n) {
  return 1.0 / (r->seconds[k] / (double)n * r->var[c][k]);
}

static int bench_scene(const char *name, long n, int nruns) {
  char path[1024];
  ss_scene *s = bench_read_scene(bench_scene_path(path, sizeof path, name));
  ss_error err;
  if (!s) {
    return 0;
  }
  s->camera.width = s->camera.height = 4;
  s->camera.fov_deg = 18.0;
  if (ss_camera_init(&s->camera, &err) != SS_OK || ss_accel_refine(s->accel, &err) != SS_OK) {
    fprintf(stderr, "%s: %s\n", name, err.message);
    ss_scene_destroy(s);
    return 0;
  }
  runs r[VARIANTS];
  for (int k = 0; k < nruns; ++k) {
    for (int v = 0; v < VARIANTS; ++v) {
      int ok = ss_scene_set_integrator_option(s, "mnee", v > 0, &err) == SS_OK &&
               ss_scene_set_integrator_option(s, "mnee_solid_angle",
                                              v == 1 ? 100.0 : SS_MNEE_DEFAULT_SOLID_ANGLE,
                                              &err) == SS_OK;
      if (!ok || !run(s, n, (uint64_t)k + 1, &r[v], k)) {
        ss_scene_destroy(s);
        return 0;
      }
    }
  }
  printf("%s, %ld samples x %d runs (medians; efficiency over mnee 0's median, range)\n", name, n,
         nruns);
  printf("  %-13s %10s %30s %30s\n", "variant", "us/sample", "variance r, g, b",
         "efficiency r / g / b");
  for (int v = 0; v < VARIANTS; ++v) {
    char var[64], eff[160];
    snprintf(var, sizeof var, "%.3g, %.3g, %.3g", median(r[v].var[0], nruns),
             median(r[v].var[1], nruns), median(r[v].var[2], nruns));
    int len = 0;
    for (int c = 0; c < 3; ++c) {
      double e[MAX_RUNS], base[MAX_RUNS];
      for (int k = 0; k < nruns; ++k) {
        e[k] = efficiency(&r[v], c, k, n);
        base[k] = efficiency(&r[0], c, k, n);
      }
      double b = median(base, nruns), lo = e[0], hi = e[0];
      for (int k = 1; k < nruns; ++k) {
        lo = fmin(lo, e[k]);
        hi = fmax(hi, e[k]);
      }
      len += snprintf(eff + len, sizeof eff - (size_t)len, "%s%.2f (%.2f-%.2f)", c ? " / " : "",
                      median(e, nruns) / b, lo / b, hi / b);
    }
    printf("  %-13s %10.3g %30s   %s\n", variant_names[v], 1e6 * median(r[v].seconds, nruns) / n,
           var, eff);
  }
  ss_scene_destroy(s);
  return 1;
}

int main(int argc, char **argv) {
  long n = argc > 1 ? atol(argv[1]) : 20000;
  int nruns = argc > 2 ? atoi(argv[2]) : 5;
  if (n < 16 || nruns < 1 || nruns > MAX_RUNS) {
    fprintf(stderr, "usage: bench_mnee [SAMPLES >= 16] [RUNS 1..%d] [SCENE.json ...]\n", MAX_RUNS);
    return 2;
  }
  static const char *const defaults[] = {"liquid_glass.json", "skin_flesh_sphere.json"};
  int ok = 1;
  if (argc > 3) {
    for (int i = 3; i < argc; ++i) {
      ok &= bench_scene(argv[i], n, nruns);
    }
  } else {
    for (size_t i = 0; i < sizeof defaults / sizeof defaults[0]; ++i) {
      ok &= bench_scene(defaults[i], n, nruns);
    }
  }
  return ok ? 0 : 1;
}
