/* `subsurf render` with the hierarchical integrator: bad scene options and
 * non-radial kernels exit 2 naming them; --irradiance-cache writes the
 * points, reuses them for the same scene (the image identical to the first
 * render's) and names a damaged or stale file before rebuilding it;
 * `subsurf compare` prepares the integrator (pass 1 and the octrees) once
 * for all its passes. */
#include "cli/cli_files.h"
#include "cli/cli_run.h"

#include <criterion/criterion.h>

CLI_SUITE(hierarchical_cli);

/* A small dipole sphere lit by a sky; `extra` is appended to the integrator
 * object, `model` names the material's model. */
static void write_scene(const char *name, const char *model, const char *extra, double sky) {
  char text[2048];
  snprintf(text, sizeof text,
           "{\"camera\": {\"resolution\": [8, 8], \"position\": [0, 0, 4]},\n"
           " \"media\": [{\"name\": \"m\", \"sigma_s\": 4, \"sigma_a\": 0.5}],\n"
           " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"boundary\": "
           "\"smooth\", \"eta\": 1.3, \"medium\": \"m\", \"bssrdf\": \"%s\"}],\n"
           " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"t\"}],\n"
           " \"lights\": [{\"type\": \"environment\", \"radiance\": %g}],\n"
           " \"integrator\": {\"type\": \"hierarchical\", \"irradiance_samples\": 4%s},\n"
           " \"render\": {\"spp\": 1}}\n",
           model, sky, extra);
  cli_write_file(dir, name, text);
}

Test(hierarchical_cli, bad_options_and_kernels_exit_2_naming_them) {
  static const struct {
    const char *extra, *model, *needle;
  } cases[] = {
      {", \"epsilon\": 0", "dipole", "epsilon"},
      {", \"epsilon\": -0.5", "dipole", "epsilon"},
      {", \"points\": 0", "dipole", "points"},
      {", \"points\": 1.5", "dipole", "points"},
      {"", "fwddip", "radially symmetric"},
      {"", "single", "radially symmetric"},
      {", \"near_field\": -1", "dipole", "near_field"},
      {", \"near_field\": 17", "dipole", "near_field"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    write_scene("s.json", cases[i].model, cases[i].extra, 1.0);
    cli_expect_bad_input(&res, dir, "render s.json -o out.exr --quiet", cases[i].needle);
  }
}

static void render(const char *scene, const char *out, const char *cache) {
  char args[256];
  snprintf(args, sizeof args, "render %s -o %s --no-png --quiet --irradiance-cache %s", scene, out,
           cache);
  cli_run_in(&res, dir, args, 0.0);
  cr_assert_eq(res.status, 0, "%s: %s", args, res.err);
}

static int same_file(const char *a, const char *b) {
  char pa[128], pb[128];
  snprintf(pa, sizeof pa, "%s/%s", dir, a);
  snprintf(pb, sizeof pb, "%s/%s", dir, b);
  FILE *fa = fopen(pa, "rb"), *fb = fopen(pb, "rb");
  int same = fa && fb;
  while (same) {
    int ca = fgetc(fa), cb = fgetc(fb);
    same = ca == cb;
    if (ca == EOF || cb == EOF) {
      break;
    }
  }
  if (fa)
    fclose(fa);
  if (fb)
    fclose(fb);
  return same;
}

Test(hierarchical_cli, cache_is_reused_and_a_bad_one_is_named_and_rebuilt) {
  write_scene("s.json", "dipole", ", \"points\": 300", 1.0);
  render("s.json", "a.exr", "c.irr");
  cr_assert(cli_file_exists(dir, "c.irr"));
  cr_expect_eq(res.err[0], '\0', "%s", res.err);
  render("s.json", "b.exr", "c.irr");
  cr_expect_eq(res.err[0], '\0', "a valid cache was refused: %s", res.err);
  cr_expect(same_file("a.exr", "b.exr"), "the image from the cache differs");
  /* a flipped byte in the middle */
  char path[128];
  snprintf(path, sizeof path, "%s/c.irr", dir);
  FILE *f = fopen(path, "r+b");
  cr_assert(f);
  fseek(f, 100, SEEK_SET);
  int c = fgetc(f);
  fseek(f, 100, SEEK_SET);
  fputc(c ^ 0x40, f);
  fclose(f);
  render("s.json", "c.exr", "c.irr");
  cr_expect(strstr(res.err, "c.irr") && strstr(res.err, "rebuilding"), "%s", res.err);
  cr_expect(same_file("a.exr", "c.exr"), "the rebuilt points differ");
  /* other lighting: stale */
  write_scene("s.json", "dipole", ", \"points\": 300", 2.0);
  render("s.json", "d.exr", "c.irr");
  cr_expect(strstr(res.err, "stale"), "%s", res.err);
  cr_expect(!same_file("a.exr", "d.exr"), "the stale points were used");
  /* truncated */
  cr_assert_eq(truncate(path, 60), 0);
  render("s.json", "e.exr", "c.irr");
  cr_expect(strstr(res.err, "truncated"), "%s", res.err);
  cr_expect(same_file("d.exr", "e.exr"));
}

static double method_number(const cJSON *root, int i, const char *key) {
  const cJSON *m = cJSON_GetArrayItem(cJSON_GetObjectItem(root, "methods"), i);
  const cJSON *v = cJSON_GetObjectItem(m, key);
  cr_assert(cJSON_IsNumber(v), "method %d: no number '%s'", i, key);
  return v->valuedouble;
}

Test(hierarchical_cli, compare_prepares_each_method_once_for_all_its_passes) {
  write_scene("s.json", "dipole", ", \"points\": 300", 1.0);
  cli_run_in(&res, dir,
             "compare s.json --methods hierarchical,volpath --spp 8 --reference-spp 4 -o c --quiet",
             0.0);
  cr_assert_eq(res.status, 0, "exit %d: %s", res.status, res.err);
  cJSON *root = cli_load_json(dir, "c/results.json");
  const cJSON *passes =
      cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(root, "methods"), 0), "passes");
  cr_expect_eq(cJSON_GetArraySize(passes), 4, "passes of 1, 2, 4 and 8 spp");
  cr_expect_eq(method_number(root, 0, "prepares"), 1.0, "hierarchical prepared once");
  cr_expect_eq(method_number(root, 1, "prepares"), 1.0, "volpath (its media) prepared once");
  cJSON_Delete(root);
}
