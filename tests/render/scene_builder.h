/* Pieces of the small scenes the render tests build by hand: a diffuse floor,
 * lights, and the "floor, lamp and sky" surroundings that make every branch of
 * an integrator run. */
#ifndef SUBSURF_TESTS_RENDER_SCENE_BUILDER_H
#define SUBSURF_TESTS_RENDER_SCENE_BUILDER_H

#include "subsurf/mesh.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"
#include "subsurf/transform.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* A light `name` of `type` (area lights: emissive shape `shape`, else -1). */
static inline ss_light test_light(const char *name, ss_light_type type, int shape, ss_rgb value) {
  ss_light l;
  memset(&l, 0, sizeof l);
  snprintf(l.name, sizeof l.name, "%s", name);
  l.type = type;
  l.shape = shape;
  l.value = value;
  return l;
}

static inline void test_add_light(ss_scene *s, const char *name, ss_light_type type, int shape,
                                  ss_rgb value) {
  ss_error err;
  ss_light l = test_light(name, type, shape, value);
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
}

/* A point light `name` of intensity I at p. */
static inline void test_add_point_light(ss_scene *s, const char *name, ss_vec3 p, double I) {
  ss_error err;
  ss_light l = test_light(name, SS_LIGHT_POINT, -1, ss_rgb_gray(I));
  l.position = p;
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
}

/* The slab tests' view: a 2 x 2 camera at (0, 0, 20) looking straight down
 * at the origin through a 1 degree field of view, and the `bssrdf`
 * integrator. */
static inline void test_slab_view(ss_scene *s) {
  s->camera.width = 2;
  s->camera.height = 2;
  s->camera.position = ss_vec3_make(0, 0, 20);
  s->camera.target = ss_vec3_make(0, 0, 0);
  s->camera.up = ss_vec3_make(0, 1, 0);
  s->camera.fov_deg = 1.0;
  snprintf(s->integrator.name, sizeof s->integrator.name, "bssrdf");
}

/* The small-object tests' view: a width x height camera at (0, 1, 4)
 * looking at the origin through a 40 degree field of view. */
static inline void test_sphere_view(ss_scene *s, int width, int height) {
  s->camera.width = width;
  s->camera.height = height;
  s->camera.position = ss_vec3_make(0, 1, 4);
  s->camera.target = ss_vec3_make(0, 0, 0);
  s->camera.up = ss_vec3_make(0, 1, 0);
  s->camera.fov_deg = 40;
}

/* A directional light "sun" of unit irradiance travelling along d. */
static inline void test_add_sun(ss_scene *s, ss_vec3 d) {
  ss_error err;
  ss_light l;
  memset(&l, 0, sizeof l);
  snprintf(l.name, sizeof l.name, "sun");
  l.type = SS_LIGHT_DIRECTIONAL;
  l.direction = d;
  l.value = ss_rgb_gray(1.0);
  l.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
}

/* A render shares its window out in SS_RENDER_TILE square tiles, at most one
 * thread to a tile (src/render/parallel.c): a render asked for more threads
 * than its window has tiles runs on fewer, and a test comparing 1 and 2
 * threads on a one-tile image compares one thread with itself. Asserts that
 * the render of `o` on s can use its threads (o->threads 0: OpenMP's
 * default, not checked). */
static inline void test_expect_tiles_for_threads(const ss_scene *s, const ss_render_options *o) {
  int w = s->camera.width, h = s->camera.height;
  if (o->crop[0] || o->crop[1] || o->crop[2] || o->crop[3]) {
    w = o->crop[2] - o->crop[0];
    h = o->crop[3] - o->crop[1];
  }
  int tiles =
      ((w + SS_RENDER_TILE - 1) / SS_RENDER_TILE) * ((h + SS_RENDER_TILE - 1) / SS_RENDER_TILE);
  cr_assert(o->threads <= tiles,
            "a %d x %d window has %d tile(s) of %d x %d: a render on %d threads runs on %d", w, h,
            tiles, SS_RENDER_TILE, SS_RENDER_TILE, o->threads, tiles);
}

/* The scene rendered with its own options but spp samples per pixel, the
 * seed and the thread count given; the render must succeed, its window must
 * have a tile for each thread (test_expect_tiles_for_threads), and each
 * thread must have rendered (ss_render_stats.threads), so that a test of 1
 * against 2 threads compares two threads' work with one's. stats may be
 * NULL. */
