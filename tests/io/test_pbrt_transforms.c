/* The pbrt-v3 importer's transforms and camera: the directives compose as
 * pbrt-v3's current transformation matrix does, pbrt's left-handed camera
 * space is mapped so that what pbrt shows on the left subsurf shows on the
 * left, the field of view spans the shorter image axis, and the crop window
 * becomes pixels as pbrt-v3's Film computes them. */
#include "io/pbrt_test.h"

#include "subsurf/transform.h"

#include <math.h>

#define DEG (3.14159265358979323846 / 180.0)

static ss_scene *read_ok(const char *text, pbrt_warnings *w) {
  char dir[64];
  pbrt_tmpdir(dir, sizeof dir);
  ss_scene *s = NULL;
  ss_error err;
  cr_assert_eq(pbrt_read(dir, "t.pbrt", text, &s, w, &err), SS_OK, "%s", err.message);
  pbrt_rmdir(dir);
  return s;
}

static void expect_vertex(const ss_mesh *m, uint32_t i, double x, double y, double z) {
  ss_vec3 p = ss_mesh_position(m, i);
  cr_expect(fabs(p.x - x) < 1e-5 && fabs(p.y - y) < 1e-5 && fabs(p.z - z) < 1e-5,
            "vertex %u at (%g %g %g), expected (%g %g %g)", i, p.x, p.y, p.z, x, y, z);
}

#define TRIANGLE                                                                                   \
  "Shape \"trianglemesh\" \"point P\" [1 0 0 0 1 0 0 0 1] \"integer indices\" [0 1 2]\n"

Test(pbrt_transforms, directives_compose_as_pbrts_current_transform) {
  pbrt_warnings w;
  ss_scene *s = read_ok(
      PBRT_TEST_HEADER
      /* 0: the last directive applies first: p' = T R S p */
      "AttributeBegin\nTranslate 1 2 3\nRotate 90 0 0 1\nScale 2 2 2\n" TRIANGLE "AttributeEnd\n"
      /* 1: Transform is column-major and replaces the CTM */
      "AttributeBegin\nTranslate 9 9 9\n"
      "Transform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1]\n" TRIANGLE "AttributeEnd\n"
      /* 2: ConcatTransform multiplies on the right */
      "TransformBegin\nTranslate 1 0 0\n"
      "ConcatTransform [0 1 0 0  -1 0 0 0  0 0 1 0  0 0 0 1]\n" TRIANGLE "TransformEnd\n"
      /* 3: the blocks restored the identity; a named system */
      "Translate 0 0 -1\nCoordinateSystem \"low\"\nIdentity\n"
      "CoordSysTransform \"low\"\n" TRIANGLE "WorldEnd\n",
      &w);
  cr_assert_eq(s->num_shapes, 4);
  const ss_mesh *m = s->shapes[0].mesh;
  expect_vertex(m, 0, 1, 4, 3);  /* (1,0,0) -> (2,0,0) -> (0,2,0) -> (1,4,3) */
  expect_vertex(m, 1, -1, 2, 3); /* (0,1,0) -> (0,2,0) -> (-2,0,0) */
  expect_vertex(m, 2, 1, 2, 5);
  expect_vertex(s->shapes[1].mesh, 0, 6, 6, 7);
  /* the matrix rotates x to y; then x + 1 */
  expect_vertex(s->shapes[2].mesh, 0, 1, 1, 0);
  expect_vertex(s->shapes[2].mesh, 1, 0, 0, 0);
  expect_vertex(s->shapes[3].mesh, 2, 0, 0, 0);
  expect_vertex(s->shapes[3].mesh, 0, 1, 0, -1);
  ss_scene_destroy(s);
}

