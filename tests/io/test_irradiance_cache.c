/* The `hierarchical` integrator's irradiance cache (irradiance_cache.h):
 * every input of pass 1 is in its key, so that changing any one of them
 * makes a cache written before stale (refused with the reason, rebuilt, the
 * points those of a fresh pass 1), while the camera, spp, epsilon and the
 * kernel table reuse it bit for bit; the key covers the placed points
 * themselves (any placement that moves, re-weighs or drops a point), not
 * their order; a cache with the right key whose irradiance is not this
 * pass 1's (another version of the estimator) fails the spot check. */
#include "render/integrators/hierarchical.h"
#include "subsurf/irradiance_cache.h"
#include "subsurf/scene_io.h"

#include "io/io_test_dir.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A dipole sphere on a textured floor under a lamp and a sky. Each %s is
 * one place a variant adds to: camera, medium, material, floor material,
 * floor shape, lamp, integrator, render. */
static const char *const scene_format =
    "{\"camera\": {\"resolution\": [4, 4], \"position\": [0, 1, 4] %s},\n"
    " \"media\": [{\"name\": \"m\", \"sigma_s\": [4, 5, 6] %s}],\n"
    " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"medium\": \"m\" %s},\n"
    "   {\"name\": \"floor\", \"type\": \"diffuse\" %s}],\n"
    " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"t\"},\n"
    "   {\"name\": \"floor\", \"type\": \"quad\", \"width\": 8, \"height\": 8, \"material\": "
    "\"floor\",\n"
    "    \"transform\": {\"rotate\": [1, 0, 0, -90], \"translate\": [0, -1, 0]} %s},\n"
    "   {\"name\": \"lamp\", \"type\": \"sphere\", \"radius\": 0.5, \"center\": [2, 3, 1]}],\n"
    " \"lights\": [{\"name\": \"lamp\", \"type\": \"area\", \"shape\": \"lamp\" %s},\n"
    "   {\"type\": \"environment\", \"radiance\": [0.1, 0.2, 0.3]}],\n"
    " \"integrator\": {\"type\": \"hierarchical\" %s},\n"
    " \"render\": {\"exposure\": 0 %s}}\n";

/* The floor's albedo: a checker texture. */
#define CHECKER(b)                                                                                 \
  ", \"albedo\": {\"texture\": {\"type\": \"checker\", \"a\": [0.2, 0.3, 0.4], \"b\": [" b         \
  ", 0.6, 0.5], \"scale\": 4}}"

/* The integrator's pass-1 options. */
#define PASS1(points, samples) ", \"points\": " #points ", \"irradiance_samples\": " #samples

enum { MEDIUM, MATERIAL, FLOOR, FLOOR_SHAPE, LAMP, INTEGRATOR, RENDER, CAMERA, PLACES };

/* The scene with `text` at place `at` (none when at == PLACES) instead of
 * what is there by default (the medium's sigma_a, the material's model, the floor's
 * albedo, the lamp's radiance, the integrator's pass-1 options). */
static ss_scene *scene_with(int at, const char *text) {
  const char *extra[PLACES];
  for (int i = 0; i < PLACES; ++i) {
    extra[i] = i == at           ? text
               : i == MEDIUM     ? ", \"sigma_a\": [0.5, 0.6, 0.7]"
               : i == MATERIAL   ? ", \"bssrdf\": \"dipole\""
               : i == FLOOR      ? CHECKER("0.6")
               : i == LAMP       ? ", \"radiance\": 5"
               : i == INTEGRATOR ? PASS1(200, 2)
                                 : "";
  }
  char json[4096];
  snprintf(json, sizeof json, scene_format, extra[CAMERA], extra[MEDIUM], extra[MATERIAL],
           extra[FLOOR], extra[FLOOR_SHAPE], extra[LAMP], extra[INTEGRATOR], extra[RENDER]);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(json, "cache.json", NULL, &s, &err), SS_OK, "%s: %s", text,
               err.message);
  cr_assert_eq(ss_subsurface_build(s->subsurface, &err), SS_OK, "%s", err.message);
  return s;
}

/* Pass 1 of the scene with the cache file `path` (NULL: none). */
static ss_hier_state *build(const ss_scene *s, const char *path) {
  ss_hier_options o;
  ss_error err;
  cr_assert_eq(ss_hier_options_read(s, &o, &err), SS_OK, "%s", err.message);
  ss_hier_state *h;
  cr_assert_eq(ss_hier_build(s, &o, 1, path, &h, &err), SS_OK, "%s", err.message);
  return h;
}

static char dir[64];

static void make_dir(void) { io_test_make_dir(dir, sizeof dir, "subsurf-irrcache"); }
static void remove_dir(void) { io_test_remove_dir(dir); }