static inline ss_film *test_render(const ss_scene *s, int spp, uint64_t seed, int threads,
                                   ss_render_stats *stats) {
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  o.seed = seed;
  o.threads = threads;
  test_expect_tiles_for_threads(s, &o);
  ss_film *film;
  ss_render_stats own;
  ss_error err;
  if (!stats) {
    stats = &own;
  }
  cr_assert_eq(ss_render(s, &o, &film, stats, &err), SS_OK, "%s", err.message);
  cr_assert_eq(stats->threads, threads, "%d of the %d threads rendered", stats->threads, threads);
  return film;
}

/* Asserts that films a and b have bit-identical pixel means, all finite;
 * returns the sum of a's green channel over its pixels. */
static inline double test_expect_identical_films(const ss_film *a, const ss_film *b) {
  cr_assert(ss_film_width(a) == ss_film_width(b) && ss_film_height(a) == ss_film_height(b));
  double sum = 0.0;
  for (int y = 0; y < ss_film_height(a); ++y) {
    for (int x = 0; x < ss_film_width(a); ++x) {
      ss_rgb pa = ss_film_pixel_mean(a, x, y), pb = ss_film_pixel_mean(b, x, y);
      cr_assert(ss_rgb_is_finite(pa), "pixel (%d, %d) is not finite", x, y);
      cr_assert(!memcmp(&pa, &pb, sizeof pa), "pixel (%d, %d) differs: green %.17g vs %.17g", x, y,
                pa.c[1], pb.c[1]);
      sum += pa.c[1];
    }
  }
  return sum;
}

/* The scene rendered on 1 and on 2 threads at spp and seed (test_render:
 * both threads render): bit-identical images, without NaN/Inf samples and
 * not black (two black images would prove nothing). */
static inline void test_expect_thread_independent(const ss_scene *s, int spp, uint64_t seed) {
  ss_render_stats st1, st2;
  ss_film *one = test_render(s, spp, seed, 1, &st1), *two = test_render(s, spp, seed, 2, &st2);
  cr_assert_eq(st1.nonfinite + st2.nonfinite, 0, "NaN/Inf samples");
  cr_assert_gt(test_expect_identical_films(one, two), 0.0, "a black image");
  ss_film_destroy(one);
  ss_film_destroy(two);
}

/* Mean and standard error per channel of n camera samples of the 2 x 2
 * slab view's pixels with the `bssrdf` integrator at a fixed seed; every
 * sample must be finite. */
