/* The pbrt-v3 importer's tokenizer and directives: comments, strings and
 * arrays read as pbrt-v3 reads them; Include resolves against the top-level
 * file's directory; syntax errors name FILE:LINE and what was expected;
 * what subsurf ignores or approximates is a warning with FILE:LINE. */
#include "io/pbrt_test.h"

#include <math.h>
#include <sys/stat.h>

Test(pbrt_syntax, comments_strings_and_arrays_tokenize_as_pbrt) {
  char dir[64];
  pbrt_tmpdir(dir, sizeof dir);
  const char *text = PBRT_TEST_HEADER
      "# a comment with \"quotes\" and [brackets]\n"
      "MakeNamedMaterial \"red # not a comment\" # a trailing comment\n"
      "  \"string type\" \"matte\"\n"
      "  \"rgb Kd\" [ 0.5\n 0.25   # inside an array\n 0.125 ]\n"
      "NamedMaterial \"red # not a comment\"\n"
      "Shape \"trianglemesh\" \"point P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n"
      "Shape \"sphere\" \"float radius\" .5 \"integer subdivisions\" 0\n"
      "WorldEnd\n";
  ss_scene *s = NULL;
  pbrt_warnings w;
  ss_error err;
  cr_assert_eq(pbrt_read(dir, "t.pbrt", text, &s, &w, &err), SS_OK, "%s", err.message);
  cr_expect_eq(w.count, 0, "%s", w.text);
  cr_assert_eq(s->num_shapes, 2);
  const ss_material *m = &s->materials[s->shapes[0].material];
  cr_expect_eq(m->kind, SS_MATERIAL_DIFFUSE);
  cr_expect_eq(m->albedo.c[0], 0.5);
  cr_expect_eq(m->albedo.c[1], 0.25);
  cr_expect_eq(m->albedo.c[2], 0.125);
  cr_expect_eq(s->shapes[1].mesh->num_triangles, 20u);
  ss_scene_destroy(s);
  pbrt_rmdir(dir);
}

Test(pbrt_syntax, include_paths_start_at_the_top_level_files_directory) {
  char dir[64], sub[128];
  pbrt_tmpdir(dir, sizeof dir);
  snprintf(sub, sizeof sub, "%s/sub", dir);
  cr_assert_eq(mkdir(sub, 0700), 0);
  /* as pbrt-v3: sub/a.pbrt names sub/b.pbrt from the top-level directory */
  pbrt_write(dir, "sub/a.pbrt", "Include \"sub/b.pbrt\"\nShape \"sphere\"\n");
  pbrt_write(dir, "sub/b.pbrt", "Material \"glass\"\n");
  ss_scene *s = NULL;
  pbrt_warnings w;
  ss_error err;
  cr_assert_eq(pbrt_read(dir, "main.pbrt", PBRT_TEST_HEADER "Import \"sub/a.pbrt\"\nWorldEnd\n", &s,
                         &w, &err),
               SS_OK, "%s", err.message);
  cr_assert_eq(s->num_shapes, 1);
  cr_expect_eq(s->materials[s->shapes[0].material].boundary, SS_BOUNDARY_SMOOTH);
  cr_expect_eq(s->materials[s->shapes[0].material].eta, 1.5);
  ss_scene_destroy(s);

  /* a missing file is named with the line of the Include */
  cr_expect_neq(
      pbrt_read(dir, "main.pbrt", PBRT_TEST_HEADER "\nInclude \"sub/nope.pbrt\"\n", &s, &w, &err),
      SS_OK);
  cr_expect(strstr(err.message, "main.pbrt:8: Include \"sub/nope.pbrt\"") &&
                strstr(err.message, "cannot open"),
            "%s", err.message);
  cr_expect_eq(err.status, SS_ERR_IO);
  /* an include cycle stops */
  pbrt_write(dir, "sub/loop.pbrt", "Include \"sub/loop.pbrt\"\n");
  cr_expect_neq(
      pbrt_read(dir, "main.pbrt", PBRT_TEST_HEADER "Include \"sub/loop.pbrt\"\n", &s, &w, &err),
      SS_OK);
  cr_expect(strstr(err.message, "nested includes"), "%s", err.message);
  pbrt_rmdir(dir);
}

