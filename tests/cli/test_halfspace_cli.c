#include "cli_run.h"

#include <cjson/cJSON.h>
#include <criterion/criterion.h>

static char dir[64];
static cli_result res;

static void setup(void) { cli_tmpdir(dir, sizeof dir); }

static void expect_bad_input(const char *args, const char *needle) {
  cli_expect_bad_input(&res, dir, args, needle);
}

TestSuite(halfspace_cli, .init = setup);

Test(halfspace_cli, bad_input_is_one_clear_line_and_exit_code_2) {
  const char *json = "--json out.json --map out.exr";
  char args[256];
  struct {
    const char *args, *needle;
  } cases[] = {
      {"--sigma-s -1", "--sigma-s"},
      {"--sigma-a nan", "--sigma-a"},
      {"--sigma-s abc", "--sigma-s"},
      {"--g 1", "--g"},
      {"--g -1.5 --phase hg", "--g"},
      {"--eta 0", "--eta"},
      {"--eta -1.3", "--eta"},
      {"--medium unobtainium", "--medium"},
      {"--frobnicate 3", "--frobnicate"},
      {"--theta-i 90", "--theta-i"},
      {"--thickness 0", "--thickness"},
      {"--phase rayleigh", "--phase"},
      {"--paths 0", "--paths"},
      {"--rbins 1", "--rbins"},
      {"--channel q --medium skin1", "--channel"},
      {"--sigma-s", "--sigma-s"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    snprintf(args, sizeof args, "halfspace %s %s", cases[i].args, json);
    expect_bad_input(args, cases[i].needle);
  }
  expect_bad_input("halfspace --json /nonexistent-dir/out.json", "/nonexistent-dir");
  expect_bad_input("halfspace --map out.bmp", "--map");
}

Test(halfspace_cli, json_output_has_the_contract_keys) {
  cli_run_in(&res, dir,
             "halfspace --paths 3000 --sigma-s 1 --sigma-a 0.1 --eta 1.33 --theta-i 30 "
             "--theta-o 0 --theta-o 45 --xbins 10 --rbins 8 --json out.json --quiet",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  char path[256], text[1 << 16];
  snprintf(path, sizeof path, "%s/out.json", dir);
  cli_slurp(path, text, sizeof text);
  cJSON *j = cJSON_Parse(text);
  cr_assert(j != NULL, "output is not JSON");
  cr_expect_str_eq(cJSON_GetObjectItem(j, "command")->valuestring, "halfspace");
  cr_expect_eq(cJSON_GetObjectItem(j, "paths")->valuedouble, 3000.0);
  const char *keys[] = {"params",   "seconds",  "reflectance", "transmittance",
                        "specular", "absorbed", "radial",      "directions"};
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; ++i) {
    cr_expect(cJSON_GetObjectItem(j, keys[i]) != NULL, "missing key %s", keys[i]);
  }
  cJSON *refl = cJSON_GetObjectItem(j, "reflectance");
  cr_expect(cJSON_GetObjectItem(refl, "value")->valuedouble > 0.1);
  cr_expect(cJSON_GetObjectItem(refl, "stderr")->valuedouble > 0.0);
  cJSON *radial = cJSON_GetObjectItem(j, "radial");
  cr_expect_eq(cJSON_GetArraySize(cJSON_GetObjectItem(radial, "r_lo")), 8);
  cr_expect_eq(cJSON_GetArraySize(cJSON_GetObjectItem(radial, "stderr")), 8);
  cJSON *dirs = cJSON_GetObjectItem(j, "directions");
  cr_expect_eq(cJSON_GetArraySize(dirs), 2);
  cJSON *d1 = cJSON_GetArrayItem(dirs, 1);
  cr_expect_eq(cJSON_GetObjectItem(d1, "theta_o")->valuedouble, 45.0);
  cr_expect_eq(cJSON_GetArraySize(cJSON_GetObjectItem(d1, "value")), 10);
  cJSON *params = cJSON_GetObjectItem(j, "params");
  cr_expect_eq(cJSON_GetObjectItem(params, "eta")->valuedouble, 1.33);
  cr_expect_eq(cJSON_GetObjectItem(params, "theta_i")->valuedouble, 30.0);
  cJSON_Delete(j);
}

Test(halfspace_cli, medium_preset_in_rgb_writes_a_colour_map) {
  cli_run_in(&res, dir,
             "halfspace --medium Skin1 --channel rgb --paths 3000 --xbins 16 --ybins 16 "
             "--map map.exr --json out.json --quiet",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(cli_file_exists(dir, "map.exr"));
  char path[256], text[1 << 16];
  snprintf(path, sizeof path, "%s/out.json", dir);
  cli_slurp(path, text, sizeof text);
  cJSON *j = cJSON_Parse(text);
  cr_assert(j != NULL);
  cJSON *ch = cJSON_GetObjectItem(j, "channels");
  cr_expect(cJSON_GetObjectItem(ch, "r") && cJSON_GetObjectItem(ch, "g") &&
            cJSON_GetObjectItem(ch, "b"));
  double rr =
      cJSON_GetObjectItem(cJSON_GetObjectItem(cJSON_GetObjectItem(ch, "r"), "reflectance"), "value")
          ->valuedouble;
  double rb =
      cJSON_GetObjectItem(cJSON_GetObjectItem(cJSON_GetObjectItem(ch, "b"), "reflectance"), "value")
          ->valuedouble;
  cr_expect(rr > rb, "skin reflects more red (%g) than blue (%g)", rr, rb);
  cJSON_Delete(j);
}

Test(halfspace_cli, ctrl_c_writes_what_it_has_marked_partial_and_exits_130) {
  cli_run_in(&res, dir,
             "halfspace --sigma-s 1 --sigma-a 0.0001 --paths 1e11 --json out.json --quiet", 1.0);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(cli_file_exists(dir, "out-partial.json"));
  cr_expect(!cli_file_exists(dir, "out.json"));
}

Test(halfspace_cli, help_lists_every_option_with_its_default) {
  cli_run_in(&res, dir, "halfspace --help", 0.0);
  cr_expect_eq(res.status, 0);
  const char *opts[] = {"--sigma-s", "--sigma-a",    "--g",      "--phase",   "--eta",
                        "--theta-i", "--thickness",  "--medium", "--scale",   "--channel",
                        "--paths",   "--time-limit", "--seed",   "--threads", "--rmax",
                        "--rbins",   "--theta-o",    "--xmin",   "--xmax",    "--xbins",
                        "--ymin",    "--ymax",       "--ybins",  "--json",    "--map"};
  for (size_t i = 0; i < sizeof opts / sizeof opts[0]; ++i) {
    cr_expect(strstr(res.out, opts[i]) != NULL, "--help misses %s", opts[i]);
  }
}

Test(halfspace_cli, json_output_names_the_version_of_subsurf_first) {
  cli_run_in(&res, dir, "--version", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  char version[64];
  cr_assert_eq(sscanf(res.out, "subsurf %63s", version), 1, "--version printed '%s'", res.out);
  int major, minor, patch;
  cr_expect_eq(sscanf(version, "%d.%d.%d", &major, &minor, &patch), 3, "version '%s'", version);

  cli_run_in(&res, dir, "halfspace --paths 1000 --sigma-s 1 --sigma-a 0.1 --json - --quiet", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *j = cJSON_Parse(res.out);
  cr_assert(j != NULL, "output is not JSON: %s", res.out);
  cr_assert(j->child && !strcmp(j->child->string, "subsurf_version"),
            "first key is not the version");
  cr_expect_str_eq(j->child->valuestring, version);
  cr_expect_str_eq(cJSON_GetObjectItem(j, "command")->valuestring, "halfspace");
  cJSON_Delete(j);
}
