/* `subsurf layer`: the JSON keys, the library's numbers, stack files, bad
 * input and Ctrl-C. */
#include "cli_files.h"
#include "cli_run.h"

#include "subsurf/layer.h"
#include "subsurf/sampling.h"

#include <cjson/cJSON.h>
#include <criterion/criterion.h>
#include <math.h>

CLI_SUITE(layer_cli);

static double value(const cJSON *obj, const char *key) {
  const cJSON *v = cJSON_GetObjectItem(cJSON_GetObjectItem(obj, key), "value");
  cr_assert(cJSON_IsNumber(v), "no number at %s", key);
  return v->valuedouble;
}

Test(layer_cli, json_has_the_keys_and_the_library_numbers) {
  cli_run_in(&res, dir,
             "layer --sigma-s 0.9 --sigma-a 0.1 --g 0.7 --phase hg --eta 1.5 --theta-i 30 "
             "--thickness 1 --theta-o 0 --theta-o -60 --json out.json --quiet",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *j = cli_load_json(dir, "out.json");
  cr_expect_str_eq(cJSON_GetObjectItem(j, "command")->valuestring, "layer");
  ss_layer_params p;
  ss_layer_params_default(&p);
  p.layers[0].albedo = 0.9;
  ss_phase_init(&p.layers[0].phase, SS_PHASE_HG, 0.7, NULL);
  p.eta = 1.5;
  p.theta_i = 30.0 * SS_PI / 180.0;
  p.n_theta_o = 2;
  p.theta_o[0] = 0.0;
  p.theta_o[1] = -60.0 * SS_PI / 180.0;
  ss_layer_result r;
  cr_assert_eq(ss_layer_adding(&p, &r, NULL), SS_OK);
  cr_expect(fabs(value(j, "specular") - r.specular) < 1e-12);
  cr_expect(fabs(value(j, "reflectance") - r.reflectance) < 1e-12);
  cr_expect(fabs(value(j, "reflectance_unscattered") - r.reflectance_unscattered) < 1e-12);
  cr_expect(fabs(value(j, "transmittance") - r.transmittance) < 1e-12);
  cr_expect(fabs(value(j, "transmittance_unscattered") - r.transmittance_unscattered) < 1e-12);
  cr_expect(fabs(value(j, "absorbed") - r.absorbed) < 1e-12);
  const cJSON *brdf = cJSON_GetObjectItem(j, "brdf"), *btdf = cJSON_GetObjectItem(j, "btdf");
  cr_assert_eq(cJSON_GetArraySize(brdf), 2);
  cr_assert_eq(cJSON_GetArraySize(btdf), 2);
  for (int k = 0; k < 2; ++k) {
    const cJSON *b = cJSON_GetArrayItem(brdf, k), *t = cJSON_GetArrayItem(btdf, k);
    cr_expect(fabs(cJSON_GetObjectItem(b, "theta_o")->valuedouble - (k ? -60.0 : 0.0)) < 1e-12);
    cr_expect(fabs(cJSON_GetObjectItem(b, "value")->valuedouble - r.brdf[k]) < 1e-12);
    cr_expect(fabs(cJSON_GetObjectItem(t, "value")->valuedouble - r.btdf[k]) < 1e-12);
  }
  cJSON_Delete(j);
}

Test(layer_cli, stack_file_equals_the_same_layers_on_the_command_line) {
  /* Two halves of a slab in a stack file, against the slab. */
  cli_write_file(dir, "stack.json",
                 "{\"eta\": 1.33, \"bottom\": \"diffuse:0.5\", \"layers\": [\n"
                 "  {\"sigma_s\": 1.8, \"sigma_a\": 0.2, \"thickness\": 0.25, \"phase\": \"hg\","
                 " \"g\": 0.5},\n"
                 "  {\"tau\": 0.5, \"albedo\": 0.9, \"phase\": \"hg\", \"g\": 0.5}]}\n");
  cli_run_in(&res, dir, "layer --stack stack.json --theta-i 40 --theta-o 10 --json s.json", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cli_run_in(&res, dir,
             "layer --sigma-s 0.9 --sigma-a 0.1 --g 0.5 --phase hg --eta 1.33 --bottom diffuse:0.5 "
             "--theta-i 40 --theta-o 10 --json l.json",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *s = cli_load_json(dir, "s.json"), *l = cli_load_json(dir, "l.json");
  cr_expect(fabs(value(s, "reflectance") - value(l, "reflectance")) < 1e-7, "%g against %g",
            value(s, "reflectance"), value(l, "reflectance"));
  double fs = cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(s, "brdf"), 0), "value")
                  ->valuedouble;
  double fl = cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(l, "brdf"), 0), "value")
                  ->valuedouble;
  cr_expect(fabs(fs / fl - 1.0) < 1e-6, "brdf %g against %g", fs, fl);
  cr_expect(value(s, "transmittance") == 0.0);
  cJSON_Delete(s);
  cJSON_Delete(l);
}

