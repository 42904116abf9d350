/* Nested and touching media in volpath (SchmidtBudge2002 priorities,
 * docs/render.md): a medium nested in or overlapping the same medium renders
 * as the single medium, the union of two overlapping regions as one mesh of
 * that shape, and a true interface between two regions reflects with the
 * Fresnel factor of both indices. The stack rules themselves are checked on
 * the functions volpath uses. Monte Carlo comparisons: 4 standard errors. */
#include "render/integrators/medium_stack.h"
#include "render/scene_builder.h"
#include "subsurf/fresnel.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static ss_scene *parse(const char *text, const char *dir) {
  ss_scene *s = NULL;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(text, "nested.json", dir, &s, &err), SS_OK, "%s\n%s",
               err.message, text);
  return s;
}

/* Renders both scenes (n samples per pixel of 8 x 8) and expects equal means. */
static void expect_equal_images(const char *a, const char *b, const char *dir, int n) {
  ss_scene *sa = parse(a, dir), *sb = parse(b, dir);
  cr_assert(sa->nested_material < 0 && sb->nested_material >= 0);
  double ma[3], ea[3], mb[3], eb[3];
  test_image_mean(sa, ss_integrator_find("volpath"), NULL, n, 1, ma, ea);
  test_image_mean(sb, ss_integrator_find("volpath"), NULL, n, 2, mb, eb);
  for (int c = 0; c < 3; ++c) {
    double tol = 4.0 * sqrt(ea[c] * ea[c] + eb[c] * eb[c]);
    cr_expect(ma[c] > 0.0 && fabs(ma[c] - mb[c]) <= tol,
              "channel %d: single %.5f +- %.5f, nested %.5f +- %.5f", c, ma[c], ea[c], mb[c],
              eb[c]);
  }
  ss_scene_destroy(sa);
  ss_scene_destroy(sb);
}

/* A chromatic medium "m", materials "a" and "b" of that medium behind
 * BOUNDARY (priorities 1 and 2), a camera and LIGHTS, then the shapes. */
#define HEAD(boundary, lights)                                                                     \
  "{\"camera\": {\"position\": [1, 2, 5], \"target\": [0, 0, 0], \"fov\": 35,\n"                   \
  "  \"resolution\": [8, 8]},\n"                                                                   \
  " \"media\": [{\"name\": \"m\", \"sigma_s\": [2, 1.5, 1], \"sigma_a\": [0.2, 0.3, 0.5]}],\n"     \
  " \"materials\": [\n"                                                                            \
  "  {\"name\": \"a\", \"type\": \"translucent\", \"medium\": \"m\", " boundary                    \
  ", \"priority\": 1},\n"                                                                          \
  "  {\"name\": \"b\", \"type\": \"translucent\", \"medium\": \"m\", " boundary                    \
  ", \"priority\": 2}],\n"                                                                         \
  " \"lights\": [" lights "],\n"                                                                   \
  " \"shapes\": [\n"

#define SMOOTH "\"boundary\": \"smooth\", \"eta\": 1.3"
#define MATCHED "\"boundary\": \"index-matched\""
#define SKY "{\"type\": \"environment\", \"radiance\": [1, 0.8, 0.6]}"
#define LAMP "{\"type\": \"point\", \"position\": [3, 3, 2], \"intensity\": 40}"

#define SPHERE(mat, r)                                                                             \
  "{\"type\": \"sphere\", \"subdivisions\": 3, \"material\": \"" mat "\", \"radius\": " #r "}"

Test(nested_media, an_equal_medium_nested_inside_equals_the_single_medium) {
  /* Inner of higher priority: true interfaces of one index (no event);
   * inner of lower priority: false interfaces. Smooth boundaries under a
   * sky, and index-matched ones lit by a point light (shadow rays from
   * inside through the nested boundary). */
  static const char *single[] = {HEAD(SMOOTH, SKY) SPHERE("a", 1) "]}",
                                 HEAD(MATCHED, LAMP) SPHERE("a", 1) "]}"};
  static const char *nested[][2] = {{HEAD(SMOOTH, SKY) SPHERE("a", 1) ",\n" SPHERE("b", 0.6) "]}",
                                     HEAD(SMOOTH, SKY) SPHERE("b", 1) ",\n" SPHERE("a", 0.6) "]}"},
                                    {HEAD(MATCHED, LAMP) SPHERE("a", 1) ",\n" SPHERE("b", 0.6) "]}",
                                     HEAD(MATCHED, LAMP)
                                         SPHERE("b", 1) ",\n" SPHERE("a", 0.6) "]}"}};
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      expect_equal_images(single[k], nested[k][j], NULL, 320);
    }
  }
}

/* Manifold NEE in nested scenes (docs/render.md): a smooth sphere under a
 * sphere light, and the same with an equal medium nested inside, whose
 * vertices reach the lamp through the outer boundary past the inner
 * sphere's surfaces (index-matching interfaces between the two regions),
 * by MNEE and phase sampling combined; both means agree. */
