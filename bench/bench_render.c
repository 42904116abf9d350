/* Renderer throughput on the default scenes: camera (closest-hit) and
 * shadow (occlusion) rays per second, volpath paths/s, scattering events/s,
 * rays/s, the 1 -> 2 thread speed-up and the peak memory (getrusage).
 * usage: bench_render [scenes dir (default $SUBSURF_SOURCE_DIR/scenes or
 *        ./scenes)] [spp per run (default 2)] */
#include "subsurf/light.h"
#include "subsurf/progress.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

/* Camera rays through every pixel (closest hit), then a shadow ray from each
 * hit toward a light sample (occlusion only); rays per second. */
static void ray_rates(const ss_scene *s, int threads, double *camera, double *shadow) {
  int w = s->camera.width, h = s->camera.height, n = w * h;
  ss_hit *hits = malloc((size_t)n * sizeof *hits);
  char *found = calloc((size_t)n, 1);
  double t0 = ss_seconds();
  for (int rep = 0; rep < 4; ++rep) {
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
    for (int i = 0; i < n; ++i) {
      ss_ray ray = ss_camera_generate_ray(&s->camera, i % w, i / w, 0.5, 0.5);
      found[i] = (char)ss_accel_intersect(s->accel, &ray, &hits[i]);
    }
  }
  double t1 = ss_seconds();
  *camera = 4.0 * n / (t1 - t0);
  long shadow_rays = 0, blocked = 0;
  t0 = ss_seconds();
  for (int rep = 0; rep < 4; ++rep) {
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads) \
    reduction(+ : shadow_rays, blocked)
    for (int i = 0; i < n; ++i) {
      if (!found[i] || s->num_lights == 0) {
        continue;
      }
      ss_light_sample ls;
      double u1 = (i % 97) / 97.0, u2 = (i % 89) / 89.0;
      if (!ss_light_sample_li(&s->lights[i % s->num_lights], hits[i].p, u1, u2, &ls)) {
        continue;
      }
      ss_ray ray = isfinite(ls.dist) ? ss_ray_spawn_to(hits[i].p, hits[i].ng, ls.p, ls.n)
                                     : ss_ray_spawn(hits[i].p, hits[i].ng, ls.wi);
      blocked += ss_accel_occluded(s->accel, &ray);
      shadow_rays++;
    }
  }
  t1 = ss_seconds();
  *shadow = shadow_rays / (t1 - t0);
  (void)blocked; /* the count only keeps the queries from being optimised away */
  free(hits);
  free(found);
}

static int render_once(const ss_scene *s, int threads, int spp, ss_render_stats *st) {
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  o.threads = threads;
  ss_film *film;
  ss_error err;
  if (ss_render(s, &o, &film, st, &err) != SS_OK) {
    fprintf(stderr, "bench_render: %s\n", err.message);
    return 0;
  }
  ss_film_destroy(film);
  return 1;
}

int main(int argc, char **argv) {
  char dir[4096];
  const char *root = getenv("SUBSURF_SOURCE_DIR");
  if (argc > 1) {
    snprintf(dir, sizeof dir, "%s", argv[1]);
  } else {
    snprintf(dir, sizeof dir, "%s/scenes", root ? root : ".");
  }
  int spp = argc > 2 ? atoi(argv[2]) : 2;
  if (spp < 1) {
    fprintf(stderr, "usage: bench_render [scenes dir] [spp >= 1]\n");
    return 2;
  }
  const char *names[] = {"skin_sphere", "fig1_cube", "skin_rough_sphere", "marble_slab"};
  int max_threads = omp_get_num_procs() < 2 ? 1 : 2;
  printf("%-18s %3s %12s %12s %10s %12s %12s %8s %7s\n", "scene", "thr", "camera ray/s",
         "shadow ray/s", "paths/s", "events/s", "rays/s", "ev/path", "speedup");
  for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s.json", dir, names[k]);
    ss_scene *s;
    ss_error err;
    if (ss_scene_read_json(path, &s, &err) != SS_OK) {
      fprintf(stderr, "bench_render: %s\n", err.message);
      return 1;
    }
    double paths1 = 0.0;
    for (int threads = 1; threads <= max_threads; ++threads) {
      double cam, shadow;
      ray_rates(s, threads, &cam, &shadow);
      ss_render_stats st;
      if (!render_once(s, threads, spp, &st)) {
        ss_scene_destroy(s);
        return 1;
      }
      double secs = st.seconds > 0.0 ? st.seconds : 1e-9;
      double paths = st.work.paths / secs;
      double rays = (st.work.camera_rays + st.work.extension_rays + st.work.shadow_rays) / secs;
      if (threads == 1) {
        paths1 = paths;
      }
      printf("%-18s %3d %12.3g %12.3g %10.3g %12.3g %12.3g %8.1f %7.2f\n", names[k], threads, cam,
             shadow, paths, st.work.scatter_events / secs, rays,
             (double)st.work.scatter_events / (double)(st.work.paths ? st.work.paths : 1),
             paths / paths1);
    }
    ss_scene_destroy(s);
  }
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  printf("peak resident memory: %.1f MiB\n", ru.ru_maxrss / 1024.0);
  return 0;
}
