/* ss_scene_parse_pbrt_limited (the fuzzers' caps): a sphere above the
 * subdivision cap is tessellated at the cap, a film side above the
 * resolution cap is lowered to it, a mesh above the triangle cap is an
 * error, and without limits nothing changes. */
#include "io/pbrt_test.h"

#include <criterion/criterion.h>

static const char *scene_text =
    "Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 30\n"
    "Film \"image\" \"integer xresolution\" 300 \"integer yresolution\" 20\nWorldBegin\n"
    "LightSource \"point\" \"rgb I\" [1 1 1] \"point from\" [0 5 5]\n"
    "Shape \"sphere\" \"float radius\" 1 \"integer subdivisions\" 3\n"
    "Shape \"trianglemesh\" \"point P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"integer indices\" [0 1 2 2 1 "
    "3]\nWorldEnd\n";

static ss_scene *parse(const ss_pbrt_limits *limits, ss_status *st, ss_error *err) {
  ss_scene *s = NULL;
  *st = ss_scene_parse_pbrt_limited(scene_text, "l.pbrt", ".", limits, &s, NULL, NULL, err);
  return s;
}

Test(pbrt_limits, without_limits_the_scene_is_read_as_written) {
  ss_status st;
  ss_error err;
  ss_scene *s = parse(NULL, &st, &err);
  cr_assert_eq(st, SS_OK, "%s", err.message);
  cr_expect_eq(s->camera.width, 300);
  cr_expect_eq(s->camera.height, 20);
  cr_assert_eq(s->num_shapes, 2);
  cr_expect_eq(s->shapes[0].mesh->num_triangles, 20u * 64u); /* 20 x 4^3 */
  ss_scene_destroy(s);
}

Test(pbrt_limits, spheres_and_film_are_lowered_to_the_caps) {
  ss_pbrt_limits limits = {.max_subdivisions = 1, .max_resolution = 64, .max_triangles = 100};
  ss_status st;
  ss_error err;
  ss_scene *s = parse(&limits, &st, &err);
  cr_assert_eq(st, SS_OK, "%s", err.message);
  cr_expect_eq(s->camera.width, 64);
  cr_expect_eq(s->camera.height, 20);
  cr_assert_eq(s->num_shapes, 2);
  cr_expect_eq(s->shapes[0].mesh->num_triangles, 80u); /* 20 x 4^1 */
  ss_scene_destroy(s);
}

Test(pbrt_limits, a_mesh_above_the_triangle_cap_is_an_error) {
  ss_pbrt_limits limits = {.max_subdivisions = 1, .max_triangles = 1};
  ss_status st;
  ss_error err;
  ss_scene *s = parse(&limits, &st, &err);
  cr_expect_eq(st, SS_ERR_PARSE);
  cr_expect_null(s);
  cr_expect(strstr(err.message, "Shape \"trianglemesh\": 2 triangles, more than the limit 1"), "%s",
            err.message);
}
