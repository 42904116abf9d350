/* `subsurf compare-halfspace --models a+b`: a curve that sums models (e.g.
 * Jensen et al.'s complete BSSRDF dipole+single, or Ferrier's
 * multiple-scattering table plus exact single scattering) is compared like
 * any model. */
#include "cli_files.h"

#include <cjson/cJSON.h>
#include <criterion/criterion.h>
#include <math.h>

static char dir[64];
static cli_result res;

static void setup(void) { cli_tmpdir(dir, sizeof dir); }

TestSuite(compare_sum_cli, .init = setup);

static double number(cJSON *model, const char *key) {
  cJSON *v = cJSON_GetObjectItem(model, key);
  cr_assert(v != NULL, "no key %s", key);
  return cJSON_IsObject(v) ? cJSON_GetObjectItem(v, "value")->valuedouble : v->valuedouble;
}

static cJSON *load_json(const char *name) { return cli_load_json(dir, name); }

Test(compare_sum_cli, a_sum_of_models_predicts_the_sum_of_their_predictions) {
  cli_run_in(&res, dir,
             "compare-halfspace --models dipole+single,dipole,single --sigma-s 0.9 "
             "--sigma-a 0.1 --eta 1.33 --theta-i 30 --paths 2000 --threads 1 --quiet "
             "--rbins 12 --json c.json --plot p.svg",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(strstr(res.out, "dipole+single") != NULL, "%s", res.out);
  cr_expect(cli_file_exists(dir, "p.svg"));
  cJSON *j = load_json("c.json");
  cJSON *models = cJSON_GetObjectItem(j, "models");
  cJSON *sum = cJSON_GetObjectItem(models, "dipole+single");
  cJSON *a = cJSON_GetObjectItem(models, "dipole"), *b = cJSON_GetObjectItem(models, "single");
  cr_assert(sum && a && b);
  const char *keys[] = {"reflectance", "rd"};
  for (int k = 0; k < 2; ++k) {
    double s = number(sum, keys[k]), x = number(a, keys[k]) + number(b, keys[k]);
    cr_expect(fabs(s - x) <= 1e-12 * fabs(x), "%s: %.15g vs %.15g", keys[k], s, x);
  }
  cJSON *rs = cJSON_GetObjectItem(sum, "radial"), *ra = cJSON_GetObjectItem(a, "radial");
  cJSON *rb = cJSON_GetObjectItem(b, "radial");
  int n = cJSON_GetArraySize(cJSON_GetObjectItem(rs, "value"));
  cr_expect_eq(n, 12);
  for (int i = 0; i < n; ++i) {
    double s = cJSON_GetArrayItem(cJSON_GetObjectItem(rs, "value"), i)->valuedouble;
    double x = cJSON_GetArrayItem(cJSON_GetObjectItem(ra, "value"), i)->valuedouble +
               cJSON_GetArrayItem(cJSON_GetObjectItem(rb, "value"), i)->valuedouble;
    cr_expect(fabs(s - x) <= 1e-12 * fabs(x), "radial bin %d: %.15g vs %.15g", i, s, x);
  }
  cJSON_Delete(j);
}

Test(compare_sum_cli, a_bad_sum_is_one_clear_line_and_exit_code_2) {
  cli_expect_bad_input(&res, dir, "compare-halfspace --models dipole+nonesuch --json o.json",
                       "nonesuch");
  cli_expect_bad_input(&res, dir, "compare-halfspace --models + --json o.json", "--models");
  cli_expect_bad_input(&res, dir,
                       "compare-halfspace --models single+single+single+single+single "
                       "--json o.json",
                       "at most");
  /* A sum is refused by the model that refuses the medium. */
  cli_expect_bad_input(&res, dir,
                       "compare-halfspace --models table-gwc+single --eta 1 --json o.json", "eta");
}

Test(compare_sum_cli, model_accepts_a_sum_and_predicts_the_sum_of_its_parts) {
  const char *medium = "--sigma-s 0.9 --sigma-a 0.1 --eta 1.33 --theta-i 30 --rbins 12 "
                       "--profile-r 0.1,1";
  const char *names[3] = {"dipole+single", "dipole", "single"};
  cJSON *j[3];
  for (int k = 0; k < 3; ++k) {
    char args[512];
    snprintf(args, sizeof args, "model --model %s %s --json -", names[k], medium);
    cli_run_in(&res, dir, args, 0.0);
    cr_assert_eq(res.status, 0, "%s: %s", names[k], res.err);
    j[k] = cJSON_Parse(res.out);
    cr_assert(j[k] != NULL);
  }
  cr_expect_str_eq(cJSON_GetObjectItem(j[0], "model")->valuestring, "dipole+single");
  const char *keys[] = {"reflectance", "rd"};
  for (int k = 0; k < 2; ++k) {
    double s = number(j[0], keys[k]), x = number(j[1], keys[k]) + number(j[2], keys[k]);
    cr_expect(fabs(s - x) <= 1e-12 * fabs(x), "%s: %.15g vs %.15g", keys[k], s, x);
  }
  for (int i = 0; i < 2; ++i) {
    double v[3];
    for (int k = 0; k < 3; ++k) {
      cJSON *prof = cJSON_GetObjectItem(cJSON_GetObjectItem(j[k], "profile"), "value");
      v[k] = cJSON_GetArrayItem(prof, i)->valuedouble;
    }
    cr_expect(fabs(v[0] - v[1] - v[2]) <= 1e-12 * v[0], "profile %d: %g vs %g", i, v[0],
              v[1] + v[2]);
  }
  for (int k = 0; k < 3; ++k) {
    cJSON_Delete(j[k]);
  }
}

Test(compare_sum_cli, a_sum_with_an_empty_or_unknown_part_is_refused) {
  cli_expect_bad_input(&res, dir, "model --model dipole+ --json o.json", "--model");
  cli_expect_bad_input(&res, dir, "model --model dipole+nope --json o.json", "nope");
  cli_expect_bad_input(&res, dir, "compare-halfspace --models dipole,,single --json o.json",
                       "--models");
  cli_expect_bad_input(&res, dir, "compare-halfspace --models +single --json o.json", "--models");
}

/* dipole-brdf puts all its light at the entry point: a BRDF has no radial
 * profile, so its profile errors are not computed but said to be absent. */
Test(compare_sum_cli, a_brdf_has_its_totals_compared_and_no_profile_errors) {
  cli_run_in(&res, dir,
             "compare-halfspace --models dipole-brdf,dipole --sigma-s 0.9 --sigma-a 0.1 "
             "--paths 2000 --threads 1 --quiet --rbins 12 --json c.json",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(strstr(res.out, "no radial profile") != NULL, "%s", res.out);
  cJSON *j = load_json("c.json");
  cJSON *models = cJSON_GetObjectItem(j, "models");
  cJSON *brdf = cJSON_GetObjectItem(cJSON_GetObjectItem(models, "dipole-brdf"), "errors");
  cJSON *dip = cJSON_GetObjectItem(cJSON_GetObjectItem(models, "dipole"), "errors");
  cr_assert(brdf && dip);
  cr_expect(cJSON_GetObjectItem(brdf, "reflectance_relative") != NULL);
  cr_expect(cJSON_GetObjectItem(brdf, "profile_mean_relative") == NULL);
  cr_expect(cJSON_IsString(cJSON_GetObjectItem(brdf, "profile")));
  cr_expect(cJSON_GetObjectItem(dip, "profile_mean_relative") != NULL);
  cJSON_Delete(j);
}
