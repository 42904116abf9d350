/* Tables shared across materials and kept on disk (table_cache.h,
 * subsurface.h): one table per (model, eta, g, options), a second scene load
 * reads the file instead of building, a damaged file is rebuilt and
 * replaced. */
#include "subsurf/scene.h"
#include "subsurf/table_cache.h"
#include "subsurf/table_file.h"

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[256];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "/tmp/subsurf_table_cache_XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void) {
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_assert_eq(system(cmd), 0);
}

/* A translucent sphere of radius 0.4 at (x, 0, 0), its medium and material
 * named `name`. */
static void add_object(ss_scene *s, const char *name, ss_rgb sigma_s, ss_rgb sigma_a,
                       const char *model, double x) {
  ss_error err;
  int index = test_add_translucent_as(s, name, name, sigma_s, sigma_a, SS_BOUNDARY_SMOOTH, model);
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(0.4, 1, &sphere, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(sphere, ss_mat4_translate(ss_vec3_make(x, 0, 0)), &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, name, sphere, index, NULL, &err), SS_OK, "%s", err.message);
}

/* Two translucent spheres of model `model` with different coefficients (the
 * second scaled by k) and the same eta and g; committed with cache `cache_dir`. */
static ss_scene *two_objects(const char *model, double k, const char *cache_dir) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  add_object(s, "a", ss_rgb_make(1.0, 2.0, 3.0), ss_rgb_make(0.01, 0.02, 0.05), model, -1.0);
  add_object(s, "b", ss_rgb_make(4.0 * k, 1.0, 0.5), ss_rgb_make(0.3, 0.02, 0.01), model, 1.0);
  test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_gray(1.0));
  s->render.table_cache = cache_dir != NULL;
  snprintf(s->render.table_cache_dir, sizeof s->render.table_cache_dir, "%s",
           cache_dir ? cache_dir : "");
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_table_cache_stats stats_of(const ss_scene *s) {
  ss_table_cache_stats st;
  ss_subsurface_table_stats(s->subsurface, &st);
  return st;
}

Test(table_cache, materials_of_equal_model_eta_g_and_options_share_one_table) {
  ss_scene *s = two_objects("table-radial", 1.0, NULL);
  ss_table_cache_stats st = stats_of(s);
  cr_expect_eq(ss_subsurface_count(s->subsurface), 2, "one BSSRDF per distinct material");
  cr_expect_eq(st.builds, 1, "%u tables built for one (model, eta, g)", st.builds);
  cr_expect_eq(st.loads, 0);
  const ss_bssrdf *a = ss_subsurface_bssrdf(s->subsurface, 0);
  const ss_bssrdf *b = ss_subsurface_bssrdf(s->subsurface, 1);
  cr_assert(a != b);
  /* The shared table still gives each material its own coefficients. */
  double ra[3], rb[3];
  ss_bssrdf_rd(a, ra);
  ss_bssrdf_rd(b, rb);
  cr_expect(fabs(ra[0] - rb[0]) > 1e-3, "rd %g %g", ra[0], rb[0]);
  ss_scene_destroy(s);
}

Test(table_cache, a_second_scene_load_reads_the_disk_file_instead_of_building) {
  make_dir();
  ss_scene *s = two_objects("table-radial", 1.0, dir);
  ss_table_cache_stats st = stats_of(s);
  cr_expect_eq(st.builds, 1);
  cr_expect_eq(st.loads, 0);
  cr_expect_eq(st.write_failures, 0, "%s", st.last_failure);
  double rd_built[3];
  ss_bssrdf_rd(ss_subsurface_bssrdf(s->subsurface, 1), rd_built);
  ss_scene_destroy(s);
  s = two_objects("table-radial", 2.0, dir);
  st = stats_of(s);
  cr_expect_eq(st.builds, 0, "the second load built %u tables", st.builds);
  cr_expect_eq(st.loads, 1);
  cr_expect_eq(st.rejected, 0);
  ss_scene_destroy(s);
  s = two_objects("table-radial", 1.0, dir);
  double rd_loaded[3];
  ss_bssrdf_rd(ss_subsurface_bssrdf(s->subsurface, 1), rd_loaded);
  for (int c = 0; c < 3; ++c) {
    /* The file holds the float32 values the built table holds: renders with
     * and without the cache agree bit for bit. */
    cr_expect_eq(rd_loaded[c], rd_built[c], "channel %d: %.17g %.17g", c, rd_loaded[c],
                 rd_built[c]);
  }
  ss_scene_destroy(s);
  remove_dir();
}

