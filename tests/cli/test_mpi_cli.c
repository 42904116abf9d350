/* `mpirun -np N subsurf render`: the image is byte-identical to
 * one process's for 2 and 3 ranks and any thread count; ranks started with
 * different arguments or seeing different scene files are caught at
 * start-up, and a rank stopped at start-up ends the job after the time-out;
 * the options that keep per-process files are refused. Runs Open
 * MPI's mpirun on localhost (--oversubscribe: more ranks than cores). */
#include "cli/cli_run.h"
#include "cli/mpirun.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

CLI_SUITE(mpi);

/* A small copy of scenes/skin_sphere.json: 40 x 24 pixels (3 x 2 tiles of
 * 16, so ranks own unequal, partial tiles), 4 spp. */
static const char *scene =
    "{\"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0], \"up\": [0, 1, 0],"
    " \"fov\": 30, \"resolution\": [40, 24]},"
    " \"media\": [{\"name\": \"skin\", \"sigma_s\": [3.7, 4.4, 5.05],"
    " \"sigma_a\": [0.16, 0.85, 2.4], \"phase\": \"iso\"}],"
    " \"materials\": [{\"name\": \"skin\", \"type\": \"translucent\", \"boundary\": \"smooth\","
    " \"eta\": 1.33, \"medium\": \"skin\"}],"
    " \"shapes\": [{\"name\": \"s\", \"type\": \"sphere\", \"radius\": 1, \"subdivisions\": 3,"
    " \"material\": \"skin\"}, {\"name\": \"lamp\", \"type\": \"sphere\", \"radius\": 2,"
    " \"center\": [6, 2, -2], \"subdivisions\": 2}],"
    " \"lights\": [{\"name\": \"lamp\", \"type\": \"area\", \"shape\": \"lamp\", \"radiance\": "
    "10}],"
    " \"integrator\": {\"type\": \"volpath\"}, \"render\": {\"spp\": 4, \"seed\": 5}}";

