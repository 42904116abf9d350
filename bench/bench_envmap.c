/* Environment map sampling against the cost of a volpath sample, on
 * scenes/skin_sphere_forest.json (a 256 x 128 map, a translucent sphere).
 * Prints (one thread, its CPU time, medians of `runs`):
 *   - ns per light sample of the map (ss_light_sample_li) and per lookup of
 *     an escaped ray with its density (ss_light_environment_li), and the
 *     same for a uniform environment of the map's mean radiance;
 *   - ns per camera sample of volpath (all pixels, and the pixels that see
 *     the object) and of bssrdf (the object's pixels) with the map and with
 *     the uniform environment, the light samples per path, and the map's
 *     cost per camera sample at most (every light sample and one escape per
 *     path) as a share of the sample's time.
 * usage: bench_envmap [scene (default $SUBSURF_SOURCE_DIR/scenes/
 *        skin_sphere_forest.json)] [samples per pixel (default 4)]
 *        [runs (default 5)] */
#include "bench_clock.h"
#include "subsurf/accel.h"
#include "subsurf/camera.h"
#include "subsurf/integrator.h"
#include "subsurf/light.h"
#include "subsurf/render.h"
#include "subsurf/rng.h"
#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>

#define QUERIES 2000000

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, compare_doubles);
  return v[n / 2];
}

/* ns per ss_light_sample_li and per escaped-ray lookup (le + pdf). */
static void query_costs(const ss_light *env, double *sample_ns, double *escape_ns, double *sink) {
  ss_rng rng;
  ss_rng_seed(&rng, 1, 0);
  ss_vec3 ref = ss_vec3_make(0, 0, 0);
  double sum = 0.0, t0 = thread_seconds();
  for (int i = 0; i < QUERIES; ++i) {
    ss_light_sample ls;
    if (ss_light_sample_li(env, ref, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &ls)) {
      sum += ls.li.c[1] / ls.pdf;
    }
  }
  double t1 = thread_seconds();
  for (int i = 0; i < QUERIES; ++i) {
    ss_vec3 w = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    double pdf;
    sum += ss_light_environment_li(env, w, &pdf).c[1] + pdf;
  }
  double t2 = thread_seconds();
  *sample_ns = 1e9 * (t1 - t0) / QUERIES;
  *escape_ns = 1e9 * (t2 - t1) / QUERIES;
  *sink += sum;
}

/* ns per camera sample of integrator `name` over the pixels of `mask`
 * (all when NULL) at spp, and the counters. */
static double sample_cost(const ss_scene *s, const char *name, const char *mask, int spp,
                          ss_path_stats *stats, double *sink) {
  const ss_integrator_ops *ops = ss_integrator_find(name);
  int w = s->camera.width, h = s->camera.height;
  ss_path_stats st = {0};
  double sum = 0.0, count = 0.0, t0 = thread_seconds();
  for (int k = 0; k < spp; ++k) {
    for (int p = 0; p < w * h; ++p) {
      if (!mask || mask[p]) {
        sum += ss_render_sample(s, ops, NULL, p % w, p / w, (uint32_t)k, 0, &st).c[1];
        count += 1.0;
      }
    }
  }
  double t = thread_seconds() - t0;
  *stats = st;
  *sink += sum;
  return 1e9 * t / count;
}