static inline void test_estimate(const ss_scene *s, int n, uint64_t seed, double mean[3],
                                 double se[3]) {
  const ss_integrator_ops *ops = ss_integrator_find("bssrdf");
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  ss_path_stats stats;
  memset(&stats, 0, sizeof stats);
  for (int i = 0; i < n; ++i) {
    ss_rgb v = ss_render_sample(s, ops, NULL, i % 2, (i / 2) % 2, (uint32_t)(i / 4), seed, &stats);
    for (int c = 0; c < 3; ++c) {
      cr_assert(isfinite(v.c[c]));
      sum[c] += v.c[c];
      sum2[c] += v.c[c] * v.c[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum[c] / n;
    se[c] = sqrt(fmax(sum2[c] / n - mean[c] * mean[c], 0.0) / n);
  }
}

/* Mean and standard error per channel over the 8 x 8 image of n samples per
 * pixel of integrator `ops` with `state`, at a fixed seed; every sample must
 * be finite. */
static inline void test_image_mean(const ss_scene *s, const ss_integrator_ops *ops,
                                   const void *state, int n, uint64_t seed, double mean[3],
                                   double se[3]) {
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  ss_path_stats stats;
  memset(&stats, 0, sizeof stats);
  int count = 0;
  for (int k = 0; k < n; ++k) {
    for (int p = 0; p < 64; ++p, ++count) {
      ss_rgb v = ss_render_sample(s, ops, state, p % 8, p / 8, (uint32_t)k, seed, &stats);
      for (int c = 0; c < 3; ++c) {
        cr_assert(isfinite(v.c[c]), "%s: a non-finite sample", ops->name);
        sum[c] += v.c[c];
        sum2[c] += v.c[c] * v.c[c];
      }
    }
  }
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum[c] / count;
    se[c] = sqrt(fmax(sum2[c] / count - mean[c] * mean[c], 0.0) / count);
  }
}

/* A diffuse square `name` of side `size` and grey albedo at height y, facing
 * +y (up) or -y (down). */
static inline void test_add_diffuse_square(ss_scene *s, const char *name, double size, double y,
                                           double albedo, int up) {
  ss_error err;
  ss_material mat;
  memset(&mat, 0, sizeof mat);
  snprintf(mat.name, sizeof mat.name, "%s", name);
  mat.kind = SS_MATERIAL_DIFFUSE;
  mat.albedo = ss_rgb_gray(albedo);
  mat.medium = -1;
  int m;
  cr_assert_eq(ss_scene_add_material(s, &mat, &m, &err), SS_OK, "%s", err.message);
  ss_mesh *mesh;
  cr_assert_eq(ss_shape_quad(size, size, 1, 1, &mesh, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(mesh,
                                 ss_mat4_mul(ss_mat4_translate(ss_vec3_make(0, y, 0)),
                                             ss_mat4_rotate(up ? -90 : 90, ss_vec3_make(1, 0, 0))),
                                 &err),
               SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, name, mesh, m, NULL, &err), SS_OK, "%s", err.message);
}

/* A 10 x 10 grey (albedo 0.6) floor facing +y at height y. */
static inline void test_add_floor(ss_scene *s, double y) {
  test_add_diffuse_square(s, "floor", 10, y, 0.6, 1);
}

/* The floor at height y, a unit area lamp of radiance 20 facing down from
 * y = 3, and a coloured sky (0.1, 0.2, 0.3). */
static inline void test_add_floor_lamp_sky(ss_scene *s, double y) {
  ss_error err;
  test_add_floor(s, y);
  ss_mesh *lamp;
  cr_assert_eq(ss_shape_quad(1, 1, 1, 1, &lamp, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(lamp,
                                 ss_mat4_mul(ss_mat4_translate(ss_vec3_make(0, 3, 0)),
                                             ss_mat4_rotate(90, ss_vec3_make(1, 0, 0))),
                                 &err),
               SS_OK);
  int lamp_shape;
  cr_assert_eq(ss_scene_add_shape(s, "lamp", lamp, -1, &lamp_shape, &err), SS_OK);
  test_add_light(s, "lamp", SS_LIGHT_AREA, lamp_shape, ss_rgb_gray(20));
  test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_make(0.1, 0.2, 0.3));
}

/* The optics of an isotropic medium `name` (sigma_s, sigma_a), before
 * ss_medium_init (flakes or a grid may be added first). */
static inline ss_medium test_medium(const char *name, ss_rgb sigma_s, ss_rgb sigma_a) {
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "%s", name);
  med.optics.sigma_s = sigma_s;
  med.optics.sigma_a = sigma_a;
  med.optics.phase = SS_PHASE_ISOTROPIC;
  return med;
}

/* An isotropic medium `medium` (sigma_s, sigma_a) and a translucent material
 * `material` enclosing it behind `boundary` of eta 1.3, with BSSRDF model
 * `model` at the level of detail "bssrdf"; returns the material's index. */
static inline int test_add_translucent_as(ss_scene *s, const char *medium, const char *material,
                                          ss_rgb sigma_s, ss_rgb sigma_a, ss_boundary_type boundary,
                                          const char *model) {
  ss_error err;
  ss_medium med = test_medium(medium, sigma_s, sigma_a);
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK);
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "%s", material);
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = boundary;
  m.eta = 1.3;
  cr_assert_eq(ss_scene_add_medium(s, &med, &m.medium, &err), SS_OK, "%s", err.message);
  m.lod = SS_LOD_BSSRDF;
  snprintf(m.bssrdf, sizeof m.bssrdf, "%s", model);
  int index;
  cr_assert_eq(ss_scene_add_material(s, &m, &index, &err), SS_OK, "%s", err.message);
  return index;
}

/* The same, the medium named "medium" and the material "translucent". */
static inline int test_add_translucent(ss_scene *s, ss_rgb sigma_s, ss_rgb sigma_a,
                                       ss_boundary_type boundary, const char *model) {
  return test_add_translucent_as(s, "medium", "translucent", sigma_s, sigma_a, boundary, model);
}

#endif