Test(layer_cli, first_order_method_and_packing) {
  /* Blinn's packing density D is the optical depth tau / (1 - D). */
  cli_run_in(&res, dir,
             "layer --method first-order --sigma-s 0.5 --sigma-a 0 --thickness 0.1 --packing 0.5 "
             "--theta-o 20 --json a.json",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cli_run_in(&res, dir,
             "layer --method first-order --sigma-s 0.5 --sigma-a 0 --thickness 0.2 --theta-o 20 "
             "--json b.json",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *a = cli_load_json(dir, "a.json"), *b = cli_load_json(dir, "b.json");
  cr_expect(fabs(value(a, "reflectance") - value(b, "reflectance")) < 1e-12);
  cr_expect(value(a, "reflectance") > 0.01);
  cJSON_Delete(a);
  cJSON_Delete(b);
}

Test(layer_cli, bad_input_is_one_line_naming_the_key_and_exit_2) {
  cli_write_file(dir, "none.json", "{\"layers\": []}\n");
  cli_write_file(dir, "negative.json",
                 "{\"layers\": [{\"sigma_s\": 1, \"sigma_a\": 0.1, \"thickness\": -2}]}\n");
  cli_write_file(dir, "eta.json", "{\"eta\": 0, \"layers\": [{\"tau\": 1}]}\n");
  cli_write_file(dir, "both.json", "{\"layers\": [{\"tau\": 1, \"thickness\": 1}]}\n");
  cli_write_file(dir, "bottom.json", "{\"bottom\": \"mirror\", \"layers\": [{\"tau\": 1}]}\n");
  /* Sixteen layers of different phase functions, each its own table. */
  char big[4096] = "{\"layers\": [";
  for (int l = 0; l < 16; ++l) {
    char one[96];
    snprintf(one, sizeof one, "%s{\"tau\": 1, \"phase\": \"hg\", \"g\": %.2f}", l ? ", " : "",
             0.05 * l + 0.1);
    strcat(big, one);
  }
  strcat(big, "]}\n");
  cli_write_file(dir, "big.json", big);
  static const struct {
    const char *args, *needle;
  } cases[] = {
      {"--stack none.json", "none.json:1: layers"},
      {"--stack negative.json", "negative.json:1: layers[0].thickness"},
      {"--stack eta.json", "eta.json:1: eta"},
      {"--stack both.json", "both.json:1: layers[0]"},
      {"--stack bottom.json", "bottom.json:1: bottom"},
      {"--stack big.json --nodes 512 --modes 1024", "--nodes 512 x --modes 1024"},
      {"--stack none.json --sigma-s 2", "--sigma-s"},
      {"--thickness -1", "--thickness"},
      {"--thickness inf", "--thickness"},
      {"--sigma-s 1e6 --thickness 1e6", "--thickness"},
      {"--eta 0", "--eta"},
      {"--bottom diffuse:1.5", "--bottom"},
      {"--bottom conductor:gold", "--bottom"},
      {"--method exact", "--method"},
      {"--packing 1", "--packing"},
      {"--nodes 1", "--nodes"},
      {"--rbins 4", "--rbins"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char args[256];
    snprintf(args, sizeof args, "layer %s --json out.json", cases[i].args);
    cli_expect_bad_input(&res, dir, args, cases[i].needle);
  }
}

Test(layer_cli, random_walk_reports_standard_errors) {
  cli_run_in(&res, dir,
             "layer --method mc --paths 20000 --seed 4 --sigma-s 0.9 --sigma-a 0.1 --eta 1.33 "
             "--bottom diffuse:0.4 --theta-o 25 --json mc.json --quiet",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *j = cli_load_json(dir, "mc.json");
  cr_expect_eq(cJSON_GetObjectItem(j, "paths")->valuedouble, 20000.0);
  const cJSON *r = cJSON_GetObjectItem(j, "reflectance");
  cr_expect(cJSON_GetObjectItem(r, "stderr")->valuedouble > 0.0);
  const cJSON *f = cJSON_GetArrayItem(cJSON_GetObjectItem(j, "brdf"), 0);
  cr_expect(cJSON_GetObjectItem(f, "value")->valuedouble > 0.0);
  cr_expect(cJSON_GetObjectItem(f, "stderr")->valuedouble > 0.0);
  cJSON_Delete(j);
  cli_run_in(&res, dir, "layer --method mc --paths 1e13 --json long.json --quiet", 1.0);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(!cli_file_exists(dir, "long.json"));
}

Test(layer_cli, ctrl_c_writes_nothing_and_exits_130) {
  cli_run_in(&res, dir,
             "layer --sigma-s 1 --sigma-a 0.001 --phase hg --g 0.9 --eta 1.5 --thickness 1000 "
             "--nodes 100 --modes 40 --json out.json --quiet",
             1.0);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(!cli_file_exists(dir, "out.json"));
}

Test(layer_cli, help_lists_every_option) {
  cli_run_in(&res, dir, "layer --help", 0.0);
  cr_expect_eq(res.status, 0);
  const char *opts[] = {"--sigma-s", "--sigma-a", "--g",         "--phase",   "--medium",
                        "--scale",   "--channel", "--thickness", "--eta",     "--theta-i",
                        "--theta-o", "--bottom",  "--stack",     "--packing", "--method",
                        "--nodes",   "--modes",   "--accuracy",  "--threads", "--quiet",
                        "--json",    "--paths",   "--seed"};
  for (size_t i = 0; i < sizeof opts / sizeof opts[0]; ++i) {
    cr_expect(strstr(res.out, opts[i]) != NULL, "--help misses %s", opts[i]);
  }
}
