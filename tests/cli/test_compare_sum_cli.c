/* `subsurf compare-halfspace --models a+b`: a curve that sums models (e.g.
 * Jensen et al.'s complete BSSRDF dipole+single, or Ferrier's
 * multiple-scattering table plus exact single scattering) is compared like
 * any model. */
#include "cli_run.h"

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

Test(compare_sum_cli, a_sum_of_models_predicts_the_sum_of_their_predictions) {
  cli_run_in(&res, dir,
             "compare-halfspace --models dipole+single,dipole,single --sigma-s 0.9 "
             "--sigma-a 0.1 --eta 1.33 --theta-i 30 --paths 2000 --threads 1 --quiet "
             "--rbins 12 --json c.json --plot p.svg",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(strstr(res.out, "dipole+single") != NULL, "%s", res.out);
  cr_expect(cli_file_exists(dir, "p.svg"));
  char path[256];
  static char text[1 << 20];
  snprintf(path, sizeof path, "%s/c.json", dir);
  cli_slurp(path, text, sizeof text);
  cJSON *j = cJSON_Parse(text);
  cr_assert(j != NULL);
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
