/* `subsurf render` from the outside: bad input exits 2 with one clear line
 * and writes nothing; a tiny render writes EXR + PNG with the expected
 * content; --crop, --time-limit and Ctrl-C behave as documented. */
#include <criterion/criterion.h>

#include "cli/cli_run.h"
#include "subsurf/image_io.h"

#include <math.h>

static char dir[64];
static cli_result res;

/* A white Lambertian sphere in a uniform sky of radiance 1: every pixel
 * converges to 1 (a furnace), so the image content can be checked. */
static const char *furnace_scene =
    "{\n"
    "  \"camera\": {\"position\": [0, 0, 4], \"fov\": 20, \"resolution\": [16, 12]},\n"
    "  \"materials\": [{\"name\": \"white\", \"type\": \"diffuse\", \"albedo\": 1}],\n"
    "  \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 3, \"material\": \"white\"}],\n"
    "  \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
    "  \"integrator\": {\"type\": \"path\"},\n"
    "  \"render\": {\"spp\": 4}\n"
    "}\n";

static void write_file(const char *name, const char *text) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f);
  fputs(text, f);
  fclose(f);
}

static void setup(void) {
  cli_tmpdir(dir, sizeof dir);
  cr_assert(dir[0]);
  write_file("scene.json", furnace_scene);
}

static void teardown(void) {
  char cmd[512];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_expect_eq(system(cmd), 0);
}

TestSuite(render_cli, .init = setup, .fini = teardown);

static int count_lines(const char *s) {
  int n = 0;
  for (; *s; ++s) {
    n += *s == '\n';
  }
  return n;
}

static void expect_bad_input(const char *args, const char *words) {
  cli_run_in(&res, dir, args, 0.0);
  cr_expect_eq(res.status, 2, "'%s': exit %d, stderr: %s", args, res.status, res.err);
  cr_expect_eq(count_lines(res.err), 1, "'%s': expected one line, got: %s", args, res.err);
  cr_expect(strstr(res.err, words) != NULL, "'%s': stderr '%s' does not say '%s'", args, res.err,
            words);
  cr_expect(!cli_file_exists(dir, "out.exr") && !cli_file_exists(dir, "scene.exr"),
            "'%s' wrote an image", args);
}

Test(render_cli, bad_input_exits_2_with_one_line) {
  expect_bad_input("render missing.json -o out.exr", "missing.json");
  expect_bad_input("render scene.json --spp 0 -o out.exr", "--spp");
  expect_bad_input("render scene.json --threads many", "--threads");
  expect_bad_input("render scene.json -o out.png", "--output");
  expect_bad_input("render scene.json --crop 5,5,2,2", "--crop");
  expect_bad_input("render scene.json --crop 0,0,100,100", "exceeds");
  expect_bad_input("render scene.json --integrator bdpt", "bdpt");
  expect_bad_input("render scene.json --frobnicate", "--frobnicate");
  expect_bad_input("render", "missing the scene file");
  write_file("broken.json",
             "{\n  \"camera\": {\"fov\": 30},\n  \"shapes\": [{\"type\": \"cone\"}]\n}\n");
  expect_bad_input("render broken.json -o out.exr", "broken.json:3: shapes[0].type");
}

