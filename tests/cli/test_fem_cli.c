/* `subsurf fem`: a box and a closed mesh solved and written as PLY (read
 * back by the project's PLY reader as a closed surface), and bad input
 * answered by one line on stderr, exit 2 and no file. */
#include "cli/cli_files.h"
#include "cli/cli_run.h"

#include "subsurf/mesh.h"
#include "subsurf/mesh_io.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

CLI_SUITE(fem_cli);

static const char octa[] = "v 3 0 0\nv -3 0 0\nv 0 3 0\nv 0 -3 0\nv 0 0 3\nv 0 0 -3\n"
                           "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\n"
                           "f 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

Test(fem_cli, box_solution_is_a_closed_ply_and_its_balance_holds, .init = fem_cli_setup,
     .fini = fem_cli_teardown) {
  cli_run_in(&res, dir,
             "fem --box 12,12,6 --sigma-a 0.05 --output out.ply --json out.json "
             "--profile-r 0,1,3",
             0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  char path[512], json[8192];
  snprintf(path, sizeof path, "%s/out.json", dir);
  cli_slurp(path, json, sizeof json);
  double inj, abs_, esc;
  const char *p = strstr(json, "\"injected\":");
  cr_assert(p && sscanf(p, "\"injected\": %lf", &inj) == 1, "%s", json);
  cr_assert(sscanf(strstr(json, "\"absorbed\":"), "\"absorbed\": %lf", &abs_) == 1);
  cr_assert(sscanf(strstr(json, "\"escaped\":"), "\"escaped\": %lf", &esc) == 1);
  /* the spot's refracted power times the albedo sigma_s'/sigma_t' (the rays'
   * first scattering events, all inside the box) */
  cr_assert_float_eq(inj, 1.0 / 1.05, 1e-9);
  cr_assert_float_eq(abs_ + esc, inj, 1e-9);
  /* the exitance is positive at the spot's centre */
  cJSON *j = cli_load_json(dir, "out.json");
  const cJSON *p0 = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "profile"), 0);
  cr_assert_gt(cJSON_GetObjectItemCaseSensitive(p0, "exitance")->valuedouble, 0.0);
  cJSON_Delete(j);
  snprintf(path, sizeof path, "%s/out.ply", dir);
  ss_mesh *m = NULL;
  ss_error err = {0};
  cr_assert_eq(ss_mesh_read_ply(path, &m, NULL, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
  cr_assert_float_eq(ss_mesh_signed_volume(m), 12.0 * 12.0 * 6.0, 1e-3);
  ss_mesh_destroy(m);
}

/* The paper's boundary source (eq. 37-38): Gamma_s is the refracted power
 * attenuated by exp(-sigma_a/sigma_s'); on a spot of half a mean free path
 * its exitance at the centre is negative. */
Test(fem_cli, the_boundary_source_injects_the_attenuated_power, .init = fem_cli_setup,
     .fini = fem_cli_teardown) {
  cli_run_in(&res, dir,
             "fem --box 12,12,6 --sigma-a 0.05 --boundary-source --output out.ply --json out.json "
             "--profile-r 0",
             0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cJSON *j = cli_load_json(dir, "out.json");
  cr_assert_float_eq(cJSON_GetObjectItemCaseSensitive(j, "injected")->valuedouble, exp(-0.05),
                     1e-12);
  const cJSON *p0 = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "profile"), 0);
  cr_assert_lt(cJSON_GetObjectItemCaseSensitive(p0, "exitance")->valuedouble, 0.0);
  cJSON_Delete(j);
}

