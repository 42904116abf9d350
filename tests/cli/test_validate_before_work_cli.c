/* Everything that can be checked is checked before the work starts: a bad
 * output path, a bad exposure, a map or a film that does not fit are refused
 * at once (exit 2, one line, nothing written), not after a long run. */
#include "cli/cli_run.h"

#include <criterion/criterion.h>
#include <unistd.h>

CLI_SUITE(validate_before_work_cli);

/* A scene that takes minutes at its own spp. */
static void write_slow_scene(const char *resolution) {
  char text[1024];
  snprintf(text, sizeof text,
           "{\"camera\": {\"position\": [0, 0, 4], \"resolution\": [%s]},\n"
           " \"materials\": [{\"name\": \"white\", \"type\": \"diffuse\", \"albedo\": 1}],\n"
           " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 3, \"material\": \"white\"}],\n"
           " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
           " \"integrator\": {\"type\": \"path\"}, \"render\": {\"spp\": 1000000}}\n",
           resolution);
  cli_write_file(dir, "slow.json", text);
}

static void expect_refused_at_once(const char *args, const char *needle) {
  double t0 = cli_now();
  cli_expect_bad_input(&res, dir, args, needle);
  cr_expect(cli_now() - t0 < 10.0, "'%s' took %.1f s to refuse", args, cli_now() - t0);
}

Test(validate_before_work_cli, render_checks_its_output_directory_before_rendering) {
  write_slow_scene("64, 64");
  expect_refused_at_once("render slow.json -o missing-dir/out.exr", "missing-dir");
}

Test(validate_before_work_cli, render_checks_the_exposure_before_rendering) {
  write_slow_scene("64, 64");
  expect_refused_at_once("render slow.json -o out.exr --exposure nan", "--exposure");
  expect_refused_at_once("render slow.json -o out.exr --exposure 1e308", "--exposure");
}

Test(validate_before_work_cli, a_film_larger_than_the_memory_is_refused_up_front) {
  double memory = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
  if (memory > 2e11) {
    cr_skip_test("this machine has %.0f GB: a 65536 x 65536 film fits", memory / 1e9);
  }
  write_slow_scene("65536, 65536");
  expect_refused_at_once("render slow.json -o out.exr", "memory");
  cr_expect(strstr(res.err, "65536 x 65536") != NULL, "%s", res.err);
}

Test(validate_before_work_cli, halfspace_checks_exposure_and_map_size_before_the_run) {
  expect_refused_at_once("halfspace --paths 1e9 --json out.json --map m.png --exposure nan",
                         "--exposure");
  expect_refused_at_once("halfspace --paths 1e9 --json out.json --map m.exr --xbins 100000 "
                         "--ybins 1000",
                         "map cells");
}

Test(validate_before_work_cli, halfspace_tallies_larger_than_the_memory_are_refused_up_front) {
  double memory = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
  if (memory > 1e12) {
    cr_skip_test("this machine has %.0f GB: 4096 threads' tallies fit", memory / 1e9);
  }
  /* 1.6e7 map cells in three tally slots for each of 4096 threads: 1.6 TB. */
  expect_refused_at_once("halfspace --paths 1e9 --json out.json --map m.exr --xbins 4000 "
                         "--ybins 4000 --threads 4096",
                         "memory");
}
