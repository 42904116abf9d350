/* Media may not touch or nest (docs/scene-format.md): the volume path tracer
 * tells a segment's medium from the surface it ends on, which is wrong
 * inside nested or touching media. The scene reader refuses such scenes,
 * naming both shapes, and keeps every scene whose media are apart. */
#include "subsurf/scene.h"
#include "subsurf/scene_io.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

static const char *head =
    "{\n"
    "  \"media\": [{\"name\": \"m\", \"sigma_s\": 1, \"sigma_a\": 0.1}],\n"
    "  \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"medium\": \"m\"},\n"
    "    {\"name\": \"glass\", \"type\": \"dielectric\"},\n"
    "    {\"name\": \"floor\", \"type\": \"diffuse\"}],\n"
    "  \"shapes\": [\n";

static ss_status read(const char *shapes, ss_error *err) {
  char text[4096];
  snprintf(text, sizeof text, "%s%s\n  ]\n}\n", head, shapes);
  ss_scene *s = NULL;
  ss_status st = ss_scene_parse_json(text, "t.json", NULL, &s, err);
  ss_scene_destroy(s);
  return st;
}

static void expect_apart(const char *shapes) {
  ss_error err;
  cr_assert_eq(read(shapes, &err), SS_OK, "%s: %s", shapes, err.message);
}

static void expect_refused(const char *shapes, const char *words) {
  ss_error err;
  ss_error_clear(&err);
  cr_assert_eq(read(shapes, &err), SS_ERR_PARSE, "accepted: %s", shapes);
  cr_assert(strstr(err.message, "t.json") && strstr(err.message, words), "'%s' lacks '%s'",
            err.message, words);
}

#define SPHERE(name, mat, r, x) \
  "{\"name\": \"" name "\", \"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"" mat \
  "\", \"radius\": " #r ", \"center\": [" #x ", 0, 0]}"
#define CUBE(name, mat, x) \
  "{\"name\": \"" name "\", \"type\": \"cube\", \"material\": \"" mat \
  "\", \"transform\": {\"translate\": [" x ", 0, 0]}}"

Test(scene_media_apart, separate_media_are_kept) {
  expect_apart(SPHERE("a", "t", 1, 0) ",\n" SPHERE("b", "t", 1, 2.5));
  expect_apart(CUBE("a", "t", "0") ",\n" CUBE("b", "glass", "1.001"));
  /* A medium may rest on a surface that bounds none. */
  expect_apart(CUBE("a", "t", "0") ",\n{\"type\": \"cube\", \"material\": \"floor\", "
                                    "\"transform\": {\"translate\": [1, 0, 0]}}");
}

Test(scene_media_apart, nested_media_are_refused) {
  expect_refused(SPHERE("outer", "t", 2, 0) ",\n" SPHERE("inner", "t", 0.5, 0.3),
                 "shape 'inner' lies inside shape 'outer'");
  expect_refused(SPHERE("small", "glass", 0.5, 0) ",\n" SPHERE("big", "t", 2, 0),
                 "shape 'small' lies inside shape 'big'");
}

Test(scene_media_apart, touching_or_crossing_media_are_refused) {
  expect_refused(SPHERE("a", "t", 1, 0) ",\n" SPHERE("b", "t", 1, 1.5),
                 "shapes 'a' and 'b' bound media that touch or cross");
  expect_refused(CUBE("left", "t", "0") ",\n" CUBE("right", "t", "1"),
                 "shapes 'left' and 'right' bound media that touch");
}
