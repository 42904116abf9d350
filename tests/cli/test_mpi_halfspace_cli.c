/* `mpirun -np N subsurf halfspace`: the ranks split the batches of
 * paths and rank 0 merges them in batch order, so its JSON and map are the
 * single process's, byte for byte, for 2 and 3 ranks and 1 or 2 threads;
 * ranks with different arguments stop at start-up; a killed or silent rank
 * ends the job with a message within seconds; Ctrl-C writes the partial
 * result; commands without MPI refuse several ranks. Runs Open MPI's mpirun
 * on localhost (tests/cli/mpirun.h). */
#include "cli/cli_run.h"
#include "cli/mpirun.h"

#include <criterion/criterion.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

CLI_SUITE(mpi_halfspace);

/* Three channels (successive runs), a slab with a boundary, directions and
 * a map: every tally of the run crosses the ranks. 6000 paths: 375 batches
 * of 16. */
#define RUN                                                                                        \
  "halfspace --medium Skin1 --channel rgb --scale 0.2 --thickness 4 --theta-i 30 --theta-o 20 "    \
  "--xbins 8 --ybins 6 --rbins 12 --paths 6000 --seed 7 --quiet"

/* dir/name without the lines that name the wall time or the thread count
 * (malloc'd). */
static char *json_without_timing(const char *name) {
  char *text = NULL;
  cr_assert(mpirun_file_bytes(dir, name, &text) > 0, "%s missing", name);
  char *out = malloc(strlen(text) + 1), *w = out;
  for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
    if (!strstr(line, "\"seconds\"") && !strstr(line, "\"threads\"")) {
      w += sprintf(w, "%s\n", line);
    }
  }
  free(text);
  return out;
}

static void expect_same_json(const char *a, const char *b) {
  char *x = json_without_timing(a), *y = json_without_timing(b);
  cr_expect_str_eq(x, y, "%s and %s differ beyond timing", a, b);
  free(x);
  free(y);
}

Test(mpi_halfspace, ranks_and_threads_give_the_single_process_result_byte_for_byte,
     .timeout = 300) {
  cli_run_in(&res, dir, RUN " --threads 1 --json one.json --map one.pfm", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cli_run_in(&res, dir, RUN " --threads 2 --json one2.json --map one2.pfm", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  const char *bin = getenv("SUBSURF_BIN");
  char args[1024];
  snprintf(args, sizeof args, "-np 2 %s " RUN " --threads 1 --json two.json --map two.pfm", bin);
  mpirun(dir, &res, args);
  cr_assert_eq(res.status, 0, "%s", res.err);
  snprintf(args, sizeof args, "-np 3 %s " RUN " --threads 2 --json three.json --map three.pfm",
           bin);
  mpirun(dir, &res, args);
  cr_assert_eq(res.status, 0, "%s", res.err);
  expect_same_file(dir, "one.pfm", "one2.pfm");
  expect_same_file(dir, "one.pfm", "two.pfm");
  expect_same_file(dir, "one.pfm", "three.pfm");
  expect_same_json("one.json", "one2.json");
  expect_same_json("one.json", "two.json");
  expect_same_json("one.json", "three.json");
  /* The whole job's paths, and rank 0 alone reports. */
  char *three = json_without_timing("three.json");
  cr_expect(strstr(three, "\"paths\":\t6000,\n\t\t\t\"partial\":\tfalse"), "%s", three);
  free(three);
  cr_expect_eq(strstr(strstr(res.err, "wrote three.json") + 1, "wrote three.json"), NULL,
               "one rank writes: %s", res.err);
}

Test(mpi_halfspace, ranks_with_different_arguments_stop_at_start_up, .timeout = 120) {
  const char *bin = getenv("SUBSURF_BIN");
  char args[1024];
  snprintf(args, sizeof args,
           "-np 1 %s halfspace --paths 1000 --json a.json : -np 1 %s halfspace --paths 2000 "
           "--json a.json",
           bin, bin);
  mpirun(dir, &res, args);
  cr_expect_neq(res.status, 0);
  cr_expect(strstr(res.err, "subsurf halfspace: the 2 MPI ranks disagree on the command line"),
            "%s", res.err);
  cr_expect(!cli_file_exists(dir, "a.json"));
}

/* `mpirun -np 2` runs a long halfspace; the ranks matching the shell
 * pattern `ranks` get `sig` after 3 s (once both are tracing); returns the
 * job's wall time. */
static double run_with_ranks_signalled(const char *ranks, const char *sig, const char *env) {
  char script[1024];
  snprintf(script, sizeof script,
           "#!/bin/sh\n"
           "case \"$OMPI_COMM_WORLD_RANK\" in %s) (sleep 3; kill -%s $$) & ;; esac\n"
           "exec %s halfspace --paths 1000000000 --threads 1 --quiet --json a.json\n",
           ranks, sig, getenv("SUBSURF_BIN"));
  cli_write_file(dir, "rank.sh", script);
  char args[256];
  snprintf(args, sizeof args, "-np 2 %s sh rank.sh", env);
  double t0 = cli_now();
  mpirun(dir, &res, args);
  return cli_now() - t0;
}

Test(mpi_halfspace, a_killed_rank_fails_the_job_with_a_message, .timeout = 120) {
  double seconds = run_with_ranks_signalled("1", "KILL", "");
  cr_expect_neq(res.status, 0);
  cr_expect(strstr(res.err, "rank 1") && strstr(res.err, "signal 9"), "%s", res.err);
  cr_expect_lt(seconds, 60.0);
  cr_expect(!cli_file_exists(dir, "a.json") && !cli_file_exists(dir, "a-partial.json"));
}

/* A stopped rank does not close its connections: rank 0 gives up on it
 * after SUBSURF_MPI_TIMEOUT (1 s here) plus twice its own run time. */
Test(mpi_halfspace, a_silent_rank_fails_the_job_after_the_time_out, .timeout = 120) {
  double seconds = run_with_ranks_signalled("1", "STOP", "-x SUBSURF_MPI_TIMEOUT=1");
  cr_expect_neq(res.status, 0);
  cr_expect(strstr(res.err, "subsurf halfspace: rank 1 sent nothing within the time-out"), "%s",
            res.err);
  cr_expect_lt(seconds, 60.0);
}

/* Ctrl-C at a terminal interrupts every rank (mpirun also passes it on as
 * SIGTERM, and kills the ranks odls_base_sigkill_timeout seconds later,
 * default 1, a race on a loaded machine): here each rank is interrupted
 * directly. */
Test(mpi_halfspace, ctrl_c_writes_the_partial_result_of_all_ranks, .timeout = 120) {
  double seconds = run_with_ranks_signalled("*", "INT", "");
  cr_expect_lt(seconds, 60.0);
  char *json = NULL;
  cr_assert(mpirun_file_bytes(dir, "a-partial.json", &json) > 0, "no a-partial.json: %s", res.err);
  cr_expect(strstr(json, "\"interrupted\":\ttrue"), "%s", json);
  cr_expect(!strstr(json, "\"paths\":\t1000000000,\n\t\"partial"), "%s", json);
  free(json);
}

Test(mpi_halfspace, commands_without_mpi_refuse_several_ranks, .timeout = 120) {
  char args[1024];
  snprintf(args, sizeof args, "-np 2 %s model --model dipole --json m.json", getenv("SUBSURF_BIN"));
  mpirun(dir, &res, args);
  cr_expect_eq(res.status, 2, "%s", res.err);
  cr_expect(strstr(res.err, "subsurf model: does not use MPI; run it without mpirun"), "%s",
            res.err);
  cr_expect(!cli_file_exists(dir, "m.json"));
}
