/* A translucent material's "bssrdf" in a scene file: a model name or an
 * object of the model and its options, read by name with no per-model code;
 * the scene builds one BSSRDF per distinct material; a bad model, option or
 * value is one error naming the file, line and key. */
#include <criterion/criterion.h>

#include "subsurf/scene_io.h"

#include <stdio.h>
#include <string.h>

/* Two translucent spheres with the given "bssrdf" values. */
static ss_status parse(const char *bssrdf_a, const char *bssrdf_b, ss_scene **s, ss_error *err) {
  char text[4096];
  snprintf(text, sizeof text,
           "{\"media\": [{\"name\": \"m\", \"sigma_s\": 4, \"sigma_a\": 0.2}],\n"
           " \"materials\": [\n"
           "  {\"name\": \"a\", \"type\": \"translucent\", \"medium\": \"m\",\n"
           "   \"bssrdf\": %s},\n"
           "  {\"name\": \"b\", \"type\": \"translucent\", \"medium\": \"m\",\n"
           "   \"bssrdf\": %s}],\n"
           " \"shapes\": [{\"name\": \"s1\", \"type\": \"sphere\", \"material\": \"a\"},\n"
           "  {\"name\": \"s2\", \"type\": \"sphere\", \"center\": [3, 0, 0], \"material\": "
           "\"b\"}],\n"
           " \"lights\": [{\"name\": \"l\", \"type\": \"point\", \"position\": [0, 5, 0]}]}\n",
           bssrdf_a, bssrdf_b);
  return ss_scene_parse_json(text, "t.json", ".", s, err);
}

Test(scene_bssrdf, options_are_set_by_name_and_identical_materials_share_a_bssrdf) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(parse("{\"model\": \"pbd\", \"beam_samples\": 50}",
                     "{\"model\": \"pbd\", \"beam_samples\": 50}", &s, &err),
               SS_OK, "%s", err.message);
  const ss_bssrdf *a = ss_subsurface_bssrdf(s->subsurface, 0);
  cr_assert_not_null(a);
  cr_expect_eq(a, ss_subsurface_bssrdf(s->subsurface, 1));
  cr_expect_eq(ss_subsurface_count(s->subsurface), 1);
  cr_expect_str_eq(ss_bssrdf_name(a), "pbd");
  cr_expect_eq(ss_bssrdf_get_params(a)->n_options, 1);
  cr_expect_float_eq(ss_bssrdf_get_params(a)->medium.sigma_s.c[0], 4.0, 1e-15);
  ss_scene_destroy(s);
  cr_assert_eq(parse("\"dipole\"", "{\"model\": \"dipole\", \"min_distance\": true}", &s, &err),
               SS_OK, "%s", err.message);
  cr_expect_eq(ss_subsurface_count(s->subsurface), 2, "different options share a BSSRDF");
  ss_scene_destroy(s);
}

Test(scene_bssrdf, a_bad_model_option_or_value_names_the_file_line_and_key) {
  const char *bad[][2] = {
      {"\"dipol\"", "t.json:4: materials[0].bssrdf: unknown BSSRDF model 'dipol'"},
      {"{\"model\": \"pbd\", \"beam_sample\": 8}",
       "t.json:4: materials[0].bssrdf.beam_sample: pbd: unknown option 'beam_sample'"},
      {"{\"model\": \"pbd\", \"beam_samples\": 3}",
       "t.json:4: materials[0].bssrdf.beam_samples: pbd: option beam_samples: expected"},
      {"{\"beam_samples\": 8}", "t.json:4: materials[0].bssrdf: a BSSRDF object needs"},
      {"{\"model\": \"dipole\", \"min_distance\": [1]}",
       "t.json:4: materials[0].bssrdf.min_distance: expected a number, a boolean or a string"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    ss_scene *s;
    ss_error err;
    cr_expect_neq(parse(bad[i][0], "\"dipole\"", &s, &err), SS_OK, "%s was accepted", bad[i][0]);
    cr_expect(!strncmp(err.message, bad[i][1], strlen(bad[i][1])), "%s: got '%s'", bad[i][0],
              err.message);
  }
}

/* "render": {"table_cache": ...} (table_cache.h): a directory relative to
 * the scene file, false for none; anything else names the file, line and key. */
static ss_status parse_cache(const char *value, ss_scene **s, ss_error *err) {
  char text[1024];
  snprintf(text, sizeof text,
           "{\"render\": {\"table_cache\": %s},\n"
           " \"shapes\": [{\"name\": \"s1\", \"type\": \"sphere\"}]}\n",
           value);
  return ss_scene_parse_json(text, "t.json", "scenes", s, err);
}

Test(scene_bssrdf, table_cache_is_a_directory_beside_the_scene_or_off) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(parse_cache("\"cache\"", &s, &err), SS_OK, "%s", err.message);
  cr_expect_eq(s->render.table_cache, 1);
  cr_expect_str_eq(s->render.table_cache_dir, "scenes/cache");
  ss_scene_destroy(s);
  cr_assert_eq(parse_cache("false", &s, &err), SS_OK, "%s", err.message);
  cr_expect_eq(s->render.table_cache, 0);
  char dir[64] = "x";
  ss_subsurface_cache_dir(s, dir, sizeof dir);
  cr_expect_str_eq(dir, "", "a cache that is off has no directory");
  ss_scene_destroy(s);
  const char *bad[] = {"3", "\"\"", "[\"a\"]"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
    cr_expect_eq(parse_cache(bad[i], &s, &err), SS_ERR_PARSE, "%s accepted", bad[i]);
    cr_expect(strstr(err.message, "t.json:1: render.table_cache: expected true, false or a "
                                  "directory name") == err.message,
              "%s: %s", bad[i], err.message);
  }
}
