/* `subsurf fem --grid`: a heterogeneous medium from a raw grid file (the
 * scene format's grid input), its per-voxel flake axes, and bad grids
 * answered by one line naming the option and the file, exit 2, nothing
 * written. */
#include "cli/cli_files.h"
#include "cli/cli_run.h"

#include "subsurf/grid.h"
#include "subsurf/grid_io.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

CLI_SUITE(fem_grid_cli);

/* A grid over the box [-6, 6] x [-6, 6] x [-6, 0] of nx x 1 x 1 voxels with
 * the given densities along x, and every voxel's axis `axis` when non-NULL. */
static void write_grid(const char *name, int nx, const float *density, const double *axis) {
  ss_grid *g = NULL;
  ss_error err = {0};
  int n[3] = {nx, 1, 1};
  cr_assert_eq(
      ss_grid_create(n, ss_vec3_make(-6, -6, -6), ss_vec3_make(6, 6, 0), axis != NULL, &g, &err),
      SS_OK, "%s", err.message);
  for (int i = 0; i < nx; ++i) {
    g->density[i] = density[i];
    if (axis) {
      ss_grid_set_axis(g, i, ss_vec3_make(axis[0], axis[1], axis[2]));
    }
  }
  cr_assert_eq(ss_grid_finish(g, &err), SS_OK, "%s", err.message);
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  cr_assert_eq(ss_grid_write_raw(path, g, &err), SS_OK, "%s", err.message);
  ss_grid_destroy(g);
}

static double json_number(const char *name, const char *key) {
  cJSON *j = cli_load_json(dir, name);
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(j, key);
  cr_assert(cJSON_IsNumber(v), "%s: no %s", name, key);
  double x = v->valuedouble;
  cJSON_Delete(j);
  return x;
}

/* The exitance at the profile's first radius. */
static double profile_exitance(const char *name) {
  cJSON *j = cli_load_json(dir, name);
  const cJSON *p = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "profile"), 0);
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(p, "exitance");
  cr_assert(cJSON_IsNumber(v), "%s: no profile", name);
  double x = v->valuedouble;
  cJSON_Delete(j);
  return x;
}

#define BOX "fem --box 12,12,6 --sigma-a 0.05 --size-near 0.5 --size-far 3 "

