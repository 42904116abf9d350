/* Images are a function of the scene and the seed only: bit-identical for
 * 1 and 2 threads and for a crop window versus the full frame. */
#include "render/scene_builder.h"

#include <criterion/criterion.h>

#include "subsurf/render.h"
#include "subsurf/scene.h"

#include <stdio.h>
#include <string.h>

/* A chromatic translucent sphere (rough boundary) on a diffuse floor, lit
 * by an area light and a sky: every code path of volpath runs. */
static ss_scene *build_scene(void) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  test_sphere_view(s, 24, 20);
  s->camera.filter = ss_filter_default(SS_FILTER_GAUSSIAN);
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "jelly");
  med.optics.sigma_s = ss_rgb_make(4, 2, 1);
  med.optics.sigma_a = ss_rgb_make(0.1, 0.3, 0.6);
  med.optics.phase = SS_PHASE_HG;
  med.optics.g = ss_rgb_gray(0.3);
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK);
  int mi;
  cr_assert_eq(ss_scene_add_medium(s, &med, &mi, &err), SS_OK, "%s", err.message);
  ss_material jelly;
  memset(&jelly, 0, sizeof jelly);
  snprintf(jelly.name, sizeof jelly.name, "jelly");
  jelly.kind = SS_MATERIAL_INTERFACE;
  jelly.boundary = SS_BOUNDARY_ROUGH;
  jelly.eta = 1.4;
  jelly.mf.type = SS_MICROFACET_GGX;
  jelly.mf.alpha = 0.3;
  jelly.medium = mi;
  int m_jelly;
  cr_assert_eq(ss_scene_add_material(s, &jelly, &m_jelly, &err), SS_OK, "%s", err.message);
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(1.0, 3, &sphere, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", sphere, m_jelly, NULL, &err), SS_OK, "%s",
               err.message);
  test_add_floor_lamp_sky(s, -1.0);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

/* The scene's render options with the spp, threads and seed given, and the
 * crop window unless NULL. */
static ss_render_options options(const ss_scene *s, int spp, int threads, uint64_t seed,
                                 const int crop[4]) {
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  o.seed = seed;
  o.threads = threads;
  if (crop) {
    memcpy(o.crop, crop, sizeof o.crop);
  }
  return o;
}

static ss_film *render(const ss_scene *s, int threads, uint64_t seed, const int crop[4]) {
  ss_render_options o = options(s, 3, threads, seed, crop);
  ss_film *film;
  ss_render_stats stats;
  ss_error err;
  cr_assert_eq(ss_render(s, &o, &film, &stats, &err), SS_OK, "%s", err.message);
  cr_assert_eq(stats.min_spp, 3);
  if (!strcmp(s->integrator.name, "volpath")) {
    cr_assert_gt(stats.work.scatter_events, 0);
  }
  return film;
}

static int same_pixels(const ss_film *a, int ax, int ay, const ss_film *b, int w, int h) {
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_rgb pa = ss_film_pixel_mean(a, x + ax, y + ay), pb = ss_film_pixel_mean(b, x, y);
      if (memcmp(&pa, &pb, sizeof pa) != 0) {
        return 0;
      }
    }
  }
  return 1;
}

Test(determinism, one_and_two_threads_give_bit_identical_images) {
  ss_scene *s = build_scene();
  s->integrator.max_depth = 1000;
  const char *integrators[] = {"volpath", "path"};
  for (int i = 0; i < 2; ++i) {
    snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrators[i]);
    ss_film *one = render(s, 1, 5, NULL), *two = render(s, 2, 5, NULL);
    cr_expect(same_pixels(one, 0, 0, two, 24, 20), "%s: 1 vs 2 threads differ", integrators[i]);
    ss_film *other = render(s, 2, 6, NULL);
    cr_expect(!same_pixels(one, 0, 0, other, 24, 20), "%s: the seed changes nothing",
              integrators[i]);
    ss_film_destroy(one);
    ss_film_destroy(two);
    ss_film_destroy(other);
  }
  ss_scene_destroy(s);
}

/* The threads that rendered a one-sample render of the 24 x 20 image (2 x 2
 * tiles), or of its tiles t with t % stride == offset. */
static int threads_rendering(const ss_scene *s, int threads, int stride, int offset,
                             const int crop[4]) {
  ss_render_options o = options(s, 1, threads, 1, crop);
  o.tile_stride = stride;
  o.tile_offset = offset;
  ss_film *film;
  ss_render_stats stats;
  ss_error err;
  cr_assert_eq(ss_render(s, &o, &film, &stats, &err), SS_OK, "%s", err.message);
  ss_film_destroy(film);
  return stats.threads;
}

/* Each thread of the team, min(threads, tiles), renders a tile: a dynamic
 * hand-out alone let thread 0 take every tile of a small image in some
 * runs. */
Test(determinism, every_thread_of_the_team_renders_and_is_counted) {
  ss_scene *s = build_scene();
  for (int run = 0; run < 10; ++run) {
    cr_expect_eq(threads_rendering(s, 1, 0, 0, NULL), 1);
    cr_expect_eq(threads_rendering(s, 2, 0, 0, NULL), 2);
    cr_expect_eq(threads_rendering(s, 3, 0, 0, NULL), 3);
    cr_expect_eq(threads_rendering(s, 8, 0, 0, NULL), 4, "4 tiles, 4 threads at the most");
  }
  const int one_tile[4] = {2, 2, 18, 18};
  cr_expect_eq(threads_rendering(s, 2, 0, 0, one_tile), 1);
  cr_expect_eq(threads_rendering(s, 2, 2, 1, NULL), 2, "tiles 1 and 3");
  cr_expect_eq(threads_rendering(s, 2, 3, 2, NULL), 1, "tile 2 alone");
  cr_expect_eq(threads_rendering(s, 2, 5, 4, NULL), 0, "no tile");
  ss_scene_destroy(s);
}

Test(determinism, crop_window_equals_the_same_pixels_of_the_full_image) {
  ss_scene *s = build_scene();
  const int crop[4] = {5, 3, 19, 17};
  ss_film *full = render(s, 2, 1, NULL), *part = render(s, 2, 1, crop);
  cr_expect_eq(ss_film_width(part), 14);
  cr_expect_eq(ss_film_height(part), 14);
  cr_expect(same_pixels(full, 5, 3, part, 14, 14));
  ss_film_destroy(full);
  ss_film_destroy(part);
  ss_scene_destroy(s);
}
