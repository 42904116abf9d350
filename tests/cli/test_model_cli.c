#include "cli_files.h"

#include <cjson/cJSON.h>
#include <criterion/criterion.h>
#include <math.h>

static char dir[64];
static cli_result res;

static void setup(void) { cli_tmpdir(dir, sizeof dir); }

static void expect_bad_input(const char *args, const char *needle) {
  cli_expect_bad_input(&res, dir, args, needle);
}

static cJSON *load_json(const char *name) { return cli_load_json(dir, name); }

TestSuite(model_cli, .init = setup);

Test(model_cli, json_has_the_halfspace_keys_on_the_same_bins) {
  const char *common = "--sigma-s 1 --sigma-a 0.05 --eta 1.33 --theta-i 30 --theta-o 0 "
                       "--theta-o 45 --xbins 10 --rbins 8";
  char args[512];
  snprintf(args, sizeof args, "model --model dipole %s --profile-r 0.1,0.5,2 --json m.json",
           common);
  cli_run_in(&res, dir, args, 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  snprintf(args, sizeof args, "halfspace --paths 500 --quiet %s --json h.json", common);
  cli_run_in(&res, dir, args, 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *m = load_json("m.json"), *h = load_json("h.json");
  cr_expect_str_eq(cJSON_GetObjectItem(m, "command")->valuestring, "model");
  cr_expect_str_eq(cJSON_GetObjectItem(m, "model")->valuestring, "dipole");
  const char *keys[] = {"params",     "reflectance", "transmittance",
                        "specular",   "absorbed",    "radial",
                        "directions", "rd",          "profile"};
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; ++i) {
    cr_expect(cJSON_GetObjectItem(m, keys[i]) != NULL, "missing key %s", keys[i]);
  }
  /* Identical bins, key by key. */
  cJSON *mr = cJSON_GetObjectItem(m, "radial"), *hr = cJSON_GetObjectItem(h, "radial");
  for (int i = 0; i < 8; ++i) {
    cr_expect_eq(cJSON_GetArrayItem(cJSON_GetObjectItem(mr, "r_hi"), i)->valuedouble,
                 cJSON_GetArrayItem(cJSON_GetObjectItem(hr, "r_hi"), i)->valuedouble);
  }
  cJSON *md = cJSON_GetObjectItem(m, "directions");
  cr_expect_eq(cJSON_GetArraySize(md), 2);
  cr_expect_eq(cJSON_GetArraySize(cJSON_GetObjectItem(cJSON_GetArrayItem(md, 1), "value")), 10);
  cJSON *prof = cJSON_GetObjectItem(m, "profile");
  const char *pk[] = {"r", "value", "ms", "ss"};
  for (int i = 0; i < 4; ++i) {
    cr_expect_eq(cJSON_GetArraySize(cJSON_GetObjectItem(prof, pk[i])), 3, "profile.%s", pk[i]);
  }
  /* Jensen et al. 2001 closed form for alpha' = 1/1.05 at eta 1.33. */
  double ap = 1.0 / 1.05, s = sqrt(3.0 * (1.0 - ap));
  double fdr = -1.4399 / (1.33 * 1.33) + 0.7099 / 1.33 + 0.6681 + 0.0636 * 1.33;
  double A = (1.0 + fdr) / (1.0 - fdr);
  double rd = 0.5 * ap * (1.0 + exp(-4.0 / 3.0 * A * s)) * exp(-s);
  cr_expect(fabs(cJSON_GetObjectItem(m, "rd")->valuedouble - rd) < 1e-12);
  cJSON_Delete(m);
  cJSON_Delete(h);
}

Test(model_cli, medium_preset_gives_the_papers_rd_per_channel) {
  cli_run_in(&res, dir, "model --model dipole --medium Skin1 --channel rgb --json - ", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *j = cJSON_Parse(res.out);
  cr_assert(j != NULL);
  cJSON *ch = cJSON_GetObjectItem(j, "channels");
  const double paper[3] = {0.44, 0.22, 0.13};
  const char *names[3] = {"r", "g", "b"};
  for (int c = 0; c < 3; ++c) {
    cJSON *one = cJSON_GetObjectItem(ch, names[c]);
    cr_assert(one != NULL, "channel %s", names[c]);
    double rd = cJSON_GetObjectItem(one, "rd")->valuedouble;
    cr_expect(fabs(rd - paper[c]) < 0.01, "%s: %g vs %g", names[c], rd, paper[c]);
  }
  cJSON_Delete(j);
}

Test(model_cli, every_model_answers) {
  const char *models[] = {"dipole",  "single",    "dipole-brdf", "better-dipole",
                          "dirpole", "multipole", "layers"};
  for (size_t i = 0; i < sizeof models / sizeof models[0]; ++i) {
    char args[256];
    snprintf(args, sizeof args,
             "model --model %s --sigma-s 2 --sigma-a 0.02 --theta-o 20 --xbins 4 --rbins 6 "
             "--json -",
             models[i]);
    cli_run_in(&res, dir, args, 0.0);
    cr_expect_eq(res.status, 0, "%s: %s", models[i], res.err);
    cJSON *j = cJSON_Parse(res.out);
    cr_expect(j != NULL, "%s: no JSON", models[i]);
    if (j) {
      double r = cJSON_GetObjectItem(cJSON_GetObjectItem(j, "reflectance"), "value")->valuedouble;
      cr_expect(r > 0.0 && r < 1.5, "%s: reflectance %g", models[i], r);
      cJSON_Delete(j);
    }
  }
}

Test(model_cli, bad_input_is_one_clear_line_and_exit_code_2) {
  expect_bad_input("model --sigma-s 1 --json o.json", "--model");
  expect_bad_input("model --model nonesuch --json o.json", "nonesuch");
  expect_bad_input("model --model dipole --profile-r 0.1,x --json o.json", "--profile-r");
  expect_bad_input("model --model dipole --profile-r=-1 --json o.json", "--profile-r");
  expect_bad_input("model --model dipole --thickness 2 --json o.json", "--thickness");
  expect_bad_input("model --model multipole --thickness 0.1 --json o.json", "thickness");
  expect_bad_input("model --model multipole --thickness 0 --json o.json", "--thickness");
  expect_bad_input("model --model dipole --theta-i 90 --json o.json", "--theta-i");
  expect_bad_input("model --model dipole --sigma-a -1 --json o.json", "--sigma-a");
  expect_bad_input("model --model dipole --paths 10 --json o.json", "--paths");
  expect_bad_input("model --model dipole --json /nonexistent-dir/o.json", "/nonexistent-dir");
  expect_bad_input("compare-halfspace --sigma-s 1 --json o.json", "--models");
  expect_bad_input("compare-halfspace --models dipole,nonesuch --json o.json", "nonesuch");
  expect_bad_input("compare-halfspace --models dipole --plot p.png", "--plot");
  expect_bad_input("compare-halfspace --models dipole --medium Skin1 --channel rgb", "--channel");
  expect_bad_input("compare-halfspace --models dipole --thickness 2 --paths 10", "--thickness");
}

Test(model_cli, compare_writes_the_error_table_json_and_plot) {
  cli_run_in(&res, dir,
             "compare-halfspace --models dipole,better-dipole --sigma-s 1 --sigma-a 0.02 "
             "--eta 1.33 --paths 4000 --threads 1 --quiet --rbins 16 --plot p.svg --json c.json",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(strstr(res.out, "better-dipole") != NULL, "%s", res.out);
  cr_expect(strstr(res.out, "reference: halfspace") != NULL, "%s", res.out);
  cr_expect(cli_file_exists(dir, "p.svg"));
  cJSON *j = load_json("c.json");
  cJSON *models = cJSON_GetObjectItem(j, "models");
  cJSON *dip = cJSON_GetObjectItem(models, "dipole");
  cr_assert(dip != NULL);
  cJSON *err = cJSON_GetObjectItem(dip, "errors");
  cr_expect(cJSON_GetObjectItem(err, "reflectance_relative") != NULL);
  cr_expect(cJSON_GetObjectItem(cJSON_GetObjectItem(j, "reference"), "radial") != NULL);
  cJSON_Delete(j);
}
