/* Rendering with BSSRDF models against the volumetric ground truth:
 * renders a scene with `volpath` and with the `bssrdf` integrator for each
 * model named, and prints per model the mean radiance per channel over the
 * object's pixels relative to volpath's (a "model" named volpath or auto is
 * that level of detail of the material; NAME+single adds Jensen's single
 * scattering), the same ratio of the subsurface light alone (the boundary's
 * reflection, rendered by volpath with a purely absorbing medium, taken off
 * both), the relMSE against volpath's image,
 * the time and the probe rays per second.
 * usage: bench_subsurface [SCENE.json SHAPE WIDTH REF_SPP SPP MODEL...]
 * (WIDTH: image width in pixels, the height keeps the scene's aspect);
 * without arguments a quick run on scenes/skin_sphere_thick.json (from
 * $SUBSURF_SOURCE_DIR or the current directory). scripts/bssrdf_accuracy.sh
 * runs the comparison of docs/results.md. */
#include "bench_scene.h"
#include "subsurf/progress.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  ss_film *film;
  double seconds;
  uint64_t probe_rays, nonfinite;
} run;

static int render(ss_scene *s, const char *integrator, int spp, run *out) {
  snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrator);
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  ss_render_stats st;
  ss_error err;
  if (ss_render(s, &o, &out->film, &st, &err) != SS_OK) {
    fprintf(stderr, "render: %s\n", err.message);
    return 0;
  }
  out->seconds = st.seconds;
  out->probe_rays = st.work.probe_rays;
  out->nonfinite = st.nonfinite;
  return 1;
}

/* Pixels whose centre sees the shape first. */
static char *object_mask(const ss_scene *s, int shape) {
  int w = s->camera.width, h = s->camera.height;
  char *mask = calloc((size_t)w * (size_t)h, 1);
  for (int i = 0; mask && i < w * h; ++i) {
    ss_ray ray = ss_camera_generate_ray(&s->camera, i % w, i / w, 0.5, 0.5);
    ss_hit hit;
    mask[i] = (char)(ss_accel_intersect(s->accel, &ray, &hit) && (int)hit.geom_id == shape);
  }
  return mask;
}

static void compare(const ss_scene *s, const char *mask, const ss_film *ref, const ss_film *refl,
                    const ss_film *f, double mean[3], double sub[3], double *rel_mse) {
  int w = s->camera.width, h = s->camera.height;
  double sum[3] = {0, 0, 0}, sum_ref[3] = {0, 0, 0}, sum_refl[3] = {0, 0, 0}, mse = 0.0;
  long n = 0;
  for (int i = 0; i < w * h; ++i) {
    if (!mask[i]) {
      continue;
    }
    ss_rgb a = ss_film_pixel_mean(f, i % w, i / w), b = ss_film_pixel_mean(ref, i % w, i / w);
    ss_rgb q = ss_film_pixel_mean(refl, i % w, i / w);
    for (int c = 0; c < 3; ++c) {
      sum_refl[c] += q.c[c];
      sum[c] += a.c[c];
      sum_ref[c] += b.c[c];
      double d = a.c[c] - b.c[c];
      mse += d * d / (b.c[c] * b.c[c] + 1e-2) / 3.0;
    }
    ++n;
  }
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum_ref[c] > 0.0 ? sum[c] / sum_ref[c] : 0.0;
    sub[c] = (sum[c] - sum_refl[c]) / (sum_ref[c] - sum_refl[c]);
  }
  *rel_mse = n ? mse / (double)n : 0.0;
}

