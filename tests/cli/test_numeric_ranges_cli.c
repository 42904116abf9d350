/* Finite values that would break the arithmetic are refused before any work
 * (exit 2, one line): an eta that rounds the Fresnel terms to 0 or 1, radial
 * bins too narrow to tell apart, a camera beyond the float range Embree
 * works in, a light whose radiance overflows an image. Values inside the
 * documented ranges give finite answers. */
#include "cli/cli_run.h"

#include <criterion/criterion.h>

CLI_SUITE(numeric_ranges_cli);

Test(numeric_ranges_cli, extreme_eta_is_refused_at_once_by_reference_and_models) {
  const char *cmds[] = {"halfspace --json out.json", "model --model dipole --json out.json",
                        "model --model pbd --json out.json",
                        "compare-halfspace --models single --json out.json"};
  const char *etas[] = {"1e20", "1e-300", "0.05", "20"};
  char args[256];
  for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; ++i) {
    for (size_t k = 0; k < sizeof etas / sizeof etas[0]; ++k) {
      snprintf(args, sizeof args, "%s --eta %s", cmds[i], etas[k]);
      double t0 = cli_now();
      cli_expect_bad_input(&res, dir, args, "eta");
      cr_expect(cli_now() - t0 < 5.0, "'%s' took %.1f s to refuse", args, cli_now() - t0);
    }
  }
}

Test(numeric_ranges_cli, models_at_the_ends_of_the_eta_range_give_finite_numbers) {
  const char *models[] = {"dipole", "single", "dipole-brdf", "better-dipole", "dirpole", "pbd"};
  const char *etas[] = {"0.1", "10"};
  char args[256];
  for (size_t i = 0; i < sizeof models / sizeof models[0]; ++i) {
    for (size_t k = 0; k < sizeof etas / sizeof etas[0]; ++k) {
      snprintf(args, sizeof args, "model --model %s --eta %s --profile-r 0,1e-6,1,1e6 --json -",
               models[i], etas[k]);
      cli_run_in(&res, dir, args, 0.0);
      cr_expect_eq(res.status, 0, "'%s': exit %d: %s", args, res.status, res.err);
      cr_expect(strstr(res.out, "null") == NULL, "'%s' printed a non-finite number", args);
    }
  }
}

Test(numeric_ranges_cli, coefficients_and_lengths_beyond_the_limits_are_refused) {
  cli_expect_bad_input(&res, dir, "halfspace --sigma-s 1e7", "--sigma-s");
  cli_expect_bad_input(&res, dir, "halfspace --sigma-s 1e-9 --sigma-a 0", "sigma");
  cli_expect_bad_input(&res, dir, "halfspace --xmax 1e308", "xmax");
  cli_expect_bad_input(&res, dir, "model --model dipole --rmax 1e7", "rmax");
  cli_expect_bad_input(&res, dir, "model --model dipole --profile-r 1,1e300", "--profile-r");
  cli_expect_bad_input(&res, dir, "halfspace --thickness 1e300", "thickness");
}

Test(numeric_ranges_cli, radial_bins_narrower_than_doubles_resolve_are_refused) {
  cli_expect_bad_input(&res, dir, "halfspace --rmin 1 --rmax 1.0000000000000002", "rmax");
  cli_expect_bad_input(&res, dir, "model --model dipole --rmin 1 --rmax 1.000000000001", "rmax");
}

/* Exits far beyond rmax with bins just wide enough: the bin index of such an
 * exit exceeds the range of an int (undefined behaviour that the float-cast
 * sanitizer of `make check` reports) unless it is compared first. */
Test(numeric_ranges_cli, exits_far_beyond_narrow_radial_bins_are_counted_outside) {
  cli_run_in(&res, dir,
             "halfspace --sigma-s 0.02 --sigma-a 0.001 --rmin 1 --rmax 1.000000002 --rbins 2 "
             "--paths 2000 --quiet --json out.json",
             0.0);
  cr_expect_eq(res.status, 0, "exit %d: %s", res.status, res.err);
}

static const char *scene_with(const char *camera_z, const char *radiance) {
  static char text[1024];
  snprintf(text, sizeof text,
           "{\"camera\": {\"position\": [0, 0, %s], \"resolution\": [8, 8]},\n"
           " \"shapes\": [{\"name\": \"ball\", \"type\": \"sphere\", \"subdivisions\": 1},\n"
           "   {\"name\": \"lamp\", \"type\": \"sphere\", \"radius\": 0.5, \"center\": [3, 2, 2],"
           " \"subdivisions\": 1}],\n"
           " \"lights\": [{\"name\": \"lamp\", \"type\": \"area\", \"shape\": \"lamp\","
           " \"radiance\": %s}],\n"
           " \"integrator\": {\"type\": \"path\"}, \"render\": {\"spp\": 1}}\n",
           camera_z, radiance);
  return text;
}

Test(numeric_ranges_cli, a_camera_beyond_the_world_limit_is_refused_not_aborted) {
  cli_write_file(dir, "far.json", scene_with("1e19", "1"));
  cli_expect_bad_input(&res, dir, "render far.json -o out.exr", "camera");
  cli_run_in(&res, dir, "render far.json -o out.exr", 0.0);
  cr_expect_eq(res.status, 2, "Embree must never see the camera: exit %d", res.status);
}

Test(numeric_ranges_cli, a_light_near_the_float_limit_is_refused) {
  cli_write_file(dir, "bright.json", scene_with("5", "3e38"));
  cli_expect_bad_input(&res, dir, "render bright.json -o out.exr", "lamp");
}

/* Converted to integers only once in range (the float-cast sanitizer of
 * `make check` reports the conversion of 1e300 otherwise). */
Test(numeric_ranges_cli, huge_counts_in_a_scene_are_refused_before_conversion) {
  cli_write_file(dir, "res.json",
                 "{\"camera\": {\"resolution\": [1e300, 8]},\n"
                 " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}]}\n");
  cli_expect_bad_input(&res, dir, "render res.json -o out.exr", "resolution");
  cli_write_file(dir, "quad.json",
                 "{\"camera\": {\"resolution\": [8, 8]},\n"
                 " \"shapes\": [{\"type\": \"quad\", \"tessellation\": [1e300, 2]}]}\n");
  cli_expect_bad_input(&res, dir, "render quad.json -o out.exr", "tessellation");
}
