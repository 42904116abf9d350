/* SIGINT and SIGTERM mean the same to every long command (cli/signals.h):
 * work stops, what is done is written as NAME-partial.* (halfspace, render)
 * or nothing is written (model, compare-halfspace, table), one line says so,
 * and the exit code is 130. A second signal right behind the first (as
 * `timeout` forwards a terminal's Ctrl-C) does not cut that short. */
#include "cli/cli_run.h"

#include <criterion/criterion.h>

CLI_SUITE(signals_cli);

static void expect_interrupted_with_nothing_written(const char *args, int sig) {
  int before = cli_dir_count(dir);
  cli_run_signalled(&res, dir, args, 0.5, sig, 1, 0.0);
  cr_expect_eq(res.status, 130, "'%s': exit %d, stderr: %s", args, res.status, res.err);
  cr_expect(strstr(res.err, "interrupted") != NULL, "'%s': %s", args, res.err);
  cr_expect(strstr(res.err, "nothing written") != NULL, "'%s': %s", args, res.err);
  cr_expect_eq(cli_dir_count(dir), before, "'%s' wrote a file", args);
}

Test(signals_cli, a_second_sigint_right_after_the_first_still_writes_the_partial_result) {
  cli_run_signalled(&res, dir, "halfspace --paths 1e12 --quiet --json out.json", 0.5, SIGINT, 2,
                    0.02);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(cli_file_exists(dir, "out-partial.json"), "no partial result; stderr: %s", res.err);
}

Test(signals_cli, sigterm_is_handled_like_sigint) {
  cli_run_signalled(&res, dir, "halfspace --paths 1e12 --quiet --json out.json", 0.5, SIGTERM, 1,
                    0.0);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(cli_file_exists(dir, "out-partial.json"), "no partial result; stderr: %s", res.err);
}

Test(signals_cli, ctrl_c_while_a_scene_loads_says_so_and_writes_nothing) {
  /* An icosphere of 8 subdivisions (1.3 million triangles) takes seconds. */
  cli_write_file(dir, "big.json",
                 "{\"camera\": {\"resolution\": [8, 8]},\n"
                 " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 8}],\n"
                 " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
                 " \"integrator\": {\"type\": \"path\"}, \"render\": {\"spp\": 100000}}\n");
  cli_run_signalled(&res, dir, "render big.json -o out.exr --quiet", 0.3, SIGINT, 1, 0.0);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(strstr(res.err, "interrupted") != NULL, "%s", res.err);
  cr_expect(!cli_file_exists(dir, "out.exr") && !cli_file_exists(dir, "out-partial.exr"),
            "an image was written after an interrupt during loading");
}

Test(signals_cli, compare_model_and_table_stop_with_nothing_written) {
  expect_interrupted_with_nothing_written("compare-halfspace --models dipole --paths 1e12 --quiet "
                                          "--json out.json",
                                          SIGTERM);
  expect_interrupted_with_nothing_written(
      "model --model pbd --beam-samples 384 --rbins 20000 --json out.json", SIGINT);
  cli_run_in(&res, dir, "table build --kind radial --eta 1.33 --g 0 -o t.sstab --quiet", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  expect_interrupted_with_nothing_written("table check t.sstab --rho 0.5 --theta 0 --samples 1e8",
                                          SIGINT);
}

Test(signals_cli, a_repeated_signal_after_the_grace_period_ends_the_process) {
  /* table build does not poll while it computes: only the repeat stops it. */
  cli_run_signalled(&res, dir, "table build --eta 1.33 --g 0 -o t.sstab --quiet", 0.2, SIGINT, 2,
                    1.5);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(!cli_file_exists(dir, "t.sstab"), "the table was written");
}
