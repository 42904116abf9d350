/* The `fem` integrator's cache (fem_cache.h): a second prepare of the same
 * scene reads the mesh and the solution (gmsh and the solves skipped) and
 * renders the image of a prepare without the cache bit for bit; each input
 * of a stage makes that stage's record stale (geometry, element size and a
 * grid's size field: the mesh and so the solution; the medium's
 * coefficients, the light, the boundary's eta, irradiance samples, source
 * and solver: the solution alone) and the recomputed image is the one a
 * prepare without the cache gives; the camera reuses both; an empty,
 * truncated, damaged, foreign or other-version file is refused naming the
 * reason, recomputed and rewritten; with cache_read_only the file is read
 * but never written or created. */
#include "render/integrators/fem.h"
#include "subsurf/fem_cache.h"
#include "subsurf/integrator.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include "io/io_test_dir.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

/* A sphere of radius 1 with a smooth boundary in a sky and under a spot
 * light, seen on 6 x 6 pixels. Each %s is where a variant adds to: camera,
 * medium, material, shape, spot light, integrator. The shortest mean free
 * path is channel 0's, so channel 2's sigma_a leaves the mesh alone. */
static const char *const scene_format =
    "{\"camera\": {\"resolution\": [6, 6], \"position\": [0, 1, 4] %s},\n"
    " \"media\": [{\"name\": \"m\", \"sigma_s\": 4 %s}],\n"
    " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"boundary\": \"smooth\",\n"
    "   \"medium\": \"m\" %s}],\n"
    " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"t\" %s}],\n"
    " \"lights\": [{\"type\": \"environment\", \"radiance\": 0.2},\n"
    "   {\"type\": \"spot\", \"position\": [0, 4, 0], \"target\": [0, 0, 0], \"cone_angle\": 30 "
    "%s}],\n"
    " \"integrator\": {\"type\": \"fem\" %s},\n"
    " \"render\": {\"spp\": 1}}\n";

/* The integrator's element size and irradiance samples. */
#define OPTIONS(size, samples) ", \"element_size\": " #size ", \"irradiance_samples\": " #samples

/* The medium's absorption, channel 2's given. */
#define SIGMA_A(blue) ", \"sigma_a\": [0.2, 0.1, " blue "]"

/* The medium with a procedural grid of ring spacing `ring`. */
#define WOOD(ring)                                                                                 \
  SIGMA_A("0.1")                                                                                   \
  ", \"grid\": {\"procedural\": \"wood\", \"resolution\": 8, \"size\": [2.2, 2.2, "                \
  "2.2], \"ring\": " ring ", \"latewood\": 1.5}"

enum { CAMERA, MEDIUM, MATERIAL, SHAPE, LIGHT, INTEGRATOR, PLACES };

static char dir[64];
static void make_dir(void) { io_test_make_dir(dir, sizeof dir, "subsurf-femcache"); }
static void remove_dir(void) { io_test_remove_dir(dir); }

TestSuite(fem_cache, .init = make_dir, .fini = remove_dir);

/* The scene with `text` at place `at` (none when at == PLACES), its cache
 * the file `cache` of the test's directory ("": none). */
static ss_scene *scene_with(int at, const char *text, const char *cache) {
  const char *extra[PLACES];
  for (int i = 0; i < PLACES; ++i) {
    extra[i] = i == at           ? text
               : i == MEDIUM     ? SIGMA_A("0.1")
               : i == LIGHT      ? ", \"intensity\": 20"
               : i == INTEGRATOR ? OPTIONS(2, 1)
                                 : "";
  }
  char integrator[256];
  snprintf(integrator, sizeof integrator, "%s%s%s%s", extra[INTEGRATOR],
           cache[0] ? ", \"cache\": \"" : "", cache, cache[0] ? "\"" : "");
  char json[4096];
  snprintf(json, sizeof json, scene_format, extra[CAMERA], extra[MEDIUM], extra[MATERIAL],
           extra[SHAPE], extra[LIGHT], integrator);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(json, "fem_cache.json", dir, &s, &err), SS_OK, "%s: %s", text,
               err.message);
  return s;
}

