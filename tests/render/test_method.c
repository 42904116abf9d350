/* Comparison methods (method.h): the text form's grammar and errors, and
 * applying a model method rebuilds every translucent material's BSSRDF;
 * the translucent mask (translucent_mask.h) marks exactly the pixels whose
 * first hit is a translucent object. */
#include "subsurf/method.h"
#include "subsurf/transform.h"
#include "subsurf/translucent_mask.h"

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

static void add_ball(ss_scene *s, const char *name, double x, int material) {
  ss_mesh *mesh;
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(0.5, 3, &mesh, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(mesh, ss_mat4_translate(ss_vec3_make(x, 0, 0)), &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, name, mesh, material, NULL, &err), SS_OK, "%s", err.message);
}

/* A translucent ball (model dipole) at x = -0.8 and a diffuse one at 0.8,
 * seen by a 16 x 16 camera on the +z axis, lit by a point light. */
static ss_scene *scene(void) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  s->camera.width = s->camera.height = 16;
  s->camera.fov_deg = 40;
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "m");
  med.optics.sigma_s = ss_rgb_gray(4.0);
  med.optics.sigma_a = ss_rgb_gray(0.1);
  int mi;
  cr_assert_eq(ss_scene_add_medium(s, &med, &mi, &err), SS_OK, "%s", err.message);
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "skin");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = SS_BOUNDARY_SMOOTH;
  m.eta = 1.3;
  m.medium = mi;
  m.lod = SS_LOD_BSSRDF;
  snprintf(m.bssrdf, sizeof m.bssrdf, "dipole");
  ss_bssrdf_params_default(&m.bssrdf_options);
  cr_assert_eq(ss_scene_add_material(s, &m, NULL, &err), SS_OK, "%s", err.message);
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "wall");
  m.kind = SS_MATERIAL_DIFFUSE;
  m.albedo = ss_rgb_gray(0.5);
  m.medium = -1;
  cr_assert_eq(ss_scene_add_material(s, &m, NULL, &err), SS_OK, "%s", err.message);
  add_ball(s, "ball", -0.8, 0);
  add_ball(s, "other", 0.8, 1);
  test_add_point_light(s, "lamp", ss_vec3_make(0, 3, 3), 10.0);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

Test(method, integrator_and_model_methods_parse) {
  ss_method m;
  ss_error err;
  cr_assert_eq(ss_method_parse("volpath", &m, &err), SS_OK, "%s", err.message);
  cr_expect_str_eq(m.integrator, "volpath");
  cr_expect_str_eq(m.model, "");
  cr_assert_eq(ss_method_parse("pbd:beam_samples=50", &m, &err), SS_OK, "%s", err.message);
  cr_expect_str_eq(m.integrator, "bssrdf");
  cr_expect_str_eq(m.model, "pbd");
  cr_expect_eq(m.options.n_options, 1);
  char file[256];
  ss_method_file_name(&m, file, sizeof file);
  cr_expect_str_eq(file, "pbd_beam_samples_50");
}

static void expect_refused(const char *text, const char *says) {
  ss_method m;
  ss_error err;
  cr_expect_eq(ss_method_parse(text, &m, &err), SS_ERR_INVALID_ARGUMENT, "%s accepted", text);
  cr_expect(strstr(err.message, text) && strstr(err.message, says), "%s: %s", text, err.message);
}

Test(method, bad_methods_are_refused_naming_the_method) {
  expect_refused("nosuch", "unknown name");
  expect_refused("pbd:beam_samples", "NAME=VALUE");
  expect_refused("pbd:beam_samples=", "NAME=VALUE");
  expect_refused("pbd:nosuch=1", "unknown option");
  expect_refused("pbd:beam_samples=-3", "beam_samples");
  expect_refused("volpath:beam_samples=3", "unknown option 'beam_samples'");
  expect_refused("volpath:max_depth=2.5", "integer");
  expect_refused("volpath:max_depth=-1", "integer");
  expect_refused("volpath:rr_depth=1e9", "integer");
  expect_refused("volpath:max_depth=0x10", "integer");
  expect_refused("volpath:max_depth", "NAME=VALUE");
  expect_refused("pbd:max_depth=nan", "max_depth");
  expect_refused("", "unknown name");
}

Test(method, integrator_options_go_to_the_integrator_and_model_options_to_the_model) {
  ss_method m;
  ss_error err;
  cr_assert_eq(ss_method_parse("volpath:max_depth=64:rr_depth=3", &m, &err), SS_OK, "%s",
               err.message);
  cr_expect_eq(m.num_integrator_options, 2);
  cr_assert_eq(ss_method_parse("pbd:beam_samples=40:max_depth=7", &m, &err), SS_OK, "%s",
               err.message);
  cr_expect_eq(m.options.n_options, 1);
  cr_expect_eq(m.num_integrator_options, 1);
  ss_scene *s = scene();
  cr_assert_eq(ss_method_apply(&m, s, &err), SS_OK, "%s", err.message);
  cr_expect_eq(s->integrator.max_depth, 7);
  cr_expect_eq(s->integrator.rr_depth, 5, "the scene's own value stays");
  cr_expect_str_eq(ss_bssrdf_name(ss_subsurface_bssrdf(s->subsurface, 0)), "pbd");
  ss_scene_destroy(s);
}

Test(method, a_model_method_replaces_every_translucent_materials_model) {
  ss_scene *s = scene();
  ss_method m;
  ss_error err;
  cr_assert_eq(ss_method_parse("pbd:beam_samples=40", &m, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_method_apply(&m, s, &err), SS_OK, "%s", err.message);
  cr_expect_str_eq(s->integrator.name, "bssrdf");
  const ss_bssrdf *b = ss_subsurface_bssrdf(s->subsurface, 0);
  cr_assert_not_null(b);
  cr_expect_str_eq(ss_bssrdf_name(b), "pbd");
  cr_expect_eq(ss_subsurface_lod(s->subsurface, 0), SS_LOD_BSSRDF);
  cr_expect_str_eq(s->materials[1].bssrdf, "", "the diffuse wall is untouched");
  ss_scene_destroy(s);
}

Test(translucent_mask, marks_the_translucent_ball_and_not_the_wall_or_background) {
  ss_scene *s = scene();
  ss_image *mask;
  ss_error err;
  cr_assert_eq(ss_translucent_mask(s, &mask, &err), SS_OK, "%s", err.message);
  /* The translucent ball is left of centre (camera x right), the wall right. */
  cr_expect_eq(*ss_image_pixel(mask, 4, 8), 1.0f);
  cr_expect_eq(*ss_image_pixel(mask, 11, 8), 0.0f);
  cr_expect_eq(*ss_image_pixel(mask, 0, 0), 0.0f);
  cr_expect_eq(*ss_image_pixel(mask, 8, 8), 0.0f, "the gap between the balls");
  ss_image_destroy(mask);
  ss_scene_destroy(s);
}
