/* A translucent material given by "albedo" and "mfp": the loader
 * converts them into a medium with the material's eta and g (the exact
 * inversion by default, each model's own on request), and every bad value or
 * pairing is one error naming the file, line and key. */
#include <criterion/criterion.h>

#include "subsurf/albedo_inversion.h"
#include "subsurf/scene_io.h"

#include <stdio.h>
#include <string.h>

static ss_status parse(const char *keys, ss_scene **s, ss_error *err) {
  char text[4096];
  snprintf(text, sizeof text,
           "{\"media\": [{\"name\": \"m\", \"sigma_s\": 4, \"sigma_a\": 0.2}],\n"
           " \"materials\": [\n"
           "  {\"name\": \"a\", \"type\": \"translucent\",\n"
           "   %s}],\n"
           " \"shapes\": [{\"name\": \"s1\", \"type\": \"sphere\", \"material\": \"a\"}],\n"
           " \"lights\": [{\"name\": \"l\", \"type\": \"point\", \"position\": [0, 5, 0]}]}\n",
           keys);
  return ss_scene_parse_json(text, "t.json", ".", s, err);
}

static const ss_medium *material_medium(const ss_scene *s) {
  cr_assert_geq(s->materials[0].medium, 0);
  return &s->media[s->materials[0].medium];
}

Test(scene_albedo, albedo_and_mfp_become_the_inverted_medium) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(parse("\"eta\": 1.4, \"albedo\": [0.8, 0.5, 0.2], \"mfp\": [2, 1, 0.5], \"g\": 0.6",
                     &s, &err),
               SS_OK, "%s", err.message);
  const ss_medium *m = material_medium(s);
  const double A[3] = {0.8, 0.5, 0.2}, mfp[3] = {2, 1, 0.5};
  for (int c = 0; c < 3; ++c) {
    double ss, sa;
    cr_assert_eq(ss_albedo_to_coefficients(SS_ALBEDO_INVERSION_EXACT, A[c], mfp[c], 0.6, 1.4, &ss,
                                           &sa, &err),
                 SS_OK);
    cr_expect_eq(m->optics.sigma_s.c[c], ss);
    cr_expect_eq(m->optics.sigma_a.c[c], sa);
    cr_expect_float_eq(m->sigma_t.c[c], 1.0 / mfp[c], 1e-12);
  }
  cr_expect_eq(m->optics.phase, SS_PHASE_HG);
  cr_expect_eq(m->optics.g.c[0], 0.6);
  ss_scene_destroy(s);
  /* index matched: eta 1; a model's own inversion on request */
  cr_assert_eq(parse("\"boundary\": \"index-matched\", \"albedo\": 0.5, \"mfp\": 1, "
                     "\"albedo_inversion\": \"dipole\", \"bssrdf\": \"burley\"",
                     &s, &err),
               SS_OK, "%s", err.message);
  double ss, sa;
  cr_assert_eq(
      ss_albedo_to_coefficients(SS_ALBEDO_INVERSION_DIPOLE, 0.5, 1.0, 0.0, 1.0, &ss, &sa, &err),
      SS_OK);
  cr_expect_eq(material_medium(s)->optics.sigma_s.c[1], ss);
  ss_scene_destroy(s);
}

Test(scene_albedo, bad_values_and_pairings_name_the_file_line_and_key) {
  const char *bad[][2] = {
      {"\"albedo\": 1.2, \"mfp\": 1", "t.json:4: materials[0].albedo: must lie in (0, 1), got 1.2"},
      {"\"albedo\": [0.5, 0, 0.5], \"mfp\": 1",
       "t.json:4: materials[0].albedo: must lie in (0, 1), got 0 in G"},
      {"\"albedo\": 0.5, \"mfp\": [1, 1, -2]",
       "t.json:4: materials[0].mfp: must be > 0 (with 1/mfp finite), got -2 in B"},
      {"\"albedo\": 0.5, \"mfp\": 0", "t.json:4: materials[0].mfp: must be > 0"},
      {"\"albedo\": 0.5", "t.json:4: materials[0].albedo: needs \"mfp\" as well"},
      {"\"mfp\": 0.5", "t.json:4: materials[0].mfp: needs \"albedo\" as well"},
      {"\"medium\": \"m\", \"albedo\": 0.5, \"mfp\": 1",
       "t.json:4: materials[0].albedo: give either a medium or albedo and mfp, not both"},
      {"\"medium\": \"m\", \"g\": 0.5", "t.json:4: materials[0].g: only with \"albedo\""},
      {"\"albedo\": 0.5, \"mfp\": 1, \"albedo_inversion\": \"jensen\"",
       "t.json:4: materials[0].albedo_inversion: unknown inversion 'jensen' (exact, dipole, pbd, "
       "burley)"},
      {"\"albedo\": 0.5, \"mfp\": 1, \"g\": 0.95",
       "t.json:4: materials[0].g: 0.95 is outside the exact albedo table's range"},
      {"\"eta\": 2.5, \"albedo\": 0.5, \"mfp\": 1",
       "t.json:4: materials[0].eta: 2.5 is outside the exact albedo table's range"},
      {"\"eta\": 1.5, \"albedo\": 0.97, \"mfp\": 1",
       "t.json:4: materials[0].albedo: albedo 0.97 is above 0.96"},
      {"\"albedo\": \"red\", \"mfp\": 1", "t.json:4: materials[0].albedo: expected a number or"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    ss_scene *s = NULL;
    ss_error err;
    cr_expect_eq(parse(bad[i][0], &s, &err), SS_ERR_PARSE, "%s", bad[i][0]);
    cr_expect_null(s);
    cr_expect(strstr(err.message, bad[i][1]) == err.message, "%s:\n got '%s'\n want '%s'",
              bad[i][0], err.message, bad[i][1]);
  }
}