int main(int argc, char **argv) {
  char def[1024];
  const char *root = getenv("SUBSURF_SOURCE_DIR");
  snprintf(def, sizeof def, "%s/scenes/skin_sphere_forest.json", root ? root : ".");
  const char *path = argc > 1 ? argv[1] : def;
  int spp = argc > 2 ? atoi(argv[2]) : 4, runs = argc > 3 ? atoi(argv[3]) : 5;
  if (spp < 1 || runs < 1 || runs > 64) {
    fprintf(stderr, "usage: bench_envmap [scene] [spp >= 1] [runs 1..64]\n");
    return 2;
  }
  ss_scene *s;
  ss_error err;
  if (ss_scene_read_json(path, &s, &err) != SS_OK || ss_scene_commit(s, &err) != SS_OK) {
    fprintf(stderr, "bench_envmap: %s\n", err.message);
    return 1;
  }
  if (s->environment < 0 || !s->lights[s->environment].map) {
    fprintf(stderr, "bench_envmap: %s has no environment map\n", path);
    return 1;
  }
  ss_light *env = &s->lights[s->environment];
  ss_envmap *map = env->map;
  ss_rgb value = env->value;
  /* The uniform environment of the map's mean radiance (over the sphere). */
  ss_rgb mean = ss_rgb_gray(0.0);
  ss_rng rng;
  ss_rng_seed(&rng, 2, 0);
  for (int i = 0; i < 200000; ++i) {
    ss_vec3 w = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    mean = ss_rgb_madd(mean, ss_light_le(env, w, w), 1.0 / 200000);
  }
  /* The pixels whose centre sees the object. */
  int npix = s->camera.width * s->camera.height;
  char *object = malloc((size_t)npix);
  for (int p = 0; p < npix; ++p) {
    ss_ray ray =
        ss_camera_generate_ray(&s->camera, p % s->camera.width, p / s->camera.width, 0.5, 0.5);
    ss_hit hit;
    object[p] = (char)ss_accel_intersect(s->accel, &ray, &hit);
  }
  static const struct {
    const char *integrator, *label;
    int object;
  } cases[] = {{"volpath", "volpath, all pixels", 0},
               {"volpath", "volpath, the object's pixels", 1},
               {"bssrdf", "bssrdf, the object's pixels", 1}};
  enum { NCASES = 3 };
  double ms[64], me[64], us[64], ue[64], cm[NCASES][64], cu[NCASES][64], sink = 0.0;
  ss_path_stats stm[NCASES], stu[NCASES];
  for (int r = 0; r < runs; ++r) {
    for (int mapped = 1; mapped >= 0; --mapped) {
      env->map = mapped ? map : NULL;
      env->value = mapped ? value : mean;
      query_costs(env, mapped ? &ms[r] : &us[r], mapped ? &me[r] : &ue[r], &sink);
      for (int c = 0; c < NCASES; ++c) {
        double *t = mapped ? &cm[c][r] : &cu[c][r];
        *t = sample_cost(s, cases[c].integrator, cases[c].object ? object : NULL, spp,
                         mapped ? &stm[c] : &stu[c], &sink);
      }
    }
  }
  env->map = map;
  env->value = value;
  double map_sample = median(ms, runs), map_escape = median(me, runs);
  double uni_sample = median(us, runs), uni_escape = median(ue, runs);
  printf("scene %s, %d x %d, %d spp, medians of %d runs, one thread (CPU time)\n", path,
         s->camera.width, s->camera.height, spp, runs);
  printf("%-40s %10s %10s\n", "ns per", "map", "uniform");
  printf("%-40s %10.1f %10.1f\n", "light sample", map_sample, uni_sample);
  printf("%-40s %10.1f %10.1f\n", "escaped-ray lookup with its density", map_escape, uni_escape);
  for (int c = 0; c < NCASES; ++c) {
    double n = (double)stm[c].paths;
    /* Light samples of a camera sample: at most its shadow rays (one per
     * light sample); escapes: at most one per path. */
    double queries = (double)stm[c].shadow_rays / n, vm = median(cm[c], runs);
    double cost = queries * map_sample + map_escape;
    printf("%-40s %10.0f %10.0f   light samples/path %.2f; map at most %.0f ns = %.1f %%\n",
           cases[c].label, vm, median(cu[c], runs), queries, cost, 100.0 * cost / vm);
  }
  free(object);
  printf("(sink %g)\n", sink);
  ss_scene_destroy(s);
  return 0;
}