Test(nested_media, a_nested_scene_under_a_lamp_equals_the_single_medium) {
#define AREA "{\"type\": \"area\", \"shape\": \"lamp\", \"radiance\": 4}"
#define LAMP_SHAPE                                                                                 \
  "{\"name\": \"lamp\", \"type\": \"sphere\", \"subdivisions\": 2, \"radius\": 1.5, "              \
  "\"center\": [3, 3, 2]}"
  static const char *single = HEAD(SMOOTH, AREA) SPHERE("a", 1) ",\n" LAMP_SHAPE "]}";
  static const char *nested =
      HEAD(SMOOTH, AREA) SPHERE("a", 1) ",\n" SPHERE("b", 0.6) ",\n" LAMP_SHAPE "]}";
#undef AREA
#undef LAMP_SHAPE
  expect_equal_images(single, nested, NULL, 320);
}

/* Writes triangle (a, b, c) of the 1-based vertices v, wound so that its
 * normal points along `out`. */
static void triangle(FILE *f, double v[][3], int a, int b, int c, const double out[3]) {
  double e1[3], e2[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = v[b - 1][k] - v[a - 1][k];
    e2[k] = v[c - 1][k] - v[a - 1][k];
  }
  double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
  int flip = n[0] * out[0] + n[1] * out[1] + n[2] * out[2] < 0.0;
  fprintf(f, "f %d %d %d\n", a, flip ? c : b, flip ? b : c);
}

/* Writes a closed, outward OBJ of the union of boxes [-1, 0.05] x [-0.4,
 * 0.4]^2 and [-0.05, 1] x [-0.6, 0.6]^2 (the small box's sides meet the big
 * box's face x = -0.05 around a square hole). */
static void write_union_obj(const char *path) {
  FILE *f = fopen(path, "w");
  cr_assert(f);
  /* Rings of four vertices: the small box at x = -1 (1-4) and x = -0.05
   * (5-8), the big box at x = -0.05 (9-12) and x = 1 (13-16), each in the
   * order (y, z) = (-,-), (+,-), (+,+), (-,+). */
  const double xs[4] = {-1, -0.05, -0.05, 1}, hs[4] = {0.4, 0.4, 0.6, 0.6};
  const int sy[4] = {-1, 1, 1, -1}, sz[4] = {-1, -1, 1, 1};
  double v[16][3];
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) {
      v[4 * r + k][0] = xs[r];
      v[4 * r + k][1] = sy[k] * hs[r];
      v[4 * r + k][2] = sz[k] * hs[r];
      fprintf(f, "v %g %g %g\n", v[4 * r + k][0], v[4 * r + k][1], v[4 * r + k][2]);
    }
  }
  const double minus_x[3] = {-1, 0, 0}, plus_x[3] = {1, 0, 0};
  triangle(f, v, 1, 2, 3, minus_x);
  triangle(f, v, 1, 3, 4, minus_x);
  triangle(f, v, 13, 14, 15, plus_x);
  triangle(f, v, 13, 15, 16, plus_x);
  /* Between rings r0 and r1: the sides of each box (outward from the axis,
   * along the side's mid-point), and the annulus facing -x. */
  const int rings[3][2] = {{1, 5}, {9, 13}, {5, 9}};
  for (int s = 0; s < 3; ++s) {
    for (int k = 0; k < 4; ++k) {
      int a = rings[s][0] + k, b = rings[s][0] + (k + 1) % 4;
      int c = rings[s][1] + (k + 1) % 4, d = rings[s][1] + k;
      double out[3] = {0, (sy[k] + sy[(k + 1) % 4]) / 2.0, (sz[k] + sz[(k + 1) % 4]) / 2.0};
      const double *o = s == 2 ? minus_x : out;
      triangle(f, v, a, b, c, o);
      triangle(f, v, a, c, d, o);
    }
  }
  fclose(f);
}

Test(nested_media, a_touching_pair_of_equal_media_equals_their_union) {
  char dir[] = "/tmp/subsurf-nested-XXXXXX";
  cr_assert(mkdtemp(dir));
  char obj[256];
  snprintf(obj, sizeof obj, "%s/union.obj", dir);
  write_union_obj(obj);
#define PAIR                                                                                       \
  "{\"type\": \"cube\", \"material\": \"a\", \"size\": [1.05, 0.8, 0.8],\n"                        \
  "  \"transform\": {\"translate\": [-0.475, 0, 0]}},\n"                                           \
  " {\"type\": \"cube\", \"material\": \"b\", \"size\": [1.05, 1.2, 1.2],\n"                       \
  "  \"transform\": {\"translate\": [0.475, 0, 0]}}]}"
#define UNION "{\"type\": \"mesh\", \"file\": \"union.obj\", \"material\": \"a\"}]}"
  expect_equal_images(HEAD(SMOOTH, SKY) UNION, HEAD(SMOOTH, SKY) PAIR, dir, 320);
  expect_equal_images(HEAD(MATCHED, LAMP) UNION, HEAD(MATCHED, LAMP) PAIR, dir, 320);
  unlink(obj);
  rmdir(dir);
}

