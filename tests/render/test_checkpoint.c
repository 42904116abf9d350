/* Render checkpoints: a film saved and read back is bit-identical, a render
 * resumed from one (stopped between passes or in the middle of one) ends
 * with exactly the pixels of an uninterrupted render, and a damaged or
 * foreign checkpoint is refused with a message naming what is wrong. */
#include <criterion/criterion.h>

#include "subsurf/checkpoint.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define SPP 12

static char dir[64], scene_path[128], ck_path[128];

static void setup(void) {
  snprintf(dir, sizeof dir, "/tmp/subsurf-ckpt-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
  snprintf(scene_path, sizeof scene_path, "%s/scene.json", dir);
  snprintf(ck_path, sizeof ck_path, "%s/render.ckpt", dir);
  FILE *f = fopen(scene_path, "w");
  cr_assert_not_null(f);
  fputs("{\"stands for\": \"the scene built below\"}\n", f);
  fclose(f);
}

static void teardown(void) {
  remove(scene_path);
  remove(ck_path);
  rmdir(dir);
}

TestSuite(checkpoint, .init = setup, .fini = teardown);

/* A grey diffuse sphere under a sky, 13 x 9 pixels (tiles cut the edges). */
static ss_scene *build_scene(void) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  s->camera.width = 13;
  s->camera.height = 9;
  s->camera.position = ss_vec3_make(0, 0, 4);
  s->camera.fov_deg = 30;
  snprintf(s->integrator.name, sizeof s->integrator.name, "path");
  ss_material grey;
  memset(&grey, 0, sizeof grey);
  snprintf(grey.name, sizeof grey.name, "grey");
  grey.kind = SS_MATERIAL_DIFFUSE;
  grey.albedo = ss_rgb_make(0.8, 0.5, 0.2);
  grey.medium = -1;
  int m;
  cr_assert_eq(ss_scene_add_material(s, &grey, &m, &err), SS_OK, "%s", err.message);
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(1.0, 2, &sphere, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", sphere, m, NULL, &err), SS_OK, "%s", err.message);
  ss_light sky;
  memset(&sky, 0, sizeof sky);
  snprintf(sky.name, sizeof sky.name, "sky");
  sky.type = SS_LIGHT_ENVIRONMENT;
  sky.shape = -1;
  sky.value = ss_rgb_make(1.0, 0.7, 0.4);
  cr_assert_eq(ss_scene_add_light(s, &sky, NULL, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static void options(const ss_scene *s, int spp, ss_render_options *o) {
  ss_render_options_from_scene(s, o);
  o->spp = spp;
  o->seed = 9;
  o->threads = 2;
}

static ss_film *render(const ss_scene *s, ss_render_options *o, ss_status expect) {
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_error err;
  cr_assert_eq(ss_render(s, o, &film, &stats, &err), expect, "%s", err.message);
  return film;
}

static int same_film(const ss_film *a, const ss_film *b) {
  for (int y = 0; y < ss_film_height(a); ++y) {
    for (int x = 0; x < ss_film_width(a); ++x) {
      ss_film_pixel_state pa, pb;
      ss_film_get_pixel_state(a, x, y, &pa);
      ss_film_get_pixel_state(b, x, y, &pb);
      if (memcmp(&pa, &pb, sizeof pa) != 0) {
        return 0;
      }
    }
  }
  return 1;
}

static ss_checkpoint_key key_of(const ss_scene *s, const ss_render_options *o) {
  ss_checkpoint_key k;
  ss_error err;
  cr_assert_eq(ss_checkpoint_key_init(&k, scene_path, s, o, &err), SS_OK, "%s", err.message);
  return k;
}

static ss_film *read_back(const ss_checkpoint_key *k) {
  ss_film *film = NULL;
  ss_error err;
  cr_assert_eq(ss_checkpoint_read(ck_path, k, &film, &err), SS_OK, "%s", err.message);
  return film;
}

/* Between passes: the callback stops the render at its third call (the
 * start of pass 3) after saving the film. */
typedef struct {
  const ss_checkpoint_key *key;
  volatile sig_atomic_t cancel;
  int calls;
} stopper;

static void save_and_stop(void *ctx, const ss_film *film) {
  stopper *st = ctx;
  ss_error err;
  cr_assert_eq(ss_checkpoint_write(ck_path, st->key, film, &err), SS_OK, "%s", err.message);
  if (++st->calls == 3) {
    st->cancel = 1;
  }
}

Test(checkpoint, resuming_between_passes_gives_the_uninterrupted_image) {
  ss_scene *s = build_scene();
  ss_render_options o;
  options(s, SPP, &o);
  ss_film *full = render(s, &o, SS_OK);
  ss_checkpoint_key k = key_of(s, &o);
  stopper st = {&k, 0, 0};
  o.checkpoint = save_and_stop;
  o.checkpoint_ctx = &st;
  o.checkpoint_interval = 0.0;
  o.cancel = &st.cancel;
  ss_film *stopped = render(s, &o, SS_ERR_INTERRUPTED);
  cr_expect_eq(ss_film_min_drawn(stopped), 3);
  ss_film *saved = read_back(&k);
  cr_expect(same_film(saved, stopped), "the checkpoint differs from the film it saved");
  ss_film_destroy(stopped);
  options(s, SPP, &o);
  o.resume = saved;
  o.threads = 1;
  ss_film *resumed = render(s, &o, SS_OK);
  cr_expect(same_film(resumed, full), "resumed image differs from the uninterrupted one");
  ss_film_destroy(resumed);
  ss_film_destroy(full);
  ss_scene_destroy(s);
}

/* In the middle of a pass some pixels hold one sample more than others: the
 * film of a render stopped there equals, pixel by pixel, a 4-spp or a 5-spp
 * render (each pixel accumulates alone). */
Test(checkpoint, resuming_in_the_middle_of_a_pass_gives_the_uninterrupted_image) {
  ss_scene *s = build_scene();
  ss_render_options o;
  options(s, 4, &o);
  ss_film *mixed = render(s, &o, SS_OK);
  options(s, 5, &o);
  ss_film *ahead = render(s, &o, SS_OK);
  for (int y = 0; y < ss_film_height(mixed); ++y) {
    for (int x = 0; x < ss_film_width(mixed); ++x) {
      if ((x * 7 + y * 3) % 5 < 2) {
        ss_film_pixel_state p;
        ss_film_get_pixel_state(ahead, x, y, &p);
        ss_film_set_pixel_state(mixed, x, y, &p);
      }
    }
  }
  ss_film_destroy(ahead);
  options(s, SPP, &o);
  ss_film *full = render(s, &o, SS_OK);
  ss_checkpoint_key k = key_of(s, &o);
  ss_error err;
  cr_assert_eq(ss_checkpoint_write(ck_path, &k, mixed, &err), SS_OK, "%s", err.message);
  ss_film_destroy(mixed);
  o.resume = read_back(&k);
  cr_expect_eq(ss_film_min_drawn(o.resume), 4);
  ss_film *resumed = render(s, &o, SS_OK);
  cr_expect(same_film(resumed, full), "resumed image differs from the uninterrupted one");
  ss_film_destroy(resumed);
  ss_film_destroy(full);
  ss_scene_destroy(s);
}

/* Writes a checkpoint of a 2-spp render and returns its key. */
static ss_checkpoint_key saved_checkpoint(ss_scene *s, ss_render_options *o) {
  options(s, 2, o);
  ss_film *film = render(s, o, SS_OK);
  ss_checkpoint_key k = key_of(s, o);
  ss_error err;
  cr_assert_eq(ss_checkpoint_write(ck_path, &k, film, &err), SS_OK, "%s", err.message);
  ss_film_destroy(film);
  return k;
}

static void expect_refused(const ss_checkpoint_key *k, ss_status status, const char *needle) {
  ss_film *film = NULL;
  ss_error err;
  cr_expect_eq(ss_checkpoint_read(ck_path, k, &film, &err), status, "expected '%s'", needle);
  cr_expect(film == NULL);
  cr_expect(strstr(err.message, needle) != NULL, "'%s' not in: %s", needle, err.message);
  cr_expect(strstr(err.message, ck_path) != NULL, "the file is not named: %s", err.message);
}

/* Overwrites `n` bytes at `offset` of the checkpoint (offset < 0: from the end). */
static void patch(long offset, const void *bytes, size_t n) {
  FILE *f = fopen(ck_path, "r+b");
  cr_assert_not_null(f);
  cr_assert_eq(fseek(f, offset, offset < 0 ? SEEK_END : SEEK_SET), 0);
  cr_assert_eq(fwrite(bytes, 1, n, f), n);
  fclose(f);
}

Test(checkpoint, damaged_files_are_refused_with_the_reason) {
  ss_scene *s = build_scene();
  ss_render_options o;
  ss_checkpoint_key k = saved_checkpoint(s, &o);
  const unsigned char flip = 0x5a;
  patch(400, &flip, 1);
  expect_refused(&k, SS_ERR_PARSE, "CRC-32 mismatch");
  k = saved_checkpoint(s, &o);
  cr_assert_eq(truncate(ck_path, 300), 0);
  expect_refused(&k, SS_ERR_PARSE, "truncated or corrupt");
  k = saved_checkpoint(s, &o);
  const uint32_t version = 7;
  patch(8, &version, sizeof version);
  expect_refused(&k, SS_ERR_PARSE, "format version 7");
  patch(0, "NOTACKPT", 8);
  expect_refused(&k, SS_ERR_PARSE, "not a subsurf render checkpoint");
  ss_film *film = NULL;
  ss_error err;
  remove(ck_path);
  cr_expect_eq(ss_checkpoint_read(ck_path, &k, &film, &err), SS_ERR_IO);
  ss_scene_destroy(s);
}

Test(checkpoint, a_checkpoint_of_other_options_or_another_scene_is_refused) {
  ss_scene *s = build_scene();
  ss_render_options o;
  ss_checkpoint_key k = saved_checkpoint(s, &o);
  ss_checkpoint_key other = k;
  other.seed = 10;
  expect_refused(&other, SS_ERR_INVALID_ARGUMENT, "--seed 9, not --spp 2 --seed 10");
  other = k;
  other.spp = 3;
  expect_refused(&other, SS_ERR_INVALID_ARGUMENT, "--spp 2");
  other = k;
  other.window[2] = 12;
  expect_refused(&other, SS_ERR_INVALID_ARGUMENT, "window 0,0,13,9, not 0,0,12,9");
  other = k;
  snprintf(other.integrator, sizeof other.integrator, "volpath");
  expect_refused(&other, SS_ERR_INVALID_ARGUMENT, "integrator 'path', not 'volpath'");
  FILE *f = fopen(scene_path, "a");
  cr_assert_not_null(f);
  fputs(" ", f);
  fclose(f);
  other = key_of(s, &o);
  expect_refused(&other, SS_ERR_INVALID_ARGUMENT, "belongs to another scene");
  ss_scene_destroy(s);
}