Test(fem_grid_cli, a_grid_of_density_one_gives_the_homogeneous_solution, .init = fem_grid_cli_setup,
     .fini = fem_grid_cli_teardown) {
  float one[2] = {1.0f, 1.0f};
  write_grid("one.ssgrid", 2, one, NULL);
  cli_run_in(&res, dir, BOX "--output a.ply --json a.json", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cli_run_in(&res, dir, BOX "--grid one.ssgrid --output b.ply --json b.json", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  const char *keys[] = {"injected", "absorbed", "escaped"};
  for (int k = 0; k < 3; ++k) {
    double a = json_number("a.json", keys[k]), b = json_number("b.json", keys[k]);
    cr_expect_float_eq(a, b, 1e-9 * fabs(a), "%s: %g without the grid, %g with it", keys[k], a, b);
  }
}

/* Denser on one side (densities 1 and 4 along x): the light from the spot
 * at the centre decays faster into the denser side, so the exitance 3 mfp
 * from the spot towards it is below that of the mirrored grid; moving the
 * grid by --grid-offset so that its dense end is under the spot raises the
 * absorbed part. */
Test(fem_grid_cli, light_decays_faster_into_the_denser_side, .init = fem_grid_cli_setup,
     .fini = fem_grid_cli_teardown) {
  float up[2] = {1.0f, 4.0f}, down[2] = {4.0f, 1.0f};
  write_grid("up.ssgrid", 2, up, NULL);
  write_grid("down.ssgrid", 2, down, NULL);
  const char *runs[] = {BOX "--grid up.ssgrid --profile-r 3 --output u.ply --json u.json",
                        BOX "--grid down.ssgrid --profile-r 3 --output d.ply --json d.json"};
  for (int i = 0; i < 2; ++i) {
    cli_run_in(&res, dir, runs[i], 0.0);
    cr_assert_eq(res.status, 0, "%s", res.err);
  }
  double towards_dense = profile_exitance("u.json"), towards_thin = profile_exitance("d.json");
  cr_expect_lt(towards_dense, 0.8 * towards_thin,
               "exitance 3 mfp away: %g into the dense side, "
               "%g into the thin side",
               towards_dense, towards_thin);
  cr_expect_float_eq(json_number("u.json", "absorbed") + json_number("u.json", "escaped"),
                     json_number("u.json", "injected"), 1e-8, "energy balance");
}

/* Fibre-like flakes whose axis comes from the grid's voxels equal the same
 * flakes given --medium-axis. */
Test(fem_grid_cli, the_grid_axes_orient_the_flakes, .init = fem_grid_cli_setup,
     .fini = fem_grid_cli_teardown) {
  float one[1] = {1.0f};
  double x[3] = {1, 0, 0};
  write_grid("axis.ssgrid", 1, one, x);
  cli_run_in(&res, dir,
             BOX "--flakes fiber --medium-axis 1,0,0 --profile-r 2 --output a.ply --json a.json",
             0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cli_run_in(&res, dir,
             BOX "--flakes fiber --grid axis.ssgrid --profile-r 2 --output b.ply --json b.json",
             0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  double a = profile_exitance("a.json"), b = profile_exitance("b.json");
  /* the grid stores axes in 16-bit octahedral coordinates */
  cr_expect_float_eq(a, b, 1e-4 * a, "exitance at 2: %g with --medium-axis, %g from the grid", a,
                     b);
  /* and differs from flakes about +z (the default axis) */
  cli_run_in(&res, dir, BOX "--flakes fiber --profile-r 2 --output c.ply --json c.json", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  cr_expect_gt(fabs(profile_exitance("c.json") - a), 0.05 * a);
}

/* --size-medium: a density step (1 to 4 at x = 0, voxels of 0.5) gets
 * smaller elements, so more of them, and the same energy balance; a
 * homogeneous grid gets none. */
Test(fem_grid_cli, size_medium_refines_at_a_density_step, .init = fem_grid_cli_setup,
     .fini = fem_grid_cli_teardown) {
  float step[24], one[24];
  for (int i = 0; i < 24; ++i) {
    step[i] = i < 12 ? 1.0f : 4.0f;
    one[i] = 1.0f;
  }
  write_grid("step.ssgrid", 24, step, NULL);
  write_grid("one.ssgrid", 24, one, NULL);
  const char *runs[] = {BOX "--grid step.ssgrid --output a.ply --json a.json",
                        BOX "--grid step.ssgrid --size-medium 0.5 --output b.ply --json b.json",
                        BOX "--grid one.ssgrid --output c.ply --json c.json",
                        BOX "--grid one.ssgrid --size-medium 0.5 --output d.ply --json d.json"};
  for (int i = 0; i < 4; ++i) {
    cli_run_in(&res, dir, runs[i], 0.0);
    cr_assert_eq(res.status, 0, "%s", res.err);
  }
  double plain = json_number("a.json", "tetrahedra"), refined = json_number("b.json", "tetrahedra");
  cr_expect_gt(refined, 1.3 * plain, "tetrahedra: %g without --size-medium, %g with it", plain,
               refined);
  cr_expect_float_eq(json_number("b.json", "absorbed") + json_number("b.json", "escaped"),
                     json_number("b.json", "injected"), 1e-8, "energy balance");
  cr_expect_eq(json_number("c.json", "tetrahedra"), json_number("d.json", "tetrahedra"),
               "a homogeneous grid is not refined");
  cli_expect_bad_input(&res, dir, BOX "--size-medium 0.5 --output x.ply", "--size-medium");
  cli_expect_bad_input(&res, dir, BOX "--grid one.ssgrid --size-medium 0 --output x.ply",
                       "--size-medium");
}

Test(fem_grid_cli, bad_grids_name_the_option_and_the_file, .init = fem_grid_cli_setup,
     .fini = fem_grid_cli_teardown) {
  float zero[2] = {0.0f, 0.0f}, one[2] = {1.0f, 1.0f};
  write_grid("zero.ssgrid", 2, zero, NULL);
  write_grid("one.ssgrid", 2, one, NULL);
  char path[512];
  snprintf(path, sizeof path, "%s/one.ssgrid", dir);
  char data[200];
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f);
  size_t n = fread(data, 1, sizeof data, f);
  fclose(f);
  cli_write_file(dir, "short.ssgrid", "SSGRID1\n");
  snprintf(path, sizeof path, "%s/trunc.ssgrid", dir);
  f = fopen(path, "wb");
  cr_assert_not_null(f);
  fwrite(data, 1, n - 3, f);
  fclose(f);
  cli_expect_bad_input(&res, dir, BOX "--grid missing.ssgrid --output x.ply", "missing.ssgrid");
  cli_expect_bad_input(&res, dir, BOX "--grid short.ssgrid --output x.ply", "short.ssgrid");
  cli_expect_bad_input(&res, dir, BOX "--grid trunc.ssgrid --output x.ply", "trunc.ssgrid");
  cli_expect_bad_input(&res, dir, BOX "--grid zero.ssgrid --output x.ply", "every density is 0");
  cli_expect_bad_input(&res, dir, BOX "--grid short.ssgrid --output x.ply", "--grid");
  cli_expect_bad_input(&res, dir, BOX "--grid one.ssgrid --grid-offset 1,2 --output x.ply",
                       "--grid-offset");
  cli_expect_bad_input(&res, dir, BOX "--grid one.ssgrid --min-density 0 --output x.ply",
                       "--min-density");
  cli_expect_bad_input(&res, dir, BOX "--grid one.ssgrid --min-density 2 --output x.ply",
                       "--min-density");
}