int main(int argc, char **argv) {
  char scene[4096];
  bench_scene_path(scene, sizeof scene, "skin_sphere_thick.json");
  char *quick[] = {argv[0], scene, "sphere", "48", "32", "16", "dipole", "pbd", "dipole-brdf"};
  if (argc == 1) {
    argc = 9;
    argv = quick;
  }
  if (argc < 7) {
    fprintf(stderr, "usage: bench_subsurface SCENE.json SHAPE WIDTH REF_SPP SPP MODEL...\n");
    return 2;
  }
  ss_scene *s = bench_read_scene(argv[1]);
  if (!s) {
    return 2;
  }
  ss_error err;
  int shape = ss_scene_find_shape(s, argv[2]);
  int material = shape >= 0 ? s->shapes[shape].material : -1;
  if (material < 0) {
    fprintf(stderr, "no shape '%s' with a material\n", argv[2]);
    return 2;
  }
  int width = atoi(argv[3]);
  s->camera.height = width * s->camera.height / s->camera.width;
  s->camera.width = width;
  if (ss_camera_init(&s->camera, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 2;
  }
  char *mask = object_mask(s, shape);
  run ref, refl;
  /* BENCH_REFERENCE_MODEL=NAME: the reference is that model instead of
   * volpath (where volpath is too slow: the level-of-detail sweep). */
  const char *ref_model = getenv("BENCH_REFERENCE_MODEL");
  if (ref_model) {
    snprintf(s->materials[material].bssrdf, SS_NAME_SIZE, "%s", ref_model);
    s->materials[material].lod = SS_LOD_BSSRDF;
    ss_subsurface_destroy(s->subsurface);
    if (ss_subsurface_create(s, &s->subsurface, &err) != SS_OK) {
      fprintf(stderr, "%s\n", err.message);
      return 2;
    }
  }
  if (!render(s, ref_model ? "bssrdf" : "volpath", atoi(argv[4]), &ref)) {
    return 1;
  }
  ss_medium *med = &s->media[s->materials[material].medium];
  ss_medium saved = *med;
  med->optics.sigma_s = ss_rgb_gray(0.0);
  med->sigma_t = med->optics.sigma_a = ss_rgb_gray(1e9);
  if (!render(s, "volpath", 4, &refl)) {
    return 1;
  }
  *med = saved;
  printf("%-20s %6s %6s %6s | %6s %6s %6s %9s %8s %10s\n", "model", "R", "G", "B", "ss R", "ss G",
         "ss B", "relMSE", "time s", "probes/s");
  printf("%-20s (reference: %d spp, %.1f s)\n", ref_model ? ref_model : "volpath", atoi(argv[4]),
         ref.seconds);
  for (int k = 6; k < argc; ++k) {
    /* "volpath" and "auto" name levels of detail (subsurface.h), not models. */
    ss_lod lod = SS_LOD_BSSRDF;
    ss_lod_from_name(argv[k], &lod);
    s->materials[material].lod = lod;
    char name[SS_NAME_SIZE];
    snprintf(name, sizeof name, "%s", argv[k]);
    char *plus = strstr(name, "+single");
    s->materials[material].bssrdf_single = plus != NULL;
    if (plus) {
      *plus = '\0';
    }
    snprintf(s->materials[material].bssrdf, SS_NAME_SIZE, "%s", lod == SS_LOD_BSSRDF ? name : "");
    ss_subsurface_destroy(s->subsurface);
    if (ss_subsurface_create(s, &s->subsurface, &err) != SS_OK) {
      printf("%-20s n/a: %s\n", argv[k], err.message);
      continue;
    }
    run r;
    if (!render(s, "bssrdf", atoi(argv[5]), &r)) {
      return 1;
    }
    double mean[3], sub[3], rel;
    compare(s, mask, ref.film, refl.film, r.film, mean, sub, &rel);
    printf("%-20s %6.3f %6.3f %6.3f | %6.3f %6.3f %6.3f %9.4f %8.2f %10.3g%s\n", argv[k], mean[0],
           mean[1], mean[2], sub[0], sub[1], sub[2], rel, r.seconds,
           (double)r.probe_rays / r.seconds, r.nonfinite ? " (NaN/Inf!)" : "");
    fflush(stdout);
    ss_film_destroy(r.film);
  }
  ss_film_destroy(ref.film);
  ss_film_destroy(refl.film);
  free(mask);
  ss_scene_destroy(s);
  return 0;
}