typedef struct {
  ss_fem_render_timings t;
  float image[6 * 6 * 3];
} prepared;

/* Prepares the fem integrator on the scene and renders its 6 x 6 pixels
 * (one sample each, fixed streams). */
static prepared run(const ss_scene *s) {
  const ss_integrator_ops *ops = ss_integrator_find("fem");
  void *state = NULL;
  ss_error err;
  cr_assert_eq(ops->prepare(s, &state, &err), SS_OK, "%s", err.message);
  prepared p;
  memset(&p, 0, sizeof p);
  ss_fem_render_timings_of(state, &p.t);
  ss_path_stats stats;
  memset(&stats, 0, sizeof stats);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 6; ++x) {
      ss_rgb c = ss_render_sample(s, ops, state, x, y, 0, 7, &stats);
      for (int k = 0; k < 3; ++k) {
        p.image[3 * (6 * y + x) + k] = (float)c.c[k];
      }
    }
  }
  ops->release(state);
  return p;
}

/* The variant rendered without a cache and with the file `cache`: the same
 * image bit for bit; returns the cached run. */
static prepared run_both(int at, const char *text, const char *cache) {
  ss_scene *s = scene_with(at, text, "");
  prepared fresh = run(s);
  ss_scene_destroy(s);
  s = scene_with(at, text, cache);
  prepared cached = run(s);
  ss_scene_destroy(s);
  cr_expect_eq(fresh.t.meshes_cached + fresh.t.solutions_cached, 0);
  cr_expect(!memcmp(fresh.image, cached.image, sizeof fresh.image),
            "%s: the image with the cache differs from the one without", text);
  return cached;
}

static void in_dir(char path[128], const char *name) { snprintf(path, 128, "%s/%s", dir, name); }

Test(fem_cache, the_second_prepare_reads_mesh_and_solution_and_renders_the_same_image) {
  prepared cold = run_both(PLACES, "", "c.fem");
  cr_expect_eq(cold.t.objects, 1);
  cr_expect_eq(cold.t.meshes_cached, 0);
  cr_expect_eq(cold.t.solutions_cached, 0);
  cr_expect(cold.t.solve_seconds > 0.0);
  prepared warm = run_both(PLACES, "", "c.fem");
  cr_expect_eq(warm.t.meshes_cached, 1, "gmsh ran again");
  cr_expect_eq(warm.t.solutions_cached, 1, "the solves ran again");
  cr_expect_eq(warm.t.solve_seconds, 0.0);
  cr_expect_eq(warm.t.assemble_seconds, 0.0);
  cr_expect_eq(warm.t.tets, cold.t.tets);
  cr_expect(!memcmp(cold.image, warm.image, sizeof cold.image));
}

Test(fem_cache, each_input_makes_its_stage_stale_and_the_camera_reuses_both) {
  char base[128], path[128];
  in_dir(base, "base.fem");
  in_dir(path, "v.fem");
  run_both(PLACES, "", "base.fem");
  static const struct {
    int at;
    const char *text;
    int mesh_reused;
  } inputs[] = {
      {SHAPE, ", \"radius\": 1.01", 0},
      {INTEGRATOR, OPTIONS(1.9, 1), 0},
      {MEDIUM, SIGMA_A("0.11"), 1},
      {MATERIAL, ", \"eta\": 1.4", 1},
      {LIGHT, ", \"intensity\": 21", 1},
      {LIGHT, ", \"intensity\": 20, \"falloff_angle\": 10", 1},
      {INTEGRATOR, OPTIONS(2, 2), 1},
      {INTEGRATOR, OPTIONS(2, 1) ", \"volume_source\": 1", 1},
      {INTEGRATOR, OPTIONS(2, 1) ", \"pcg\": 1", 1},
  };
  for (size_t i = 0; i < sizeof inputs / sizeof inputs[0]; ++i) {
    io_test_copy_file(base, path);
    prepared p = run_both(inputs[i].at, inputs[i].text, "v.fem");
    cr_expect_eq(p.t.meshes_cached, inputs[i].mesh_reused, "%s: mesh %s", inputs[i].text,
                 inputs[i].mesh_reused ? "not reused" : "reused");
    cr_expect_eq(p.t.solutions_cached, 0, "%s: a stale solution was used", inputs[i].text);
  }
  io_test_copy_file(base, path);
  prepared p = run_both(CAMERA, ", \"target\": [0.2, 0, 0], \"fov\": 50", "v.fem");
  cr_expect_eq(p.t.meshes_cached + p.t.solutions_cached, 2, "the camera made the cache stale");
}