/* Each malformed file fails with FILE:LINE and what was expected. */
Test(pbrt_syntax, syntax_errors_name_the_file_line_and_what_was_expected) {
  static const struct {
    const char *tail, *needle;
  } cases[] = {
      {"Shape \"sphere\" \"float radius\" [1\n",
       "t.pbrt:8: parameter \"float radius\": expected "
       "']' to close the array opened on line 7, got end of file"},
      {"Material \"matte\" \"rgb Kd\" [0.5 0.5 \"x\"]\n", "t.pbrt:7: parameter \"rgb Kd\": "
                                                          "expected numbers, got 'x'"},
      {"Shape \"sphere\" \"float radius\" \"big\"\n", "t.pbrt:7: parameter \"float radius\": "
                                                      "expected numbers"},
      {"Shape \"sphere\" \"float radius\" 1.2.3\n", "t.pbrt:7: expected a finite number, got "
                                                    "'1.2.3'"},
      {"Shape \"sphere\n\"\n", "t.pbrt:7: unterminated string"},
      {"Shape \"sphere\" \"radius\" 1\n", "t.pbrt:7: expected a parameter declaration \"TYPE "
                                          "NAME\", got \"radius\""},
      {"Shape \"sphere\" \"real radius\" 1\n", "t.pbrt:7: unknown parameter type 'real'"},
      {"Shpae \"sphere\"\n", "t.pbrt:7: unknown directive 'Shpae'"},
      {"AttributeBegin\n\"float radius\" 1\n", "t.pbrt:8: expected a directive, got \"float "
                                               "radius\""},
      {"AttributeEnd\n", "t.pbrt:7: AttributeEnd without a matching AttributeBegin"},
      {"AttributeBegin\nTransformEnd\n", "t.pbrt:8: TransformEnd without a matching "
                                         "TransformBegin (an AttributeBegin is open)"},
      {"Translate 1 2\nWorldEnd\n", "t.pbrt:8: Translate: expected 3 numbers, got WorldEnd"},
      {"Shape \"sphere\"\n", "t.pbrt:8: end of file before WorldEnd (truncated?)"},
      {"NamedMaterial \"nope\"\nWorldEnd\n", "t.pbrt:7: NamedMaterial: no material named \"nope\""},
      {"Camera \"perspective\"\nWorldEnd\n", "t.pbrt:7: Camera must come before WorldBegin"},
      {"Shape \"trianglemesh\" \"point P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 3]\n"
       "WorldEnd\n",
       "t.pbrt:7: Shape \"trianglemesh\": index 2 is 3, not a vertex of P (0..2)"},
      {"MediumInterface \"fog\"\nWorldEnd\n", "t.pbrt:7: MediumInterface: no medium named \"fog\""},
      {"WorldEnd\nShape \"sphere\"\n", "t.pbrt:8: 'Shape' after WorldEnd"},
  };
  char dir[64];
  pbrt_tmpdir(dir, sizeof dir);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char text[2048];
    snprintf(text, sizeof text, "%s%s", PBRT_TEST_HEADER, cases[i].tail);
    ss_scene *s = NULL;
    pbrt_warnings w;
    ss_error err;
    cr_expect_eq(pbrt_read(dir, "t.pbrt", text, &s, &w, &err), SS_ERR_PARSE, "case %zu", i);
    cr_expect_null(s);
    cr_expect(strstr(err.message, cases[i].needle), "case %zu: '%s' lacks '%s'", i, err.message,
              cases[i].needle);
  }
  pbrt_rmdir(dir);
}

/* What subsurf does not do is never silent: each line gets a warning. */
Test(pbrt_syntax, unsupported_directives_and_parameters_warn_with_file_and_line) {
  static const struct {
    const char *tail, *needle;
  } cases[] = {
      {"Shape \"cylinder\"\n", "t.pbrt:7: Shape \"cylinder\" is not supported (left out)"},
      {"Shape \"sphere\" \"float zmin\" 0\n", "t.pbrt:7: Shape \"sphere\": zmin, zmax and phimax"},
      {"Shape \"sphere\"\n  \"float wobble\" 2\n",
       "t.pbrt:8: Shape \"sphere\": parameter \"float wobble\" is not supported (ignored)"},
      {"TransformTimes 0 1\n", "t.pbrt:7: TransformTimes is not supported (ignored)"},
      {"Material \"plastic\"\nShape \"sphere\"\n", "t.pbrt:7: plastic is not supported; a diffuse"},
      {"Material \"matte\" \"float sigma\" 20\nShape \"sphere\"\n",
       "t.pbrt:7: Material \"matte\": sigma (Oren-Nayar roughness) is not supported"},
      {"Material \"glass\" \"rgb Kr\" [0.5 0.5 0.5]\nShape \"sphere\"\n",
       "t.pbrt:7: Material \"glass\": Kr (0.5 0.5 0.5) is not supported"},
      {"LightSource \"goniometric\"\n", "t.pbrt:7: LightSource \"goniometric\" is not supported"},
      {"AttributeBegin\nMaterial \"none\"\nShape \"sphere\"\nAttributeEnd\n",
       "t.pbrt:9: Shape \"sphere\" with Material \"none\" and no inside medium is invisible (left "
       "out)"},
      {"MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\nMediumInterface \"\" \"m\"\n",
       "t.pbrt:8: MediumInterface: outside medium \"m\" ignored"},
      {"Texture \"t\" \"spectrum\" \"marble\"\n",
       "t.pbrt:7: Texture \"t\" \"marble\": texture class \"marble\" is not supported"},
  };
  char dir[64];
  pbrt_tmpdir(dir, sizeof dir);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char text[2048];
    snprintf(text, sizeof text, "%s%sShape \"sphere\" \"integer subdivisions\" 0\nWorldEnd\n",
             PBRT_TEST_HEADER, cases[i].tail);
    ss_scene *s = NULL;
    pbrt_warnings w;
    ss_error err;
    cr_expect_eq(pbrt_read(dir, "t.pbrt", text, &s, &w, &err), SS_OK, "case %zu: %s", i,
                 err.message);
    cr_expect(strstr(w.text, cases[i].needle), "case %zu: warnings '%s' lack '%s'", i, w.text,
              cases[i].needle);
    ss_scene_destroy(s);
  }
  /* and a directive before WorldBegin that belongs in the world is ignored
   * with a warning, as pbrt-v3 does */
  ss_scene *s = NULL;
  pbrt_warnings w;
  ss_error err;
  cr_expect_eq(pbrt_read(dir, "t.pbrt",
                         "Shape \"sphere\"\nWorldBegin\nLightSource \"point\"\n"
                         "Shape \"trianglemesh\" \"point P\" [0 0 0 1 0 0 0 1 0]\nWorldEnd\n",
                         &s, &w, &err),
               SS_OK, "%s", err.message);
  cr_expect(strstr(w.text, "t.pbrt:1: Shape before WorldBegin is ignored"), "%s", w.text);
  cr_expect_eq(s->num_shapes, 1);
  ss_scene_destroy(s);
  pbrt_rmdir(dir);
}
