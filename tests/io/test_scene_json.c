/* The scene reader: the default scenes parse; every kind of error names the
 * key path and the line of the offending key. */
#include <criterion/criterion.h>

#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static ss_scene *load_default(const char *name) {
  const char *root = getenv("SUBSURF_SOURCE_DIR");
  cr_assert_not_null(root, "SUBSURF_SOURCE_DIR is not set");
  char path[4096];
  snprintf(path, sizeof path, "%s/scenes/%s", root, name);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_read_json(path, &s, &err), SS_OK, "%s", err.message);
  return s;
}

Test(scene_json, default_scenes_parse) {
  const char *names[] = {"skin_sphere.json", "fig1_cube.json", "skin_rough_sphere.json",
                         "marble_slab.json", "freckles_sphere.json"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
    ss_scene *s = load_default(names[i]);
    cr_expect(s->committed);
    cr_expect_gt(s->num_shapes, 0);
    cr_expect_gt(s->num_lights, 0);
    ss_scene_destroy(s);
  }
}

Test(scene_json, skin_sphere_is_exactly_as_specified) {
  ss_scene *s = load_default("skin_sphere.json");
  cr_expect_eq(s->camera.width, 256);
  cr_expect_eq(s->camera.height, 256);
  cr_expect_float_eq(s->camera.fov_deg, 30.0, 1e-12);
  cr_expect_float_eq(s->camera.position.z, 5.0, 1e-12);
  cr_expect_eq(s->camera.filter.type, SS_FILTER_BOX);
  cr_assert_eq(s->num_media, 1);
  const double sig_s[3] = {3.70, 4.40, 5.05}, sig_a[3] = {0.16, 0.85, 2.40};
  for (int c = 0; c < 3; ++c) {
    cr_expect_float_eq(s->media[0].optics.sigma_s.c[c], sig_s[c], 1e-12);
    cr_expect_float_eq(s->media[0].optics.sigma_a.c[c], sig_a[c], 1e-12);
  }
  cr_expect_eq(s->media[0].phase.type, SS_PHASE_ISOTROPIC);
  cr_assert_eq(s->num_materials, 1);
  cr_expect_eq(s->materials[0].boundary, SS_BOUNDARY_SMOOTH);
  cr_expect_float_eq(s->materials[0].eta, 1.33, 1e-12);
  cr_assert_eq(s->num_lights, 1);
  cr_expect_eq(s->lights[0].type, SS_LIGHT_AREA);
  cr_expect_float_eq(s->lights[0].value.c[1], 10.0, 1e-12);
  cr_expect_eq(s->environment, -1, "the background must be black");
  /* The lamp: radius 2 about (6, 2, -2) (vertices of the icosphere lie on it). */
  const ss_mesh *lamp = s->shapes[s->lights[0].shape].mesh;
  for (size_t v = 0; v < lamp->num_vertices; v += 97) {
    ss_vec3 p = ss_vec3_sub(ss_mesh_position(lamp, (uint32_t)v), ss_vec3_make(6, 2, -2));
    cr_expect_float_eq(ss_vec3_length(p), 2.0, 1e-5);
  }
  ss_scene_destroy(s);
}

static const char *good_prefix = "{\n"
                                 "  \"camera\": {\"resolution\": [8, 8]},\n";

/* Parses `text` and expects an SS_ERR_PARSE whose message starts with
 * "<file>:<line>: " and contains `path` and `words`. */
static void expect_error(const char *text, int line, const char *path, const char *words) {
  ss_scene *s = NULL;
  ss_error err;
  ss_status st = ss_scene_parse_json(text, "t.json", ".", &s, &err);
  cr_assert_neq(st, SS_OK, "expected an error naming %s", path);
  cr_expect_null(s);
  char head[64];
  snprintf(head, sizeof head, "t.json:%d: ", line);
  cr_expect(!strncmp(err.message, head, strlen(head)), "expected '%s...', got '%s'", head,
            err.message);
  cr_expect(strstr(err.message, path) != NULL, "'%s' does not name %s", err.message, path);
  cr_expect(strstr(err.message, words) != NULL, "'%s' does not say '%s'", err.message, words);
}

static char *cat(const char *a, const char *b) {
  static char buf[8192];
  snprintf(buf, sizeof buf, "%s%s", a, b);
  return buf;
}

static const char *sphere_shape =
    "  \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}]\n}\n";

Test(scene_json, minimal_scene_parses_with_defaults) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(cat(good_prefix, sphere_shape), "t.json", ".", &s, &err), SS_OK,
               "%s", err.message);
  cr_expect_str_eq(s->integrator.name, "volpath");
  cr_expect_eq(s->render.spp, 16);
  cr_expect_eq(s->camera.width, 8);
  ss_scene_destroy(s);
}