/* The path of file `name` in the test's directory. */
static void in_dir(char path[128], const char *name) { snprintf(path, 128, "%s/%s", dir, name); }

/* The same points bit for bit, field by field (not the struct's padding). */
static int same_points(const ss_hier_state *a, const ss_hier_state *b) {
  int same = a->num_points == b->num_points;
  for (size_t i = 0; same && i < a->num_points; ++i) {
    const ss_irradiance_point *p = &a->points[i], *q = &b->points[i];
    same = !memcmp(&p->p, &q->p, sizeof p->p) && !memcmp(&p->n, &q->n, sizeof p->n) &&
           !memcmp(&p->area, &q->area, sizeof p->area) && !memcmp(&p->E, &q->E, sizeof p->E) &&
           !memcmp(&p->power, &q->power, sizeof p->power) && p->shape == q->shape;
  }
  return same;
}

TestSuite(irradiance_cache, .init = make_dir, .fini = remove_dir);

Test(irradiance_cache, each_input_of_pass_1_makes_the_cache_stale_and_it_is_rebuilt) {
  char base[128], path[128];
  in_dir(base, "base.irr");
  in_dir(path, "v.irr");
  ss_scene *s = scene_with(PLACES, "");
  ss_hier_destroy(build(s, base));
  ss_scene_destroy(s);
  static const struct {
    int at;
    const char *text;
  } inputs[] = {
      {MEDIUM, ", \"sigma_a\": [0.5, 0.6, 0.7], \"phase\": {\"type\": \"hg\", \"g\": 0.01}"},
      {MEDIUM, ", \"sigma_a\": [0.5, 0.6, 0.71]"},
      {MATERIAL, ", \"bssrdf\": \"dipole\", \"eta\": 1.31"},
      {MATERIAL, ", \"bssrdf\": \"dipole\", \"boundary\": \"rough\", \"alpha\": 0.2"},
      {MATERIAL, ", \"bssrdf\": \"better-dipole\""},
      {MATERIAL, ", \"bssrdf\": \"dipole\", \"single_scattering\": true"},
      {MATERIAL, ", \"bssrdf\": {\"model\": \"multipole\", \"thickness\": 2}"},
      {MATERIAL, ", \"bssrdf\": {\"model\": \"multipole\", \"thickness\": 3}"},
      {FLOOR, ", \"albedo\": [0.2, 0.3, 0.4]"},
      {FLOOR, CHECKER("0.61")},
      {FLOOR_SHAPE, ", \"tessellation\": [2, 1]"},
      {LAMP, ", \"radiance\": 5.5"},
      {INTEGRATOR, PASS1(201, 2)},
      {INTEGRATOR, PASS1(200, 3)},
      {INTEGRATOR, PASS1(200, 2) ", \"max_depth\": 3"},
      {INTEGRATOR, PASS1(200, 2) ", \"rr_depth\": 1"},
      {RENDER, ", \"seed\": 4"},
  };
  for (size_t i = 0; i < sizeof inputs / sizeof inputs[0]; ++i) {
    s = scene_with(inputs[i].at, inputs[i].text);
    io_test_copy_file(base, path);
    ss_error err;
    cr_expect_eq(ss_hierarchical_cache_check(s, path, &err), SS_ERR_PARSE, "%s: accepted",
                 inputs[i].text);
    cr_expect(strstr(err.message, "stale") && strstr(err.message, "v.irr"), "%s: %s",
              inputs[i].text, err.message);
    ss_hier_state *cached = build(s, path), *fresh = build(s, NULL);
    cr_expect(!cached->from_cache, "%s: the stale cache was used", inputs[i].text);
    cr_expect(same_points(cached, fresh), "%s: the rebuilt points differ", inputs[i].text);
    ss_hier_destroy(cached);
    ss_hier_destroy(fresh);
    ss_hier_destroy(build(s, path)); /* the rewritten cache is reused */
    cr_expect_eq(ss_hierarchical_cache_check(s, path, &err), SS_OK, "%s: %s", inputs[i].text,
                 err.message);
    ss_scene_destroy(s);
  }
}