Test(mpi, two_and_three_ranks_write_the_single_process_image_byte_for_byte, .timeout = 300) {
  cli_write_file(dir, "scene.json", scene);
  cli_run_in(&res, dir, "render scene.json --threads 2 --quiet -o one.exr", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  const char *bin = getenv("SUBSURF_BIN");
  char args[1024];
  snprintf(args, sizeof args, "-np 2 %s render scene.json --threads 1 --quiet -o two.exr", bin);
  mpirun(dir, &res, args);
  cr_assert_eq(res.status, 0, "%s", res.err);
  snprintf(args, sizeof args, "-np 3 %s render scene.json --threads 2 -o three.exr", bin);
  mpirun(dir, &res, args);
  cr_assert_eq(res.status, 0, "%s", res.err);
  expect_same_file(dir, "one.exr", "two.exr");
  expect_same_file(dir, "one.exr", "three.exr");
  expect_same_file(dir, "one.png", "three.png");
  /* Rank 0 alone reports, on the collected film (every pixel has its 4
   * samples, not only rank 0's tiles). */
  char out[4096];
  char path[256];
  snprintf(path, sizeof path, "%s/out.txt", dir);
  cli_slurp(path, out, sizeof out);
  cr_expect(strstr(out, "40 x 24, 4 spp (min over pixels)"), "%s", out);
  cr_expect_eq(strstr(strstr(out, "wrote ") + 1, "wrote "), NULL, "one rank writes: %s", out);
}

Test(mpi, ranks_with_different_arguments_or_scene_files_stop_at_start_up, .timeout = 120) {
  cli_write_file(dir, "scene.json", scene);
  const char *bin = getenv("SUBSURF_BIN");
  char args[2048];
  snprintf(args, sizeof args,
           "-np 1 %s render scene.json --spp 2 --quiet -o a.exr : "
           "-np 1 %s render scene.json --spp 3 --quiet -o a.exr",
           bin, bin);
  mpirun(dir, &res, args);
  cr_expect_neq(res.status, 0);
  cr_expect(strstr(res.err, "ranks disagree on the command line"), "%s", res.err);
  cr_expect(!cli_file_exists(dir, "a.exr"));

  char sub[300];
  snprintf(sub, sizeof sub, "%s/b", dir);
  cr_assert(mkdir(sub, 0700) == 0);
  /* The same command line in two folders whose scene.json differ by a digit. */
  char changed[4096];
  snprintf(changed, sizeof changed, "%s", scene);
  *strstr(changed, "\"seed\": 5") = '\0';
  strcat(changed, "\"seed\": 6}}");
  cli_write_file(sub, "scene.json", changed);
  snprintf(args, sizeof args,
           "-np 1 --wdir %s %s render scene.json --quiet -o /dev/null/x.exr : "
           "-np 1 --wdir %s %s render scene.json --quiet -o /dev/null/x.exr",
           dir, bin, sub, bin);
  mpirun(dir, &res, args);
  cr_expect_neq(res.status, 0);
  cr_expect(strstr(res.err, "disagree on the content of scene.json"), "%s", res.err);
}

Test(mpi, per_process_files_are_refused_with_several_ranks, .timeout = 120) {
  cli_write_file(dir, "scene.json", scene);
  char args[1024];
  snprintf(args, sizeof args, "-np 2 %s render scene.json --checkpoint c.ck -o a.exr",
           getenv("SUBSURF_BIN"));
  mpirun(dir, &res, args);
  cr_expect_eq(res.status, 2, "%s", res.err);
  cr_expect(strstr(res.err, "--checkpoint is not available with 2 MPI ranks"), "%s", res.err);
  cr_expect(!cli_file_exists(dir, "a.exr") && !cli_file_exists(dir, "c.ck"));
}

/* Rank 1 runs in b/, where scene.json is a FIFO: its writer, in the rank's
 * own script, sends the rank SIGSTOP as soon as the rank has opened the
 * file to compare it (after MPI_Init and the command-line check), and only
 * then writes the scene. Rank 0 waits for the comparison at most
 * SUBSURF_MPI_TIMEOUT (1 s here) plus twice its own start-up time. */
Test(mpi, a_rank_stopped_at_start_up_fails_the_job_after_the_time_out, .timeout = 120) {
  cli_write_file(dir, "scene.json", scene);
  char sub[300], fifo[320];
  snprintf(sub, sizeof sub, "%s/b", dir);
  cr_assert(mkdir(sub, 0700) == 0);
  snprintf(fifo, sizeof fifo, "%s/scene.json", sub);
  cr_assert(mkfifo(fifo, 0600) == 0);
  char script[1024];
  snprintf(script, sizeof script,
           "#!/bin/sh\n"
           "case \"$OMPI_COMM_WORLD_RANK\" in 1) (exec 3>scene.json; kill -STOP $$; "
           "cat ../scene.json >&3) & ;; esac\n"
           "exec %s render scene.json --quiet -o a.exr\n",
           getenv("SUBSURF_BIN"));
  cli_write_file(dir, "rank.sh", script);
  char args[1024];
  snprintf(args, sizeof args,
           "-x SUBSURF_MPI_TIMEOUT=1 -np 1 --wdir %s sh %s/rank.sh : "
           "-np 1 --wdir %s sh %s/rank.sh",
           dir, dir, sub, dir);
  double t0 = cli_now();
  mpirun(dir, &res, args);
  double seconds = cli_now() - t0;
  cr_expect_neq(res.status, 0);
  cr_expect(strstr(res.err, "subsurf render: rank 0: not all 2 MPI ranks answered within ") &&
                strstr(res.err, "while the ranks compared the content of scene.json at start-up"),
            "%s", res.err);
  cr_expect_lt(seconds, 60.0);
  cr_expect(!cli_file_exists(dir, "a.exr") && !cli_file_exists(sub, "a.exr"));
}

/* Open MPI is in the plugin libsubsurf_mpi.so, loaded only under mpirun: a
 * copy of the binary with no plugin beside it (nor in ../lib) runs alone,
 * and under mpirun stops at start-up with one line naming the plugin. */
Test(mpi, without_its_plugin_the_binary_runs_alone_and_mpirun_says_why, .timeout = 120) {
  cli_write_file(dir, "scene.json", scene);
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "cp '%s' '%s/alone'", getenv("SUBSURF_BIN"), dir);
  cr_assert_eq(system(cmd), 0);
  snprintf(cmd, sizeof cmd, "cd '%s' && ./alone render scene.json --spp 1 --quiet -o a.exr", dir);
  cr_expect_eq(system(cmd), 0);
  cr_expect(cli_file_exists(dir, "a.exr"));
  mpirun(dir, &res, "-np 1 ./alone render scene.json --quiet -o b.exr");
  cr_expect_neq(res.status, 0);
  cr_expect(strstr(res.err, "subsurf: the plugin libsubsurf_mpi.so (for mpirun) was found "
                            "neither beside ./alone nor in ../lib"),
            "%s", res.err);
  cr_expect(!cli_file_exists(dir, "b.exr"));
}