/* Lossless reflectors a and b in series, light bouncing between them
 * incoherently: R = a + (1 - a)^2 b / (1 - a b). */
static double in_series(double a, double b) { return (a + b - 2.0 * a * b) / (1.0 - a * b); }

/* Straight down through a glass slab (eta 1.5, z in [-1, 1]) holding a slab
 * of index n2 (z in [-0.5, 0.5]) above a black floor under a white sky: the
 * pixel sees the reflectance of the four interfaces at normal incidence. */
static double layered_reflectance(double n2, double *se) {
  char text[2048];
  snprintf(text, sizeof text,
           "{\"camera\": {\"position\": [0, 0, 10], \"target\": [0, 0, 0], \"fov\": 1,\n"
           "  \"resolution\": [8, 8]},\n"
           " \"materials\": [{\"name\": \"glass\", \"type\": \"dielectric\", \"eta\": 1.5,\n"
           "   \"priority\": 1},\n"
           "  {\"name\": \"inner\", \"type\": \"dielectric\", \"eta\": %.17g, \"priority\": 2}],\n"
           " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
           " \"shapes\": [{\"type\": \"cube\", \"material\": \"glass\", \"size\": [6, 6, 2]},\n"
           "  {\"type\": \"cube\", \"material\": \"inner\", \"size\": [4, 4, 1]},\n"
           "  {\"type\": \"quad\", \"width\": 40, \"height\": 40,\n"
           "   \"transform\": {\"translate\": [0, 0, -3]}}]}",
           n2);
  ss_scene *s = parse(text, NULL);
  double mean[3], e[3];
  test_image_mean(s, ss_integrator_find("volpath"), NULL, 625, 3, mean, e);
  ss_scene_destroy(s);
  *se = e[0];
  return mean[0];
}

Test(nested_media, an_interface_between_two_media_uses_both_indices) {
  const double n2[2] = {1.5, 2.2};
  for (int k = 0; k < 2; ++k) {
    double outer = ss_fresnel_dielectric(1.0, 1.5), inner = ss_fresnel_dielectric(1.0, n2[k] / 1.5);
    double expected = in_series(in_series(in_series(outer, inner), inner), outer);
    double se, r = layered_reflectance(n2[k], &se);
    cr_expect(fabs(r - expected) <= 4.0 * se + 1e-4, "n2 %g: R %.5f +- %.5f, expected %.5f", n2[k],
              r, se, expected);
  }
  /* Index matched inside: no reflection at the inner interface at all. */
  cr_expect_eq(ss_fresnel_dielectric(1.0, 1.5 / 1.5), 0.0);
}

Test(nested_media, the_region_of_highest_priority_owns_the_point) {
  ss_scene *s = parse(HEAD(SMOOTH, SKY) SPHERE("a", 1) ",\n" SPHERE("b", 0.6) "]}", NULL);
  s->materials[1].eta = 1.6;
  ss_medium_stack st = {0, {0}};
  double eta;
  /* Vacuum -> a: true, eta 1.3. */
  cr_assert_eq(ss_medium_stack_cross(s, &st, 0, 1, &eta), SS_CROSSING_TRUE);
  cr_assert_float_eq(eta, 1.3, 1e-15);
  /* a -> b (higher priority): true, between both indices. */
  cr_assert_eq(ss_medium_stack_cross(s, &st, 1, 1, &eta), SS_CROSSING_TRUE);
  cr_assert_float_eq(eta, 1.6 / 1.3, 1e-15);
  /* Leaving a while inside b: false; entering a again: false. */
  cr_assert_eq(ss_medium_stack_cross(s, &st, 0, 0, &eta), SS_CROSSING_FALSE);
  cr_assert_eq(ss_medium_stack_cross(s, &st, 0, 1, &eta), SS_CROSSING_FALSE);
  cr_assert_eq(ss_medium_stack_top(s, &st), 1);
  /* Leaving b into a: the normal's inside is b's. */
  cr_assert_eq(ss_medium_stack_cross(s, &st, 1, 0, &eta), SS_CROSSING_TRUE);
  cr_assert_float_eq(eta, 1.6 / 1.3, 1e-15);
  /* Leaving b again is a lost path; leaving a reaches vacuum. */
  cr_assert_eq(ss_medium_stack_cross(s, &st, 1, 0, &eta), SS_CROSSING_LOST);
  cr_assert_eq(ss_medium_stack_cross(s, &st, 0, 0, &eta), SS_CROSSING_TRUE);
  cr_assert_eq(st.n, 0);
  /* A full stack loses the path. */
  for (int k = 0; k < SS_MEDIUM_STACK_SIZE; ++k) {
    ss_medium_stack_cross(s, &st, 0, 1, &eta);
  }
  cr_assert_eq(ss_medium_stack_cross(s, &st, 0, 1, &eta), SS_CROSSING_LOST);
  ss_scene_destroy(s);
}