Test(fem_cli, closed_obj_mesh_is_filled_and_solved, .init = fem_cli_setup,
     .fini = fem_cli_teardown) {
  cli_write_file(dir, "octa.obj", octa);
  cli_run_in(&res, dir, "fem --mesh octa.obj --spot 0,0,3 --solver pcg --output o.ply", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cr_assert(strstr(res.out, "tetrahedra"), "%s", res.out);
  cr_assert(cli_file_exists(dir, "o.ply"));
}

Test(fem_cli, bad_input_names_the_cause_and_writes_nothing, .init = fem_cli_setup,
     .fini = fem_cli_teardown) {
  cli_write_file(dir, "octa.obj", octa);
  char open_mesh[sizeof octa];
  memcpy(open_mesh, octa, sizeof octa);
  *strrchr(open_mesh, 'f') = '\0'; /* drop the last triangle */
  cli_write_file(dir, "open.obj", open_mesh);
  cli_expect_bad_input(&res, dir, "fem --mesh open.obj --output x.ply", "not a closed surface");
  cli_expect_bad_input(&res, dir, "fem --mesh missing.obj --output x.ply", "missing.obj");
  cli_expect_bad_input(&res, dir, "fem --mesh octa.obj --spot 0,0,9 --output x.ply",
                       "does not touch the boundary");
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1 --mesh octa.obj --output x.ply",
                       "exactly one of --box and --mesh");
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1", "--output");
  cli_expect_bad_input(&res, dir, "fem --box 1,1 --output x.ply", "--box");
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1 --size-near 3 --output x.ply", "--size-near");
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1 --solver lu --output x.ply", "--solver");
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1 --sigma-s 0 --output x.ply",
                       "reduced scattering");
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1 --solver pcg --max-iterations 1 --output x.ply",
                       "conjugate gradients did not reach");
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1 --output nodir/x.ply", "nodir");
  cli_expect_bad_input(&res, dir, "fem --box 4,4,2 --point-source --size-rim 0.1 --output x.ply",
                       "--size-rim");
  cli_expect_bad_input(&res, dir, "fem --box 4,4,2 --point-source --boundary-source --output x.ply",
                       "--boundary-source");
  cli_expect_bad_input(&res, dir,
                       "fem --mesh octa.obj --spot 0,0,9 --boundary-source --output x.ply",
                       "does not touch the boundary");
  /* one "fem" in a message: the command's */
  cli_expect_bad_input(&res, dir, "fem --box 1,1,1 --solver pcg --max-iterations 1 --output x.ply",
                       "subsurf fem: conjugate");
}

Test(fem_cli, a_self_intersecting_surface_is_named_and_nothing_is_written, .init = fem_cli_setup,
     .fini = fem_cli_teardown) {
  /* two overlapping octahedra: closed (every edge shared by two triangles)
   * but crossing each other */
  char twin[1024];
  snprintf(twin, sizeof twin,
           "%sv 4.5 0.5 0.3\nv -1.5 0.5 0.3\nv 1.5 3.5 0.3\nv 1.5 -2.5 0.3\nv 1.5 0.5 3.3\n"
           "v 1.5 0.5 -2.7\nf 7 9 11\nf 9 8 11\nf 8 10 11\nf 10 7 11\nf 9 7 12\nf 8 9 12\n"
           "f 10 8 12\nf 7 10 12\n",
           octa);
  cli_write_file(dir, "twin.obj", twin);
  cli_expect_bad_input(&res, dir, "fem --mesh twin.obj --output x.ply --json x.json",
                       "the surface intersects itself");
  cr_expect(!cli_file_exists(dir, "x.json"));
}

Test(fem_cli, ctrl_c_while_meshing_exits_130_and_writes_nothing, .init = fem_cli_setup,
     .fini = fem_cli_teardown) {
  /* about a million tetrahedra: gmsh meshes for minutes */
  cli_run_signalled(&res, dir,
                    "fem --box 60,60,30 --size-far 0.3 --size-near 0.3 --output x.ply "
                    "--json x.json",
                    2.0, SIGINT, 1, 0.0);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(strstr(res.err, "subsurf fem: interrupted; nothing written"), "%s", res.err);
  cr_expect(!cli_file_exists(dir, "x.ply") && !cli_file_exists(dir, "x.json"));
}