/* A grid medium refined by medium_element_size: the size field's lattice
 * is in the mesh's key (another ring spacing, same densities: a new mesh),
 * while without the refinement the mesh does not depend on the grid. */
Test(fem_cache, the_size_field_of_a_grid_is_in_the_mesh_key) {
  static const char *const refine[] = {"", ", \"medium_element_size\": 1.8"};
  for (int r = 0; r < 2; ++r) {
    char base[128], path[128];
    in_dir(base, "base.fem");
    in_dir(path, "v.fem");
    ss_scene *s = scene_with(MEDIUM, WOOD("0.5"), "");
    snprintf(s->integrator.cache, sizeof s->integrator.cache, "%s", base);
    if (r) {
      ss_error err;
      cr_assert_eq(ss_scene_set_integrator_option(s, "medium_element_size", 1.8, &err), SS_OK);
    }
    run(s);
    ss_scene_destroy(s);
    io_test_copy_file(base, path);
    s = scene_with(MEDIUM, WOOD("0.45"), "v.fem");
    if (r) {
      ss_error err;
      cr_assert_eq(ss_scene_set_integrator_option(s, "medium_element_size", 1.8, &err), SS_OK);
    }
    prepared p = run(s);
    ss_scene_destroy(s);
    cr_expect_eq(p.t.meshes_cached, !r, "%s: mesh %s", refine[r], r ? "reused" : "not reused");
    cr_expect_eq(p.t.solutions_cached, 0, "%s: a stale solution was used", refine[r]);
  }
}

/* Overwrites `size` bytes at `offset` of the file (-1: append nothing and
 * truncate to `offset`), then sets its CRC-32 to match when `fix_crc`. */
static void damage(const char *path, long offset, const void *bytes, size_t size, int fix_crc) {
  FILE *f = fopen(path, "r+b");
  cr_assert(f);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  unsigned char *data = malloc((size_t)n);
  fseek(f, 0, SEEK_SET);
  cr_assert_eq(fread(data, 1, (size_t)n, f), (size_t)n);
  fclose(f);
  memcpy(data + offset, bytes, size);
  if (fix_crc) {
    uint32_t crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), data, (uInt)(n - 4));
    memcpy(data + n - 4, &crc, 4);
  }
  f = fopen(path, "wb");
  fwrite(data, 1, (size_t)n, f);
  fclose(f);
  free(data);
}

