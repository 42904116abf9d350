/* `subsurf model` and `compare-halfspace` read every model's declared options
 * generically: --kebab-name value, bool options also as flags, each value
 * checked against the model that takes it. */
#include "cli_run.h"

#include <cjson/cJSON.h>
#include <criterion/criterion.h>

static char dir[64];
static cli_result res;

static void setup(void) { cli_tmpdir(dir, sizeof dir); }

TestSuite(model_options_cli, .init = setup);

Test(model_options_cli, help_lists_each_models_options_with_range_and_default) {
  cli_run_in(&res, dir, "model --help", 0.0);
  cr_assert_eq(res.status, 0);
  cr_expect(strstr(res.out, "--beam-samples N") != NULL, "%s", res.out);
  cr_expect(strstr(res.out, "a whole number in [6, 384], default 100") != NULL, "%s", res.out);
  cr_expect(strstr(res.out, "--min-distance") != NULL, "%s", res.out);
  cr_expect(strstr(res.out, "--table FILE") != NULL, "%s", res.out);
  cr_expect(strstr(res.out, "--layers STACK") != NULL, "%s", res.out);
}

Test(model_options_cli, options_reach_the_model_and_the_json) {
  cli_run_in(&res, dir, "model --model pbd --beam-samples=30 --rbins 4 --json -", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cJSON *j = cJSON_Parse(res.out);
  cr_assert(j != NULL);
  cJSON *opts = cJSON_GetObjectItem(j, "options");
  cr_expect_str_eq(cJSON_GetObjectItem(opts, "beam_samples")->valuestring, "30");
  cJSON_Delete(j);
  cli_run_in(&res, dir, "model --model dipole --min-distance --rbins 4 --json -", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cr_expect(strstr(res.out, "\"min_distance\":\t\"true\"") != NULL, "%s", res.out);
}

Test(model_options_cli, bad_model_options_are_one_line_naming_option_and_model) {
  cli_expect_bad_input(&res, dir, "model --model dipole --beam-samples 50 --json o.json",
                       "--beam-samples: model 'dipole' has no such option (its options: "
                       "min-distance)");
  cli_expect_bad_input(&res, dir, "model --model pbd --beam-samples 3 --json o.json",
                       "--beam-samples: pbd: option beam_samples: expected a whole number in "
                       "[6, 384], got '3'");
  cli_expect_bad_input(&res, dir, "model --model dipole --min-distance=maybe --json o.json",
                       "--min-distance: dipole");
  cli_expect_bad_input(&res, dir, "model --model layers --layers sigma_s=1 --json o.json",
                       "layer 0: missing sigma_a=");
  cli_expect_bad_input(&res, dir, "model --model layers --thickness 1 --json o.json",
                       "--thickness");
  cli_expect_bad_input(&res, dir, "model --model dipole --no-such-option 1 --json o.json",
                       "--no-such-option");
  cli_expect_bad_input(&res, dir,
                       "compare-halfspace --models dipole,better-dipole --beam-samples 30 "
                       "--paths 10 --json o.json",
                       "--beam-samples: none of the chosen models");
}

/* An option goes to every compared model that declares it. */
Test(model_options_cli, compare_passes_an_option_to_the_models_that_take_it) {
  cli_run_in(&res, dir,
             "compare-halfspace --models dipole,pbd --beam-samples 30 --paths "
             "2000 --threads 1 "
             "--quiet --rbins 8 --json c.json",
             0.0);
  cr_expect_eq(res.status, 0, "%s", res.err);
}
