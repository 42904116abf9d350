/* `mpirun -np N subsurf compare`: every pass of the reference
 * and of each method is rendered tile by tile over the ranks and collected
 * by rank 0, so with --spp the images and errors are the single process's,
 * byte for byte, for 2 and 3 ranks; a time budget works (its numbers depend
 * on timing); ranks seeing different scene files stop at start-up. Runs
 * Open MPI's mpirun on localhost (tests/cli/mpirun.h). */
#include "cli/cli_run.h"
#include "cli/compare_scene_fixture.h"
#include "cli/mpirun.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

CLI_SUITE(mpi_compare);

/* The compare fixture at 36 x 20 pixels: 3 x 2 tiles of 16, so that ranks
 * own unequal, partial tiles. */
static void write_scene(const char *where) {
  char text[4096];
  snprintf(text, sizeof text, "%s", compare_fixture_scene);
  char *res12 = strstr(text, "[12, 12]");
  cr_assert(res12);
  memcpy(res12, "[36, 20]", 8);
  cli_write_file(where, "scene.json", text);
}

/* The "rel_mse" lines of DIR/results.json, in order (malloc'd). */
static char *errors_of(const char *out) {
  char name[128], *text = NULL;
  snprintf(name, sizeof name, "%s/results.json", out);
  cr_assert(mpirun_file_bytes(dir, name, &text) > 0, "%s missing", name);
  char *keep = malloc(strlen(text) + 1), *w = keep;
  *w = '\0';
  for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
    if (strstr(line, "\"rel_mse") || strstr(line, "\"mean_rgb") || strstr(line, "\"spp\"")) {
      w += sprintf(w, "%s\n", line);
    }
  }
  free(text);
  return keep;
}

static void expect_same_outputs(const char *a, const char *b) {
  static const char *const files[] = {"reference.exr", "reference.png", "volpath.exr",
                                      "volpath.png",   "dipole.exr",    "dipole-error.png"};
  for (size_t i = 0; i < sizeof files / sizeof files[0]; ++i) {
    char x[64], y[64];
    snprintf(x, sizeof x, "%s/%s", a, files[i]);
    snprintf(y, sizeof y, "%s/%s", b, files[i]);
    expect_same_file(dir, x, y);
  }
  char *ea = errors_of(a), *eb = errors_of(b);
  cr_expect(strlen(ea) > 100, "%s", ea);
  cr_expect_str_eq(ea, eb, "errors in %s and %s differ", a, b);
  free(ea);
  free(eb);
}

#define RUN "compare scene.json --methods volpath,dipole --spp 4 --reference-rel-error 0.2 --quiet"

Test(mpi_compare, ranks_write_the_single_process_images_and_errors_byte_for_byte, .timeout = 300) {
  write_scene(dir);
  cli_run_in(&res, dir, RUN " --threads 2 -o one", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  const char *bin = getenv("SUBSURF_BIN");
  char args[1024];
  snprintf(args, sizeof args, "-np 2 %s " RUN " --threads 1 -o two", bin);
  mpirun(dir, &res, args);
  cr_assert_eq(res.status, 0, "%s", res.err);
  snprintf(args, sizeof args, "-np 3 %s " RUN " --threads 1 -o three", bin);
  mpirun(dir, &res, args);
  cr_assert_eq(res.status, 0, "%s", res.err);
  expect_same_outputs("one", "two");
  expect_same_outputs("one", "three");
  cr_expect(cli_path_exists(dir, "three/index.html"));
}

Test(mpi_compare, a_time_budget_runs_on_all_ranks_and_rank_0_reports, .timeout = 120) {
  write_scene(dir);
  char args[1024];
  snprintf(args, sizeof args,
           "-np 2 %s compare scene.json --methods dipole --time 0.5 --reference-spp 4 "
           "--threads 1 -o t",
           getenv("SUBSURF_BIN"));
  mpirun(dir, &res, args);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cr_expect(cli_path_exists(dir, "t/index.html") && cli_path_exists(dir, "t/dipole.exr"));
  char out[8192], path[256];
  snprintf(path, sizeof path, "%s/out.txt", dir);
  cli_slurp(path, out, sizeof out);
  char *first = strstr(out, "report: ");
  cr_expect(first && !strstr(first + 1, "report: "), "rank 0 alone reports: %s", out);
}

Test(mpi_compare, ranks_seeing_different_scene_files_stop_at_start_up, .timeout = 120) {
  write_scene(dir);
  char sub[300];
  snprintf(sub, sizeof sub, "%s/b", dir);
  cr_assert(mkdir(sub, 0700) == 0);
  cli_write_file(sub, "scene.json", compare_fixture_scene);
  const char *bin = getenv("SUBSURF_BIN");
  char args[2048];
  snprintf(args, sizeof args,
           "-np 1 --wdir %s %s compare scene.json --methods dipole --spp 1 -o out : "
           "-np 1 --wdir %s %s compare scene.json --methods dipole --spp 1 -o out",
           dir, bin, sub, bin);
  mpirun(dir, &res, args);
  cr_expect_eq(res.status, 2, "%s", res.err);
  cr_expect(strstr(res.err, "subsurf compare: the 2 MPI ranks disagree on the content of "
                            "scene.json"),
            "%s", res.err);
  cr_expect(!cli_path_exists(dir, "out") && !cli_path_exists(sub, "out"));
}
