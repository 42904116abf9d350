/* Textured materials in renders: a texture that is constant renders
 * bit-identically to the constant parameter (so untextured scenes are what
 * they were), and textured renders are finite and independent of the
 * thread count. */
#include "render/scene_builder.h"

#include <criterion/criterion.h>

#include "subsurf/render.h"
#include "subsurf/scene.h"
#include "subsurf/scene_io.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A diffuse floor (albedo ALBEDO), a rough glass sphere (alpha ALPHA) and a
 * translucent rough sphere (alpha ALPHA) under a lamp and a sky. The wax has
 * no energy compensation, which textured roughness does not get. */
/* Two tiles, so that 2 threads share them (test_render). */
enum { W = 20, H = 10 };

static ss_scene *load(const char *integrator, const char *albedo, const char *alpha) {
  char text[4096];
  snprintf(text, sizeof text,
           "{\"camera\": {\"position\": [0, 1.5, 5], \"target\": [0, 0.3, 0], \"fov\": 40, "
           "\"resolution\": [%d, %d]},\n"
           "\"materials\": [\n"
           " {\"name\": \"floor\", \"type\": \"diffuse\", \"albedo\": %s},\n"
           " {\"name\": \"glass\", \"type\": \"roughdielectric\", \"alpha\": %s},\n"
           " {\"name\": \"wax\", \"type\": \"translucent\", \"boundary\": \"rough\", \"alpha\": "
           "%s, \"medium\": {\"sigma_s\": [3, 2, 1], \"sigma_a\": [0.05, 0.1, 0.2]}, "
           "\"bssrdf\": \"dipole\", \"energy_compensation\": false}],\n"
           "\"shapes\": [\n"
           " {\"type\": \"quad\", \"width\": 8, \"height\": 8, \"material\": \"floor\", "
           "\"transform\": {\"rotate\": [1, 0, 0, -90]}},\n"
           " {\"type\": \"sphere\", \"subdivisions\": 3, \"material\": \"glass\", "
           "\"transform\": {\"translate\": [-1.1, 1, 0]}},\n"
           " {\"type\": \"sphere\", \"subdivisions\": 3, \"material\": \"wax\", "
           "\"transform\": {\"translate\": [1.1, 1, 0]}},\n"
           " {\"name\": \"lamp\", \"type\": \"quad\", \"transform\": {\"rotate\": [1, 0, 0, 90], "
           "\"translate\": [0, 4, 0]}}],\n"
           "\"lights\": [{\"type\": \"area\", \"shape\": \"lamp\", \"radiance\": 8}, "
           "{\"type\": \"environment\", \"radiance\": 0.2}],\n"
           "\"integrator\": {\"type\": \"%s\"}}\n",
           W, H, albedo, alpha, alpha, integrator);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(text, "t.json", ".", &s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_film *render(const ss_scene *s, int threads, int spp) {
  return test_render(s, spp, 7, threads, NULL);
}

/* Compares two films pixel by pixel: bit-identical, or (exact = 0) only
 * checks that a is finite. Returns the mean of a's red channel. */
static double compare(const ss_film *a, const ss_film *b, int w, int h) {
  double sum = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_rgb pa = ss_film_pixel_mean(a, x, y);
      cr_assert(ss_rgb_is_finite(pa), "pixel (%d, %d) is not finite", x, y);
      if (b) {
        ss_rgb pb = ss_film_pixel_mean(b, x, y);
        cr_assert_eq(memcmp(&pa, &pb, sizeof pa), 0, "pixel (%d, %d) differs", x, y);
      }
      sum += pa.c[0];
    }
  }
  return sum / (w * h);
}

Test(texture_render, a_constant_texture_renders_bit_identically_to_the_constant) {
  const char *const integrators[] = {"path", "volpath", "bssrdf"};
  for (int k = 0; k < 3; ++k) {
    ss_scene *plain = load(integrators[k], "[0.5, 0.25, 0.75]", "0.3");
    ss_scene *tex = load(integrators[k],
                         "{\"texture\": {\"type\": \"checker\", \"a\": [0.5, 0.25, 0.75], "
                         "\"b\": [0.5, 0.25, 0.75], \"scale\": 5}}",
                         "{\"texture\": {\"type\": \"noise\", \"a\": 0.3, \"b\": 0.3}}");
    ss_film *a = render(plain, 1, 2), *b = render(tex, 1, 2);
    double mean = compare(a, b, W, H);
    cr_assert_gt(mean, 0.0, "%s renders something", integrators[k]);
    ss_film_destroy(a);
    ss_film_destroy(b);
    ss_scene_destroy(plain);
    ss_scene_destroy(tex);
  }
}

Test(texture_render, textured_renders_are_finite_and_the_same_for_1_and_2_threads) {
  const char *const integrators[] = {"path", "volpath", "bssrdf"};
  for (int k = 0; k < 3; ++k) {
    ss_scene *s = load(integrators[k],
                       "{\"texture\": {\"type\": \"checker\", \"a\": 0.1, \"b\": 0.9, \"scale\": "
                       "4}}",
                       "{\"texture\": {\"type\": \"noise\", \"a\": 0.0, \"b\": 0.6, \"space\": "
                       "\"world\", \"scale\": 3}}");
    test_expect_thread_independent(s, 2, 7);
    ss_scene_destroy(s);
  }
}

Test(texture_render, the_checker_shows_on_the_floor) {
  /* Two renders whose floor checker has swapped colours: their sum is the
   * render of the average floor, and they differ pixel by pixel. */
  ss_scene *s1 =
      load("path", "{\"texture\": {\"type\": \"checker\", \"a\": 0.1, \"b\": 0.9}}", "0.3");
  ss_scene *s2 =
      load("path", "{\"texture\": {\"type\": \"checker\", \"a\": 0.9, \"b\": 0.1}}", "0.3");
  ss_film *a = render(s1, 2, 1), *b = render(s2, 2, 1);
  int differ = 0;
  for (int y = H / 2; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      ss_rgb pa = ss_film_pixel_mean(a, x, y), pb = ss_film_pixel_mean(b, x, y);
      differ += fabs(pa.c[0] - pb.c[0]) > 1e-3;
    }
  }
  cr_assert_gt(differ, 20, "the floor's pixels follow the checker (%d differ)", differ);
  ss_film_destroy(a);
  ss_film_destroy(b);
  ss_scene_destroy(s1);
  ss_scene_destroy(s2);
}