/* Flips one byte of the payload, or truncates the file. */
static void damage(const char *path, int truncate_it) {
  FILE *f = fopen(path, "r+b");
  cr_assert_not_null(f, "%s", path);
  if (truncate_it) {
    fclose(f);
    cr_assert_eq(truncate(path, SS_TABLE_FILE_HEADER + 10), 0);
    return;
  }
  cr_assert_eq(fseek(f, SS_TABLE_FILE_HEADER + 100, SEEK_SET), 0);
  int c = fgetc(f);
  cr_assert_eq(fseek(f, SS_TABLE_FILE_HEADER + 100, SEEK_SET), 0);
  fputc(c ^ 0x5a, f);
  fclose(f);
}

static void damaged_file_is_rebuilt(int truncate_it) {
  make_dir();
  ss_scene *s = two_objects("table-radial", 1.0, dir);
  ss_table_cache *c;
  ss_error err;
  cr_assert_eq(ss_table_cache_create(dir, &c, &err), SS_OK);
  char path[512];
  ss_table_cache_path(c, SS_TABLE_KIND_RADIAL, 0, 1.3, 0.0, path, sizeof path);
  ss_table_cache_destroy(c);
  ss_scene_destroy(s);
  damage(path, truncate_it);
  ss_table_radial *t;
  cr_assert_neq(ss_table_radial_load(path, &t, &err), SS_OK, "the damaged file still loads");
  s = two_objects("table-radial", 1.0, dir);
  ss_table_cache_stats st = stats_of(s);
  cr_expect_eq(st.rejected, 1);
  cr_expect_eq(st.builds, 1, "the damaged table was not rebuilt");
  cr_expect_eq(st.loads, 0);
  ss_scene_destroy(s);
  cr_assert_eq(ss_table_radial_load(path, &t, &err), SS_OK, "not replaced: %s", err.message);
  ss_table_radial_destroy(t);
  remove_dir();
}

Test(table_cache, a_corrupted_cache_file_is_rebuilt_and_replaced) { damaged_file_is_rebuilt(0); }

Test(table_cache, a_truncated_cache_file_is_rebuilt_and_replaced) { damaged_file_is_rebuilt(1); }

/* A file whose header holds another key (renamed by hand) is stale. */
Test(table_cache, a_file_of_another_key_is_not_trusted) {
  make_dir();
  ss_table_radial *t;
  ss_error err;
  cr_assert_eq(ss_table_radial_build(1.5, 0.0, &t, &err), SS_OK);
  ss_table_cache *c;
  cr_assert_eq(ss_table_cache_create(dir, &c, &err), SS_OK);
  char path[512];
  ss_table_cache_path(c, SS_TABLE_KIND_RADIAL, 0, 1.3, 0.0, path, sizeof path);
  cr_assert_eq(ss_table_radial_save(t, path, &err), SS_OK);
  ss_table_radial_destroy(t);
  const ss_table_radial *got;
  cr_assert_eq(ss_table_cache_radial(c, 1.3, 0.0, &got, &err), SS_OK);
  cr_expect_eq(got->eta, 1.3);
  ss_table_cache_stats st;
  ss_table_cache_get_stats(c, &st);
  cr_expect_eq(st.rejected, 1);
  cr_expect_eq(st.builds, 1);
  ss_table_cache_destroy(c);
  remove_dir();
}
