/* Speed of the `bssrdf` integrator against volpath (issue 9): for volpath
 * and each model, the time to reach a relMSE of 0.01 on a centred crop of
 * the scene (relMSE against the same method rendered at FACTOR times the
 * samples, corrected for that reference's own noise, scaled as 1/time), the
 * speed-up over volpath, probe rays/s and BSSRDF samples/s (entry points
 * sampled per second of rendering; all times are process CPU time, so run
 * it with OMP_NUM_THREADS=1 on a loaded machine), and the memory the scene's BSSRDF cache
 * adds (resident set before and after building it).
 * usage: bench_bssrdf_pt [SCENE.json CROP SPP FACTOR MODEL...]; without
 * arguments a quick run on scenes/marble_sphere_mm.json (from
 * $SUBSURF_SOURCE_DIR or the current directory). */
#include "bench_scene.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

static double peak_rss_mb(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

/* Process CPU seconds (user + system): with one thread the render's own
 * work, whatever else the machine runs. */
static double cpu_seconds(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec +
         1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

static ss_film *render(ss_scene *s, const char *integrator, int spp, uint64_t seed,
                       const int crop[4], ss_render_stats *st) {
  snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrator);
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  o.seed = seed;
  memcpy(o.crop, crop, sizeof o.crop);
  ss_film *film = NULL;
  ss_error err;
  double t0 = cpu_seconds();
  if (ss_render(s, &o, &film, st, &err) != SS_OK) {
    fprintf(stderr, "render: %s\n", err.message);
    exit(1);
  }
  st->seconds = cpu_seconds() - t0;
  return film;
}

static double rel_mse(const ss_film *a, const ss_film *ref) {
  int w = ss_film_width(a), h = ss_film_height(a);
  double sum = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_rgb p = ss_film_pixel_mean(a, x, y), q = ss_film_pixel_mean(ref, x, y);
      for (int c = 0; c < 3; ++c) {
        double d = p.c[c] - q.c[c];
        sum += d * d / (q.c[c] * q.c[c] + 1e-2) / 3.0;
      }
    }
  }
  return sum / (w * h);
}

/* Seconds to relMSE 0.01 and the rates of one method. */
static double measure(ss_scene *s, const char *integrator, int spp, int factor, const int crop[4],
                      double *probes, double *samples) {
  ss_render_stats lo, hi;
  ss_film *a = render(s, integrator, spp, 1, crop, &lo);
  ss_film *ref = render(s, integrator, spp * factor, 2, crop, &hi);
  double e = rel_mse(a, ref) / (1.0 + 1.0 / factor);
  *probes = (double)hi.work.probe_rays / hi.seconds;
  *samples = (double)hi.work.probe_rays / 3.0 / hi.seconds;
  ss_film_destroy(a);
  ss_film_destroy(ref);
  return lo.seconds * e / 0.01;
}

int main(int argc, char **argv) {
  char scene[4096];
  bench_scene_path(scene, sizeof scene, "marble_sphere_mm.json");
  char *quick[] = {argv[0], scene, "16", "2", "4", "dipole", "pbd", "table-gwc"};
  if (argc == 1) {
    argc = 8;
    argv = quick;
  }
  if (argc < 6) {
    fprintf(stderr, "usage: bench_bssrdf_pt SCENE.json CROP SPP FACTOR MODEL...\n");
    return 2;
  }
  ss_scene *s = bench_read_scene(argv[1]);
  if (!s) {
    return 2;
  }
  ss_error err;
  int c = atoi(argv[2]), spp = atoi(argv[3]), factor = atoi(argv[4]);
  int x0 = (s->camera.width - c) / 2, y0 = (s->camera.height - c) / 2;
  const int crop[4] = {x0, y0, x0 + c, y0 + c};
  double probes, samples;
  double t_vol = measure(s, "volpath", spp, factor, crop, &probes, &samples);
  printf("%-14s %14s %9s %12s %14s %10s\n", "method", "s to relMSE .01", "speed-up", "probes/s",
         "entries/s", "cache MB");
  printf("%-14s %14.3g %9s %12s %14s %10s\n", "volpath", t_vol, "1", "-", "-", "-");
  int material = s->shapes[0].material;
  for (int k = 5; k < argc; ++k) {
    snprintf(s->materials[material].bssrdf, SS_NAME_SIZE, "%s", argv[k]);
    s->materials[material].lod = SS_LOD_BSSRDF;
    ss_subsurface_destroy(s->subsurface);
    double rss0 = peak_rss_mb();
    if (ss_subsurface_create(s, &s->subsurface, &err) != SS_OK) {
      printf("%-14s n/a: %s\n", argv[k], err.message);
      continue;
    }
    double rss = peak_rss_mb() - rss0;
    double t = measure(s, "bssrdf", spp, factor, crop, &probes, &samples);
    printf("%-14s %14.3g %9.1f %12.3g %14.3g %10.2f\n", argv[k], t, t_vol / t, probes, samples,
           rss);
    fflush(stdout);
  }
  ss_scene_destroy(s);
  return 0;
}