Test(scene_json, syntax_error_names_its_line) {
  expect_error("{\n  \"camera\": {\n    \"fov\": 30,,\n  }\n}\n", 3, "", "invalid JSON");
}

Test(scene_json, unknown_key_names_path_and_line) {
  expect_error(cat(good_prefix, "  \"materials\": [\n"
                                "    {\"name\": \"a\", \"type\": \"diffuse\"},\n"
                                "    {\"name\": \"b\", \"type\": \"diffuse\",\n"
                                "     \"colour\": [1, 0, 0]}\n"
                                "  ],\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               6, "materials[1].colour", "unknown key");
}

Test(scene_json, wrong_type_names_path_and_line) {
  expect_error("{\n  \"camera\": {\n    \"fov\": \"wide\"\n  },\n"
               "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n",
               3, "camera.fov", "expected a number");
}

Test(scene_json, missing_reference_names_path_and_line) {
  expect_error(cat(good_prefix, "  \"shapes\": [\n    {\"type\": \"sphere\",\n"
                                "     \"material\": \"gold\"}\n  ]\n}\n"),
               5, "shapes[0].material", "no material named 'gold'");
}

Test(scene_json, out_of_range_array_element_names_index_and_line) {
  expect_error(cat(good_prefix, "  \"media\": [\n    {\"name\": \"m\",\n"
                                "     \"sigma_s\": 1,\n     \"sigma_a\": [0.1, -2, 0.1]}\n  ],\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               6, "media[0].sigma_a[1]", "out of range");
}

Test(scene_json, inline_medium_error_names_nested_path) {
  expect_error(cat(good_prefix, "  \"materials\": [\n"
                                "    {\"name\": \"skin\", \"type\": \"translucent\",\n"
                                "     \"medium\": {\n"
                                "       \"sigma_s\": [1, 1, 1],\n"
                                "       \"sigma_a\": \"red\"}}\n"
                                "  ],\n  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               7, "materials[0].medium.sigma_a", "expected a number or an array");
}

Test(scene_json, missing_required_key_names_the_object) {
  expect_error(cat(good_prefix, "  \"lights\": [\n    {\"name\": \"sun\"}\n  ],\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               4, "lights[0]", "missing required key 'type'");
}

Test(scene_json, unknown_integrator_option_is_an_error) {
  expect_error(cat(good_prefix, "  \"integrator\": {\"type\": \"path\",\n"
                                "    \"photons\": 1000},\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               4, "integrator.photons", "unknown option");
}

Test(scene_json, unknown_enumeration_values_are_errors) {
  expect_error(cat(good_prefix, "  \"integrator\": {\"type\": \"bdpt\"},\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               3, "integrator.type", "unknown integrator 'bdpt'");
  expect_error(cat(good_prefix, "  \"media\": [{\"name\": \"m\", \"sigma_s\": 1, \"sigma_a\": 0,\n"
                                "    \"phase\": {\"type\": \"rayleigh\"}}],\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               4, "media[0].phase", "unknown phase function");
  expect_error(cat(good_prefix, "  \"materials\": [{\"name\": \"s\", \"type\": \"translucent\",\n"
                                "    \"medium\": {\"preset\": \"Skin1\"},\n"
                                "    \"bssrdf\": \"no-such-model\"}],\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               5, "materials[0].bssrdf", "unknown BSSRDF model");
  expect_error(cat(good_prefix, "  \"media\": [{\"name\": \"m\",\n    \"preset\": \"Jelly\"}],\n"
                                "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               4, "media[0].preset", "unknown medium preset");
}

Test(scene_json, open_mesh_with_a_medium_is_an_error) {
  expect_error(cat(good_prefix,
                   "  \"materials\": [{\"name\": \"skin\", \"type\": \"translucent\",\n"
                   "    \"medium\": {\"preset\": \"Skin1\"}}],\n"
                   "  \"shapes\": [\n    {\"type\": \"quad\", \"material\": \"skin\"}\n  ]\n}\n"),
               6, "shapes[0]", "closed");
}

Test(scene_json, duplicate_names_and_keys_are_errors) {
  expect_error(cat(good_prefix,
                   "  \"materials\": [\n    {\"name\": \"a\", \"type\": \"diffuse\"},\n"
                   "    {\"name\": \"a\", \"type\": \"diffuse\"}\n  ],\n"
                   "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               5, "materials[1]", "defined twice");
  expect_error("{\n  \"camera\": {\"fov\": 30,\n    \"fov\": 40},\n"
               "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n",
               2, "camera.fov", "duplicate key");
}

/* Lights follow the rule of every kind: names are unique and not empty. */
Test(scene_json, light_names_are_unique_and_not_empty) {
  expect_error(cat(good_prefix, "  \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
                                "  \"lights\": [{\"type\": \"point\"},\n"
                                "    {\"name\": \"\", \"type\": \"point\"}]\n}\n"),
               5, "lights[1]", "empty name");
  expect_error(cat(good_prefix, "  \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
                                "  \"lights\": [{\"name\": \"sun\", \"type\": \"point\"},\n"
                                "    {\"name\": \"sun\", \"type\": \"directional\"}]\n}\n"),
               5, "lights[1]", "light 'sun' is defined twice");
  /* The default names count: an explicit "light0" after an unnamed light. */
  expect_error(cat(good_prefix, "  \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
                                "  \"lights\": [{\"type\": \"point\"},\n"
                                "    {\"name\": \"light0\", \"type\": \"point\"}]\n}\n"),
               5, "lights[1]", "defined twice");
}

Test(scene_json, mesh_files_are_found_relative_to_the_scene) {
  char dir[] = "/tmp/subsurf_scene_XXXXXX";
  cr_assert_not_null(mkdtemp(dir));
  char path[256];
  snprintf(path, sizeof path, "%s/tet.obj", dir);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f);
  /* A closed, outward-wound tetrahedron. */
  fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", f);
  fclose(f);
  snprintf(path, sizeof path, "%s/scene.json", dir);
  f = fopen(path, "w");
  cr_assert_not_null(f);
  fputs("{\n  \"materials\": [{\"name\": \"g\", \"type\": \"dielectric\"}],\n"
        "  \"shapes\": [{\"type\": \"mesh\", \"file\": \"tet.obj\", \"material\": \"g\",\n"
        "    \"transform\": {\"scale\": 2, \"translate\": [1, 0, 0]}},\n"
        "    {\"type\": \"mesh\",\n     \"file\": \"missing.ply\"}]\n}\n",
        f);
  fclose(f);
  ss_scene *s = NULL;
  ss_error err;
  cr_assert_neq(ss_scene_read_json(path, &s, &err), SS_OK);
  cr_expect(strstr(err.message, "scene.json:6: shapes[1].file") != NULL, "%s", err.message);
  cr_expect(strstr(err.message, "missing.ply") != NULL, "%s", err.message);
  /* Without the missing mesh it loads, transformed. */
  f = fopen(path, "w");
  fputs("{\n  \"materials\": [{\"name\": \"g\", \"type\": \"dielectric\"}],\n"
        "  \"shapes\": [{\"type\": \"mesh\", \"file\": \"tet.obj\", \"material\": \"g\",\n"
        "    \"transform\": {\"scale\": 2, \"translate\": [1, 0, 0]}}]\n}\n",
        f);
  fclose(f);
  cr_assert_eq(ss_scene_read_json(path, &s, &err), SS_OK, "%s", err.message);
  ss_vec3 lo, hi;
  ss_mesh_bounds(s->shapes[0].mesh, &lo, &hi);
  cr_expect_float_eq(lo.x, 1.0, 1e-6);
  cr_expect_float_eq(hi.x, 3.0, 1e-6);
  ss_scene_destroy(s);
  unlink(path);
  snprintf(path, sizeof path, "%s/tet.obj", dir);
  unlink(path);
  rmdir(dir);
}

Test(scene_json, energy_compensation_is_a_rough_boundary_bool) {
  expect_error(
      cat(good_prefix,
          "  \"materials\": [\n"
          "    {\"name\": \"a\", \"type\": \"translucent\", \"medium\": "
          "{\"sigma_s\": 1, \"sigma_a\": 0.1},\n     \"energy_compensation\": true}\n  ],\n"
          "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
      5, "materials[0].energy_compensation", "rough boundaries only");
  expect_error(cat(good_prefix,
                   "  \"materials\": [\n"
                   "    {\"name\": \"a\", \"type\": \"translucent\", \"medium\": "
                   "{\"sigma_s\": 1, \"sigma_a\": 0.1},\n     \"boundary\": \"rough\",\n"
                   "     \"energy_compensation\": 2}\n  ],\n"
                   "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
               6, "materials[0].energy_compensation", "expected true or false");
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(cat(good_prefix, "  \"materials\": [\n"
                                                    "    {\"name\": \"a\", \"type\": "
                                                    "\"translucent\", \"medium\": {\"sigma_s\": 1, "
                                                    "\"sigma_a\": 0.1}, "
                                                    "\"boundary\": \"rough\"}\n  ],\n"
                                                    "  \"shapes\": [{\"type\": \"sphere\"}]\n}\n"),
                                   "t.json", ".", &s, &err),
               SS_OK, "%s", err.message);
  cr_expect_eq(s->materials[0].energy_compensation, 1, "on by default for translucent");
  cr_expect_str_eq(s->materials[0].bsdf.ops->name, "rough_dielectric_ms");
  ss_scene_destroy(s);
}
