/* One strict number grammar for every command (cli/args.h): hexadecimal,
 * padded, empty, textual and overflowing numbers are refused; tiny
 * (subnormal) numbers and -0 read as themselves. Options of one `table`
 * action are refused by the other, and lists have no empty names. The 91
 * malformed numbers call the commands in the test process (cli/cli_call.h). */
#include "cli/cli_call.h"

#include <criterion/criterion.h>

CLI_SUITE(number_parsing_cli);

Test(number_parsing_cli, malformed_numbers_are_refused_by_every_parser) {
  const char *bad[] = {"0x10", "' 5'", "'5 '", "''", "nan", "inf", "1e400",
                       "5x",   "e5",   "1e",   "+",  ".",   "1,5"};
  const char *opts[] = {"halfspace --paths 10 --sigma-s",
                        "halfspace --paths 10 --rbins",
                        "halfspace --paths",
                        "render scene.json --spp",
                        "render scene.json --seed",
                        "model --model dipole --eta",
                        "table check x.sstab --rho 0.5 --theta"};
  char args[256];
  for (size_t i = 0; i < sizeof opts / sizeof opts[0]; ++i) {
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
      snprintf(args, sizeof args, "%s %s", opts[i], bad[k]);
      cli_call_expect_bad_input(&res, dir, args, "expected");
    }
  }
}

Test(number_parsing_cli, subnormal_and_negative_zero_read_as_numbers) {
  cli_run_in(&res, dir, "halfspace --paths 100 --sigma-a 1e-320 --quiet", 0.0);
  cr_expect_eq(res.status, 0, "a subnormal sigma-a was refused: %s", res.err);
  cli_run_in(&res, dir, "halfspace --paths 100 --theta-i -0 --quiet", 0.0);
  cr_expect_eq(res.status, 0, "--theta-i -0 was refused: %s", res.err);
}

Test(number_parsing_cli, table_check_takes_negative_zero_like_zero) {
  cli_run_in(&res, dir, "table build --kind radial --eta 1.33 --g 0 -o t.sstab --quiet", 0.0);
  cr_assert_eq(res.status, 0, "build failed: %s", res.err);
  cli_run_in(&res, dir, "table check t.sstab --rho 0.5 --theta -0 --samples 200", 0.0);
  cr_expect_eq(res.status, 0, "--theta -0 failed: %s", res.err);
  cli_run_in(&res, dir, "table check t.sstab --rho 1e-300 --theta 0 --samples 200", 0.0);
  cr_expect_eq(res.status, 2, "--rho 1e-300 should be refused like 0: %s", res.err);
  cr_expect(strstr(res.err, "--rho") != NULL, "%s", res.err);
}

Test(number_parsing_cli, table_actions_refuse_each_others_options) {
  cli_expect_bad_input(&res, dir, "table check x.sstab --eta 1.3 --rho 0.5 --theta 0", "--eta");
  cli_expect_bad_input(&res, dir, "table check x.sstab -o y --rho 0.5 --theta 0", "-o");
  cli_expect_bad_input(&res, dir, "table build --eta 1.3 --g 0 -o t.sstab --rho 0.4", "--rho");
  cli_expect_bad_input(&res, dir, "table build --eta 1.3 --g 0 -o t.sstab --theta 30", "--theta");
  cli_expect_bad_input(&res, dir, "table", "build or check");
}

Test(number_parsing_cli, model_lists_have_no_empty_name) {
  const char *lists[] = {"dipole+", "dipole,,single", ",dipole", "+dipole",
                         "dipole,", "dipole++single", "''"};
  char args[256];
  for (size_t i = 0; i < sizeof lists / sizeof lists[0]; ++i) {
    snprintf(args, sizeof args, "compare-halfspace --paths 100 --models %s", lists[i]);
    cli_expect_bad_input(&res, dir, args, "--models");
  }
}
