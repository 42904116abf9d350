/* Nested and touching media (docs/scene-format.md, "Nested and touching
 * media"): regions of two materials may overlap when their priorities
 * differ and each has an index; the scene reader refuses the rest, naming
 * the shapes, the materials and the key, and marks scenes whose media
 * overlap (paths then carry a stack of media). */
#include "subsurf/scene.h"
#include "subsurf/scene_io.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

static const char *head =
    "{\n"
    "  \"media\": [{\"name\": \"m\", \"sigma_s\": 1, \"sigma_a\": 0.1}],\n"
    "  \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"medium\": \"m\"},\n"
    "    {\"name\": \"core\", \"type\": \"translucent\", \"medium\": \"m\", \"eta\": 1.4,\n"
    "     \"priority\": 2},\n"
    "    {\"name\": \"clear\", \"type\": \"translucent\", \"medium\": \"m\",\n"
    "     \"boundary\": \"index-matched\", \"priority\": 3},\n"
    "    {\"name\": \"glass\", \"type\": \"dielectric\"},\n"
    "    {\"name\": \"floor\", \"type\": \"diffuse\"}],\n"
    "  \"shapes\": [\n";

/* Reads the scene; *nested receives the material index marked as nested. */
static ss_status read(const char *shapes, int *nested, ss_error *err) {
  char text[4096];
  snprintf(text, sizeof text, "%s%s\n  ]\n}\n", head, shapes);
  ss_scene *s = NULL;
  ss_status st = ss_scene_parse_json(text, "t.json", NULL, &s, err);
  *nested = s ? s->nested_material : -2;
  ss_scene_destroy(s);
  return st;
}

static void expect_kept(const char *shapes, int nested) {
  ss_error err;
  int got;
  cr_assert_eq(read(shapes, &got, &err), SS_OK, "%s: %s", shapes, err.message);
  cr_assert_eq(got >= 0, nested, "%s: nested_material %d", shapes, got);
}

static void expect_refused(const char *shapes, const char *words) {
  ss_error err;
  ss_error_clear(&err);
  int got;
  cr_assert_eq(read(shapes, &got, &err), SS_ERR_PARSE, "accepted: %s", shapes);
  cr_assert(strstr(err.message, "t.json") && strstr(err.message, words), "'%s' lacks '%s'",
            err.message, words);
}

#define SPHERE(name, mat, r, x)                                                                    \
  "{\"name\": \"" name "\", \"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"" mat       \
  "\", \"radius\": " #r ", \"center\": [" #x ", 0, 0]}"
#define CUBE(name, mat, x)                                                                         \
  "{\"name\": \"" name "\", \"type\": \"cube\", \"material\": \"" mat                              \
  "\", \"transform\": {\"translate\": [" x ", 0, 0]}}"

Test(scene_media_nesting, separate_media_need_no_stack) {
  expect_kept(SPHERE("a", "t", 1, 0) ",\n" SPHERE("b", "t", 1, 2.5), 0);
  expect_kept(CUBE("a", "t", "0") ",\n" CUBE("b", "glass", "1.001"), 0);
  /* A medium may rest on a surface that bounds none. */
  expect_kept(CUBE("a", "t", "0") ",\n{\"type\": \"cube\", \"material\": \"floor\", "
                                  "\"transform\": {\"translate\": [1, 0, 0]}}",
              0);
}

Test(scene_media_nesting, overlaps_of_distinct_priorities_are_kept) {
  expect_kept(SPHERE("outer", "t", 2, 0) ",\n" SPHERE("inner", "core", 0.5, 0.3), 1);
  expect_kept(SPHERE("a", "t", 1, 0) ",\n" SPHERE("b", "core", 1, 1.5), 1);
  /* One material's shapes overlapping fill their union. */
  expect_kept(SPHERE("a", "t", 1, 0) ",\n" SPHERE("b", "t", 1, 1.5), 1);
}

Test(scene_media_nesting, equal_priorities_are_refused) {
  expect_refused(SPHERE("outer", "t", 2, 0) ",\n" SPHERE("inner", "glass", 0.5, 0.3),
                 "shapes 'outer' (material 't') and 'inner' (material 'glass') nest with the "
                 "same priority 0: give the material that fills the overlap a higher 'priority'");
  expect_refused(CUBE("left", "t", "0") ",\n" CUBE("right", "glass", "1"),
                 "shapes 'left' (material 't') and 'right' (material 'glass') touch or cross "
                 "with the same priority 0");
}

Test(scene_media_nesting, index_matched_against_a_refracting_medium_is_refused) {
  expect_refused(SPHERE("outer", "core", 2, 0) ",\n" SPHERE("inner", "clear", 0.5, 0.3),
                 "material 'clear' is index-matched (no index of its own) against 'core' of eta "
                 "1.4: the interface between them has no defined index");
}

Test(scene_media_nesting, priority_out_of_range_is_refused) {
  ss_error err;
  ss_scene *s = NULL;
  const char *text = "{\"materials\": [{\"name\": \"g\", \"type\": \"dielectric\", "
                     "\"priority\": 1001}],\n \"shapes\": [{\"type\": \"sphere\"}]}";
  cr_assert_eq(ss_scene_parse_json(text, "t.json", NULL, &s, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "t.json") && strstr(err.message, "priority"), "%s", err.message);
  text = "{\"materials\": [{\"name\": \"d\", \"type\": \"diffuse\", \"priority\": 1}],\n"
         " \"shapes\": [{\"type\": \"sphere\"}]}";
  cr_assert_eq(ss_scene_parse_json(text, "t.json", NULL, &s, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "priority"), "%s", err.message);
}

/* Concentric spheres of one material, radii 1 .. n. */
static void concentric(char *buf, size_t size, int n) {
  size_t used = 0;
  for (int k = 1; k <= n; ++k) {
    used += (size_t)snprintf(buf + used, size - used,
                             "%s{\"name\": \"s%d\", \"type\": \"sphere\", \"subdivisions\": 1, "
                             "\"material\": \"t\", \"radius\": %d}",
                             k > 1 ? ",\n" : "", k, k);
  }
}

Test(scene_media_nesting, more_regions_than_a_path_holds_are_refused) {
  char shapes[2048];
  concentric(shapes, sizeof shapes, SS_MEDIUM_STACK_SIZE);
  expect_kept(shapes, 1);
  concentric(shapes, sizeof shapes, SS_MEDIUM_STACK_SIZE + 1);
  expect_refused(shapes, "shapes 's1', 's2', 's3', 's4', 's5', 's6', 's7', 's8', 's9' bound 9 "
                         "media that all nest, touch or cross one another: at most 8 may overlap");
}

Test(scene_media_nesting, a_chain_of_overlaps_is_not_a_deep_nesting) {
  /* Twelve spheres each crossing its neighbours: never more than two
   * regions at a point, however many overlaps there are. */
  char shapes[2048];
  size_t used = 0;
  for (int k = 0; k < 12; ++k) {
    used += (size_t)snprintf(shapes + used, sizeof shapes - used,
                             "%s{\"name\": \"c%d\", \"type\": \"sphere\", \"subdivisions\": 1, "
                             "\"material\": \"t\", \"center\": [%d, 0, 0]}",
                             k ? ",\n" : "", k, 2 * k);
  }
  expect_kept(shapes, 1);
}