Test(pbrt_transforms, lookat_keeps_pbrts_left_on_the_left) {
  /* pbrt-v3's LookAt from +z toward the origin with up +y has camera +x =
   * up x dir = world -x: world -x is on the right of pbrt's image. */
  const char *scene = "LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
                      "Film \"image\" \"integer xresolution\" 64 \"integer yresolution\" 64\n"
                      "WorldBegin\nLightSource \"point\"\n"
                      "AttributeBegin\nTranslate -1 0.5 0\n" TRIANGLE "AttributeEnd\n"
                      "AttributeBegin\nTranslate 1 -1.5 0\n" TRIANGLE "AttributeEnd\nWorldEnd\n";
  pbrt_warnings w;
  ss_scene *s = read_ok(scene, &w);
  /* the centres of the shapes' bounds: (-0.5, 1, 0.5) and (1.5, -1, 0.5) */
  ss_vec3 lo, hi;
  ss_mesh_bounds(s->shapes[0].mesh, &lo, &hi);
  double xa, ya, xb, yb;
  cr_assert(ss_camera_raster(
      &s->camera, ss_vec3_sub(ss_vec3_scale(ss_vec3_add(lo, hi), 0.5), s->camera.position), &xa,
      &ya));
  ss_mesh_bounds(s->shapes[1].mesh, &lo, &hi);
  cr_assert(ss_camera_raster(
      &s->camera, ss_vec3_sub(ss_vec3_scale(ss_vec3_add(lo, hi), 0.5), s->camera.position), &xb,
      &yb));
  /* pbrt: the object at world x < 0 is on the right, the one at x > 0 on
   * the left; up is up */
  cr_expect_gt(xa, 32.0, "world x < 0 should be right of centre in pbrt's image: %g", xa);
  cr_expect_lt(xb, 32.0, "world x > 0 should be left of centre: %g", xb);
  cr_expect_lt(ya, 32.0, "world y > 0 should be above the centre: %g", ya);
  cr_expect_gt(yb, 32.0);
  ss_scene_destroy(s);

  /* with pbrt's usual "Scale -1 1 1" the world is not mirrored: world +x is
   * on the right and subsurf's world equals pbrt's */
  char mirrored[2048];
  snprintf(mirrored, sizeof mirrored, "Scale -1 1 1\n%s", scene);
  s = read_ok(mirrored, &w);
  ss_mesh_bounds(s->shapes[1].mesh, &lo, &hi);
  cr_expect_float_eq(0.5 * (lo.x + hi.x), 1.5, 1e-6);
  cr_assert(ss_camera_raster(
      &s->camera, ss_vec3_sub(ss_vec3_scale(ss_vec3_add(lo, hi), 0.5), s->camera.position), &xb,
      &yb));
  cr_expect_gt(xb, 32.0);
  cr_expect_gt(yb, 32.0);
  cr_expect_float_eq(s->camera.position.z, 5.0, 1e-12);
  ss_scene_destroy(s);
}

Test(pbrt_transforms, fov_spans_the_shorter_image_axis) {
  for (int portrait = 0; portrait < 2; ++portrait) {
    char text[2048];
    snprintf(text, sizeof text,
             "Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
             "Film \"image\" \"integer xresolution\" %d \"integer yresolution\" %d\n"
             "WorldBegin\nLightSource \"point\"\n" TRIANGLE "WorldEnd\n",
             portrait ? 30 : 60, portrait ? 60 : 30);
    pbrt_warnings w;
    ss_scene *s = read_ok(text, &w);
    /* a direction 20 degrees off the axis along the shorter side meets the
     * image's edge */
    double t = tan(20.0 * DEG), x, y;
    ss_vec3 d = portrait ? ss_vec3_make(t, 0, -1) : ss_vec3_make(0, t, -1);
    cr_assert(ss_camera_raster(&s->camera, d, &x, &y));
    if (portrait) {
      cr_expect_float_eq(x, 30.0, 1e-9, "portrait: %g", x);
      cr_expect_float_eq(y, 30.0, 1e-9);
    } else {
      cr_expect_float_eq(y, 0.0, 1e-9, "landscape: %g", y);
      cr_expect_float_eq(s->camera.fov_deg, 40.0, 1e-12);
    }
    ss_scene_destroy(s);
  }
}

Test(pbrt_transforms, crop_window_becomes_pbrts_pixel_bounds) {
  pbrt_warnings w;
  ss_scene *s = read_ok("Film \"image\" \"integer xresolution\" 10 \"integer yresolution\" 20\n"
                        "  \"float cropwindow\" [0.25 0.75 0.1 0.5]\n"
                        "WorldBegin\nLightSource \"point\"\n" TRIANGLE "WorldEnd\n",
                        &w);
  /* ceil(10 * 0.25) = 3 .. ceil(7.5) = 8; ceil(2) = 2 .. ceil(10) = 10 */
  cr_expect_eq(s->render.crop[0], 3);
  cr_expect_eq(s->render.crop[2], 8);
  cr_expect_eq(s->render.crop[1], 2);
  cr_expect_eq(s->render.crop[3], 10);
  /* pbrt-v3's default camera: fov 90 on the shorter (x) axis */
  double x, y;
  cr_assert(ss_camera_raster(&s->camera, ss_vec3_make(1, 0, 1), &x, &y));
  cr_expect(fabs(x) < 1e-9 || fabs(x - 10.0) < 1e-9, "%g", x);
  ss_scene_destroy(s);
}
