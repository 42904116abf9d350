/* `subsurf render` with the fem integrator: bad scene options exit 2
 * naming the key and write nothing; a closed but self-intersecting
 * translucent mesh (the mesher fails) exits 2 naming the shape and the
 * cause and writes nothing; a small sphere renders (exit 0); with
 * integrator.cache the second render writes the same image silently, a
 * damaged cache is named on one line and recomputed, and a cache in a
 * missing directory or naming a directory exits 2 naming the key; with
 * cache_read_only a missing cache is named and not created. */
#include "cli/cli_run.h"
#include "io/io_test_dir.h"

#include <criterion/criterion.h>

CLI_SUITE(fem_render_cli);

/* A sphere of radius 1 (1 / sigma_t' = 0.24) lit by a sky; `extra` is
 * appended to the integrator object. */
static void write_scene(const char *name, const char *extra) {
  char text[2048];
  snprintf(text, sizeof text,
           "{\"camera\": {\"resolution\": [8, 8], \"position\": [0, 0, 4]},\n"
           " \"media\": [{\"name\": \"m\", \"sigma_s\": 4, \"sigma_a\": 0.2}],\n"
           " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"boundary\": "
           "\"smooth\", \"eta\": 1.3, \"medium\": \"m\"}],\n"
           " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"t\"}],\n"
           " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
           " \"integrator\": {\"type\": \"fem\", \"element_size\": 2%s},\n"
           " \"render\": {\"spp\": 1}}\n",
           extra);
  cli_write_file(dir, name, text);
}

Test(fem_render_cli, bad_options_exit_2_naming_the_key) {
  static const struct {
    const char *extra, *needle;
  } cases[] = {
      {", \"element_size\": 0", "element_size"},
      {", \"element_size\": -1", "element_size"},
      {", \"pcg\": 3", "pcg"},
      {", \"irradiance_samples\": 0.5", "irradiance_samples"},
      {", \"max_elements\": 1", "max_elements"},
      {", \"min_density\": 2", "min_density"},
      {", \"volume_source\": 2", "volume_source"},
      {", \"indirect\": 0.5", "indirect"},
      {", \"points\": 100", "points"},
      {", \"cache\": \"\"", "cache"},
      {", \"cache\": 3", "cache"},
      {", \"cache\": \"no/such/dir/c.fem\"", "integrator.cache"},
      {", \"cache\": \".\"", "integrator.cache: './.' is a directory"},
      {", \"cache_read_only\": 2", "cache_read_only"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    write_scene("s.json", cases[i].extra);
    cli_expect_bad_input(&res, dir, "render s.json -o out.exr --quiet", cases[i].needle);
  }
}

Test(fem_render_cli, a_sphere_renders) {
  write_scene("s.json", ", \"pcg\": 1");
  cli_run_in(&res, dir, "render s.json -o out.exr --no-png --quiet", 0.0);
  cr_expect_eq(res.status, 0, "%s", res.err);
}

Test(fem_render_cli, a_self_intersecting_mesh_exits_2_naming_the_shape) {
  /* two overlapping octahedra: closed (every edge shared by two triangles),
   * so the scene takes them, but crossing each other, so gmsh cannot fill
   * them */
  cli_write_file(dir, "twin.obj",
                 "v 3 0 0\nv -3 0 0\nv 0 3 0\nv 0 -3 0\nv 0 0 3\nv 0 0 -3\n"
                 "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n"
                 "v 4.5 0.5 0.3\nv -1.5 0.5 0.3\nv 1.5 3.5 0.3\nv 1.5 -2.5 0.3\nv 1.5 0.5 3.3\n"
                 "v 1.5 0.5 -2.7\nf 7 9 11\nf 9 8 11\nf 8 10 11\nf 10 7 11\nf 9 7 12\n"
                 "f 8 9 12\nf 10 8 12\nf 7 10 12\n");
  cli_write_file(dir, "twin.json",
                 "{\"camera\": {\"resolution\": [8, 8], \"position\": [0, 0, 12]},\n"
                 " \"media\": [{\"name\": \"m\", \"sigma_s\": 4, \"sigma_a\": 0.2}],\n"
                 " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"boundary\": "
                 "\"smooth\", \"eta\": 1.3, \"medium\": \"m\"}],\n"
                 " \"shapes\": [{\"name\": \"twin\", \"type\": \"mesh\", \"file\": \"twin.obj\", "
                 "\"material\": \"t\"}],\n"
                 " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
                 " \"integrator\": {\"type\": \"fem\", \"element_size\": 4},\n"
                 " \"render\": {\"spp\": 1}}\n");
  cli_expect_bad_input(&res, dir, "render twin.json -o out.exr --quiet",
                       "shape 'twin': fem mesh: the surface intersects itself");
}

/* Whether dir/a and dir/b hold the same bytes. */
static int same_file(const char *a, const char *b) {
  char pa[128], pb[128];
  snprintf(pa, sizeof pa, "%s/%s", dir, a);
  snprintf(pb, sizeof pb, "%s/%s", dir, b);
  size_t na = 0, nb = 0;
  unsigned char *da = io_test_read_file(pa, &na), *db = io_test_read_file(pb, &nb);
  cr_assert(da && db, "%s or %s missing", a, b);
  int same = na == nb && !memcmp(da, db, na);
  free(da);
  free(db);
  return same;
}

Test(fem_render_cli, the_cache_is_reused_and_a_damaged_one_is_named_and_recomputed) {
  write_scene("s.json", ", \"cache\": \"c.fem\"");
  cli_run_in(&res, dir, "render s.json -o a.exr --no-png --quiet", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cr_expect_eq(res.err[0], '\0', "%s", res.err);
  cr_assert(cli_file_exists(dir, "c.fem"));
  cli_run_in(&res, dir, "render s.json -o b.exr --no-png --quiet", 0.0);
  cr_expect_eq(res.status, 0, "%s", res.err);
  cr_expect_eq(res.err[0], '\0', "a valid cache was refused: %s", res.err);
  cr_expect(same_file("a.exr", "b.exr"), "the image from the cache differs");
  cli_write_file(dir, "c.fem", "SSFEMCH but not a cache");
  cli_run_in(&res, dir, "render s.json -o c.exr --no-png --quiet", 0.0);
  cr_expect_eq(res.status, 0, "%s", res.err);
  cr_expect(strstr(res.err, "warning: fem cache") && strstr(res.err, "c.fem") &&
                strstr(res.err, "recomputing") &&
                strchr(res.err, '\n') == res.err + strlen(res.err) - 1,
            "expected one line naming the file: %s", res.err);
  cr_expect(same_file("a.exr", "c.exr"), "the recomputed image differs");
  cli_run_in(&res, dir, "render s.json -o d.exr --no-png --quiet", 0.0);
  cr_expect_eq(res.err[0], '\0', "the cache was not rewritten: %s", res.err);
}

Test(fem_render_cli, a_missing_read_only_cache_is_named_and_not_created) {
  write_scene("s.json", ", \"cache\": \"c.fem\", \"cache_read_only\": 1");
  cli_run_in(&res, dir, "render s.json -o a.exr --no-png --quiet", 0.0);
  cr_expect_eq(res.status, 0, "%s", res.err);
  cr_expect(strstr(res.err, "c.fem") && strstr(res.err, "cache_read_only: not written") &&
                strchr(res.err, '\n') == res.err + strlen(res.err) - 1,
            "expected one line naming the file: %s", res.err);
  cr_expect(!cli_file_exists(dir, "c.fem"), "a read-only cache was created");
}