Test(fem_cache, a_damaged_file_is_refused_with_the_reason_recomputed_and_rewritten) {
  char base[128], path[128];
  in_dir(base, "base.fem");
  in_dir(path, "v.fem");
  run_both(PLACES, "", "base.fem");
  static const struct {
    const char *name, *reason;
  } cases[] = {
      {"empty", "empty"},
      {"truncated", "truncated"},
      {"flipped", "checksum"},
      {"version", "another version"},
      {"code", "another version of the fem code"},
      {"record", "larger than the file"},
      {"nan", "not finite"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    io_test_copy_file(base, path);
    const char *name = cases[i].name;
    uint32_t v = 99;
    uint64_t big = 1ull << 40;
    if (!strcmp(name, "empty")) {
      cr_assert_eq(truncate(path, 0), 0);
    } else if (!strcmp(name, "truncated")) {
      cr_assert_eq(truncate(path, 2000), 0);
    } else if (!strcmp(name, "flipped")) {
      damage(path, 1500, "\x40", 1, 0);
    } else if (!strcmp(name, "version")) {
      damage(path, 8, &v, 4, 1);
    } else if (!strcmp(name, "code")) {
      damage(path, 16, &v, 4, 1);
    } else if (!strcmp(name, "record")) {
      damage(path, 32 + 16, &big, 8, 1); /* the first record's vertex count */
    } else {
      double nan = NAN;
      damage(path, 32 + 32, &nan, 8, 1); /* the first record's first values */
    }
    ss_fem_cache *c = NULL;
    ss_error err;
    cr_expect_eq(ss_fem_cache_read(path, &c, &err), SS_ERR_PARSE, "%s: accepted", name);
    cr_expect(strstr(err.message, cases[i].reason) && strstr(err.message, "v.fem"), "%s: %s", name,
              err.message);
    cr_expect_null(c);
    prepared p = run_both(PLACES, "", "v.fem");
    cr_expect_eq(p.t.meshes_cached + p.t.solutions_cached, 0, "%s: a record was used", name);
    cr_expect_eq(ss_fem_cache_read(path, &c, &err), SS_OK, "%s: not rewritten: %s", name,
                 err.message);
    ss_fem_cache_destroy(c);
  }
}

Test(fem_cache, a_read_only_cache_is_read_but_never_written) {
  char base[128], path[128];
  in_dir(base, "base.fem");
  in_dir(path, "v.fem");
  run_both(PLACES, "", "base.fem");
  io_test_copy_file(base, path);
  size_t n0 = 0, n1 = 0;
  unsigned char *before = io_test_read_file(path, &n0);
  static const char *const read_only = OPTIONS(2, 1) ", \"cache_read_only\": 1";
  prepared p = run_both(INTEGRATOR, read_only, "v.fem");
  cr_expect_eq(p.t.meshes_cached + p.t.solutions_cached, 2, "a valid read-only cache unused");
  prepared q = run_both(INTEGRATOR, OPTIONS(2, 2) ", \"cache_read_only\": 1", "v.fem");
  cr_expect_eq(q.t.meshes_cached, 1);
  cr_expect_eq(q.t.solutions_cached, 0, "a stale solution was used");
  unsigned char *after = io_test_read_file(path, &n1);
  cr_assert(after);
  cr_expect(n0 == n1 && !memcmp(before, after, n0), "the read-only cache was rewritten");
  free(before);
  free(after);
  char missing[128];
  in_dir(missing, "missing.fem");
  prepared r = run_both(INTEGRATOR, read_only, "missing.fem");
  cr_expect_eq(r.t.meshes_cached + r.t.solutions_cached, 0);
  cr_expect_null(io_test_read_file(missing, &n0), "a read-only cache was created");
}

/* Another kind of file (an irradiance cache) is named and not replaced. */
Test(fem_cache, a_foreign_file_is_refused_and_kept) {
  char base[128], path[128];
  in_dir(base, "base.fem");
  in_dir(path, "v.fem");
  run_both(PLACES, "", "base.fem");
  io_test_copy_file(base, path);
  damage(path, 0, "SSIRRCH", 7, 1);
  ss_fem_cache *c = NULL;
  ss_error err;
  cr_expect_eq(ss_fem_cache_read(path, &c, &err), SS_ERR_PARSE);
  cr_expect(strstr(err.message, "not an fem cache"), "%s", err.message);
  cr_expect_eq(ss_fem_cache_write(path, NULL, 0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "v.fem") && strstr(err.message, "is not an fem cache"), "%s",
            err.message);
  size_t n = 0;
  unsigned char *data = io_test_read_file(path, &n);
  cr_assert_not_null(data);
  cr_expect_eq(memcmp(data, "SSIRRCH", 7), 0, "the file is kept");
  free(data);
}