Test(irradiance_cache, camera_spp_epsilon_and_kernel_table_reuse_it_bit_for_bit) {
  char path[128];
  in_dir(path, "c.irr");
  ss_scene *s = scene_with(PLACES, "");
  ss_hier_state *first = build(s, path);
  cr_expect(!first->from_cache);
  ss_scene_destroy(s);
  static const struct {
    int at;
    const char *text;
  } others[] = {
      {CAMERA, ", \"target\": [0.2, 0, 0], \"fov\": 25"},
      {RENDER, ", \"spp\": 7"},
      {INTEGRATOR, PASS1(200, 2) ", \"epsilon\": 0.2"},
      {INTEGRATOR, PASS1(200, 2) ", \"kernel_table\": 0"},
  };
  for (size_t i = 0; i < sizeof others / sizeof others[0]; ++i) {
    s = scene_with(others[i].at, others[i].text);
    ss_hier_state *h = build(s, path);
    cr_expect(h->from_cache, "%s: the cache was not reused", others[i].text);
    cr_expect(same_points(h, first), "%s: the cached points differ", others[i].text);
    ss_hier_destroy(h);
    ss_scene_destroy(s);
  }
  ss_hier_destroy(first);
}

/* The placed points of the scene's pass 1 (placement order, no
 * irradiance) and its pass-1 description. */
static ss_irradiance_point *placed(const ss_scene *s, const ss_hier_state *h,
                                   ss_irradiance_pass1 *p1) {
  ss_irradiance_point *p = malloc(h->num_points * sizeof *p);
  ss_error err;
  cr_assert_eq(ss_poisson_disk_points(s->shapes[0].mesh, 0, h->num_points, h->opt.seed, p, &err),
               SS_OK);
  *p1 = (ss_irradiance_pass1){p, h->num_points, h->eta, h->opt.irradiance_samples, h->opt.seed};
  return p;
}

Test(irradiance_cache, the_key_covers_every_placed_point_but_not_their_order) {
  ss_scene *s = scene_with(PLACES, "");
  ss_hier_state *h = build(s, NULL);
  ss_irradiance_pass1 p1;
  ss_irradiance_point *p = placed(s, h, &p1);
  uint64_t key = ss_irradiance_cache_key(s, &p1);
  size_t n = h->num_points, k = n / 2;
  /* another placement: one coordinate, normal, area or shape changed by the
   * least amount, or a point fewer */
  double *fields[] = {&p[k].p.x, &p[k].p.z, &p[k].n.y, &p[k].area};
  for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f) {
    double was = *fields[f];
    *fields[f] = nextafter(was, 2.0 * was + 1.0);
    cr_expect_neq(ss_irradiance_cache_key(s, &p1), key, "field %zu moved by one ulp", f);
    *fields[f] = was;
  }
  p[k].shape = 1;
  cr_expect_neq(ss_irradiance_cache_key(s, &p1), key, "another shape");
  p[k].shape = 0;
  p1.count = n - 1;
  cr_expect_neq(ss_irradiance_cache_key(s, &p1), key, "a point fewer");
  p1.count = n;
  /* the same points in another order (the octree's) */
  ss_irradiance_point t = p[0];
  p[0] = p[n - 1];
  p[n - 1] = t;
  cr_expect_eq(ss_irradiance_cache_key(s, &p1), key, "the order changed the key");
  cr_expect_eq(
      key,
      ss_irradiance_cache_key(
          s, &(ss_irradiance_pass1){h->points, n, h->eta, h->opt.irradiance_samples, h->opt.seed}),
      "the octree-ordered points with their irradiance have another key");
  free(p);
  ss_hier_destroy(h);
  ss_scene_destroy(s);
}

Test(irradiance_cache, another_estimators_irradiance_under_the_right_key_fails_the_spot_check) {
  char path[128];
  in_dir(path, "c.irr");
  ss_scene *s = scene_with(PLACES, "");
  ss_hier_state *h = build(s, NULL);
  ss_irradiance_pass1 p1;
  ss_irradiance_point *p = placed(s, h, &p1);
  ss_error err;
  cr_assert_eq(ss_irradiance_cache_write(path, s, &p1, h->points, h->num_points, &err), SS_OK);
  ss_irradiance_point *back;
  size_t n;
  cr_assert_eq(ss_irradiance_cache_read(path, s, &p1, &back, &n, &err), SS_OK, "%s", err.message);
  free(back);
  /* the same points, the irradiance off by one ulp at every point (what
   * another version of the estimator writes): key and checksum fine */
  ss_irradiance_point *other = malloc(h->num_points * sizeof *other);
  memcpy(other, h->points, h->num_points * sizeof *other);
  for (size_t i = 0; i < h->num_points; ++i) {
    other[i].E.c[1] = nextafter(other[i].E.c[1], 1.0);
  }
  cr_assert_eq(ss_irradiance_cache_write(path, s, &p1, other, h->num_points, &err), SS_OK);
  cr_expect_eq(ss_irradiance_cache_read(path, s, &p1, &back, &n, &err), SS_ERR_PARSE);
  cr_expect(strstr(err.message, "irradiance differs") && strstr(err.message, "stale"), "%s",
            err.message);
  free(other);
  free(p);
  ss_hier_destroy(h);
  ss_scene_destroy(s);
}