Test(render_cli, tiny_render_writes_exr_and_png) {
  cli_run_in(&res, dir, "render scene.json -o out.exr --spp 8 --seed 3 --variance", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(cli_file_exists(dir, "out.exr"));
  cr_expect(cli_file_exists(dir, "out.png"));
  cr_expect(cli_file_exists(dir, "out-variance.exr"));
  cr_expect(strstr(res.out, "out.exr") && strstr(res.out, "out.png"), "stdout: %s", res.out);
  cr_expect(strstr(res.out, "samples/s") && strstr(res.out, "NaN/Inf samples dropped: 0"),
            "stdout: %s", res.out);
  char path[512];
  snprintf(path, sizeof path, "%s/out.exr", dir);
  ss_image *img = NULL;
  ss_error err;
  cr_assert_eq(ss_image_read(path, &img, &err), SS_OK, "%s", err.message);
  cr_expect_eq(img->width, 16);
  cr_expect_eq(img->height, 12);
  /* Furnace: the mean over all pixels is 1 (per-sample spread is small). */
  double sum = 0.0;
  size_t n = (size_t)img->width * img->height * img->channels;
  for (size_t i = 0; i < n; ++i) {
    sum += img->data[i];
  }
  cr_expect(fabs(sum / n - 1.0) < 0.02, "mean pixel %g, expected 1", sum / n);
  ss_image_destroy(img);
  /* The variance of each pixel mean: non-negative, and small next to 1. */
  snprintf(path, sizeof path, "%s/out-variance.exr", dir);
  cr_assert_eq(ss_image_read(path, &img, &err), SS_OK, "%s", err.message);
  double vmax = 0.0;
  for (size_t i = 0; i < n; ++i) {
    cr_expect(img->data[i] >= 0.0f);
    vmax = fmax(vmax, img->data[i]);
  }
  cr_expect(vmax > 0.0 && vmax < 0.5, "largest variance of a pixel mean %g", vmax);
  ss_image_destroy(img);
}

Test(render_cli, a_scene_where_nothing_emits_is_rendered_with_one_warning) {
  write_file("dark.json", "{\"camera\": {\"resolution\": [8, 8]},\n"
                          " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
                          " \"lights\": [{\"type\": \"point\", \"intensity\": 0}],\n"
                          " \"render\": {\"spp\": 1}}\n");
  cli_run_in(&res, dir, "render dark.json -o dark.exr --quiet", 0.0);
  cr_expect_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(cli_file_exists(dir, "dark.exr"));
  cr_expect_eq(count_lines(res.err), 1, "stderr: %s", res.err);
  cr_expect(strstr(res.err, "warning: dark.json: nothing emits light"), "stderr: %s", res.err);
  /* A lit scene has no such warning. */
  cli_run_in(&res, dir, "render scene.json -o out.exr --quiet --spp 1", 0.0);
  cr_expect_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(!strstr(res.err, "nothing emits"), "stderr: %s", res.err);
}

Test(render_cli, default_output_name_follows_the_scene_and_crop_shrinks_it) {
  cli_run_in(&res, dir, "render scene.json --spp 1 --quiet --crop 2,3,10,7 --no-png", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(cli_file_exists(dir, "scene.exr"));
  cr_expect(!cli_file_exists(dir, "scene.png"));
  char path[512];
  snprintf(path, sizeof path, "%s/scene.exr", dir);
  ss_image *img = NULL;
  ss_error err;
  cr_assert_eq(ss_image_read(path, &img, &err), SS_OK, "%s", err.message);
  cr_expect_eq(img->width, 8);
  cr_expect_eq(img->height, 4);
  ss_image_destroy(img);
}

Test(render_cli, time_limit_stops_early_and_writes_the_image) {
  double t0 = (double)time(NULL);
  cli_run_in(&res, dir, "render scene.json -o out.exr --spp 100000000 --time-limit 0.5", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect((double)time(NULL) - t0 < 20.0, "the time limit was not honoured");
  cr_expect(cli_file_exists(dir, "out.exr") && cli_file_exists(dir, "out.png"));
  cr_expect(strstr(res.out, "time limit") != NULL, "stdout: %s", res.out);
}

Test(render_cli, ctrl_c_writes_partial_image_and_exits_130) {
  cli_run_in(&res, dir, "render scene.json -o out.exr --spp 100000000 --quiet", 1.0);
  cr_expect_eq(res.status, 130, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(cli_file_exists(dir, "out-partial.exr"));
  cr_expect(cli_file_exists(dir, "out-partial.png"));
  cr_expect(!cli_file_exists(dir, "out.exr"));
}

Test(render_cli, help_lists_the_options) {
  cli_run_in(&res, dir, "render --help", 0.0);
  cr_expect_eq(res.status, 0);
  const char *opts[] = {"--output",     "--spp",   "--threads",    "--seed",
                        "--integrator", "--crop",  "--time-limit", "--exposure",
                        "--variance",   "--quiet", "volpath"};
  for (size_t i = 0; i < sizeof opts / sizeof opts[0]; ++i) {
    cr_expect(strstr(res.out, opts[i]) != NULL, "--help misses %s", opts[i]);
  }
}
