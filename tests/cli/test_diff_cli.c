/* subsurf diff: the numbers of image_metrics.h for two images written here
 * with known values, the error map, and bad input. */
#include "cli_run.h"

#include "subsurf/image.h"
#include "subsurf/image_io.h"

#include <cjson/cJSON.h>
#include <criterion/criterion.h>

static char dir[64];
static cli_result res;

static void setup(void) { cli_tmpdir(dir, sizeof dir); }

TestSuite(diff_cli, .init = setup);

/* A w x h image of constant (r, g, b) in dir/name. */
static void write_constant(const char *name, int w, int h, float r, float g, float b) {
  ss_image *img = ss_image_create(w, h, 3);
  cr_assert(img != NULL);
  for (int i = 0; i < w * h; ++i) {
    img->data[3 * i] = r;
    img->data[3 * i + 1] = g;
    img->data[3 * i + 2] = b;
  }
  char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  ss_error err;
  cr_assert_eq(ss_image_write_exr(path, img, &err), SS_OK, "%s", err.message);
  ss_image_destroy(img);
}

static double item(const cJSON *j, const char *key, int i) {
  return cJSON_GetArrayItem(cJSON_GetObjectItem(j, key), i)->valuedouble;
}

Test(diff_cli, reports_the_relmse_and_mean_ratio_of_known_images) {
  write_constant("img.exr", 8, 4, 1.0f, 0.5f, 0.25f);
  write_constant("ref.exr", 8, 4, 0.5f, 0.5f, 0.5f);
  cli_run_in(&res, dir, "diff img.exr ref.exr --json - --map map.png", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *j = cJSON_Parse(res.out);
  cr_assert(j != NULL, "not JSON: %s", res.out);
  cr_expect_eq(cJSON_GetObjectItem(j, "pixels")->valuedouble, 32.0);
  /* (v - ref)^2 / (ref + 0.01)^2 per channel, the same at every pixel. */
  double d = 0.51 * 0.51;
  double expect[3] = {0.25 / d, 0.0, 0.0625 / d};
  for (int c = 0; c < 3; ++c) {
    cr_expect_float_eq(item(j, "rel_mse_rgb", c), expect[c], 1e-6, "channel %d", c);
  }
  cr_expect_float_eq(cJSON_GetObjectItem(j, "rel_mse")->valuedouble,
                     (expect[0] + expect[1] + expect[2]) / 3.0, 1e-6);
  cr_expect_float_eq(item(j, "mean_ratio_rgb", 0), 2.0, 1e-6);
  cr_expect_float_eq(item(j, "mean_ratio_rgb", 1), 1.0, 1e-6);
  cr_expect_float_eq(item(j, "mean_ratio_rgb", 2), 0.5, 1e-6);
  cr_expect_float_eq(item(j, "rmse_rgb", 2), 0.25, 1e-6);
  cJSON_Delete(j);
  cr_expect(cli_path_exists(dir, "map.png"), "no error map written");
}

Test(diff_cli, a_black_reference_has_no_ratio) {
  write_constant("img.exr", 2, 2, 0.1f, 0.1f, 0.1f);
  write_constant("ref.exr", 2, 2, 0.0f, 0.0f, 0.0f);
  cli_run_in(&res, dir, "diff img.exr ref.exr --json -", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cJSON *j = cJSON_Parse(res.out);
  cr_assert(j != NULL, "not JSON: %s", res.out);
  cr_expect(cJSON_IsNull(cJSON_GetArrayItem(cJSON_GetObjectItem(j, "mean_ratio_rgb"), 0)));
  cJSON_Delete(j);
}

Test(diff_cli, bad_input_is_one_line_exit_2_and_nothing_written) {
  write_constant("img.exr", 8, 4, 1.0f, 0.5f, 0.25f);
  write_constant("ref.exr", 8, 4, 0.5f, 0.5f, 0.5f);
  write_constant("small.exr", 4, 4, 0.5f, 0.5f, 0.5f);
  struct {
    const char *args, *needle;
  } cases[] = {
      {"diff img.exr", "REFERENCE"},
      {"diff img.exr missing.exr", "missing.exr"},
      {"diff img.exr small.exr --json out.json", "8 x 4"},
      {"diff img.exr ref.exr --map img.exr", "--map"},
      {"diff img.exr ref.exr --map out.bmp", "--map"},
      {"diff img.exr ref.exr --mask ref.exr --json out.json", "mask"},
      {"diff img.exr ref.exr extra.exr", "extra.exr"},
      {"diff img.exr ref.exr --frobnicate 1", "--frobnicate"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    cli_expect_bad_input(&res, dir, cases[i].args, cases[i].needle);
  }
}
