/* Image error metrics (image_metrics.h) on synthetic images whose relMSE,
 * RMSE and means are known in closed form; the mask selects the pixels. */
#include "subsurf/error_map.h"
#include "subsurf/image_metrics.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

static ss_image *filled(int w, int h, float r, float g, float b) {
  ss_image *img = ss_image_create(w, h, 3);
  cr_assert_not_null(img);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float *p = ss_image_pixel(img, x, y);
      p[0] = r;
      p[1] = g;
      p[2] = b;
    }
  }
  return img;
}

Test(image_metrics, identical_images_have_zero_error_and_unit_mean_ratio) {
  ss_image *a = filled(5, 3, 0.25f, 2.0f, 0.0f), *b = filled(5, 3, 0.25f, 2.0f, 0.0f);
  ss_image_error e;
  ss_error err;
  cr_assert_eq(ss_image_error_compute(a, b, NULL, &e, &err), SS_OK, "%s", err.message);
  cr_expect_eq(e.pixels, 15u);
  cr_expect_eq(e.rel_mse, 0.0);
  for (int c = 0; c < 2; ++c) {
    cr_expect_eq(e.rmse[c], 0.0);
    cr_expect_eq(ss_image_error_mean_ratio(&e, c), 1.0);
  }
  cr_expect(isnan(ss_image_error_mean_ratio(&e, 2)), "a black reference has no ratio");
  ss_image_destroy(a);
  ss_image_destroy(b);
}

/* Offsets d_c on a constant reference r_c: relMSE_c = d_c^2 / (r_c + 0.01)^2,
 * RMSE_c = |d_c|, mean ratio (r_c + d_c) / r_c. */
Test(image_metrics, constant_offsets_give_closed_form_errors) {
  const float ref[3] = {1.0f, 0.5f, 4.0f}, d[3] = {0.5f, -0.25f, 2.0f};
  ss_image *img = filled(4, 4, ref[0] + d[0], ref[1] + d[1], ref[2] + d[2]);
  ss_image *r = filled(4, 4, ref[0], ref[1], ref[2]);
  ss_image_error e;
  ss_error err;
  cr_assert_eq(ss_image_error_compute(img, r, NULL, &e, &err), SS_OK, "%s", err.message);
  double all = 0.0;
  for (int c = 0; c < 3; ++c) {
    double rel = (double)d[c] * d[c] / ((ref[c] + 0.01) * (ref[c] + 0.01));
    all += rel / 3.0;
    cr_expect_float_eq(e.rel_mse_c[c], rel, 1e-12);
    cr_expect_float_eq(e.rmse[c], fabs(d[c]), 1e-12);
    cr_expect_float_eq(ss_image_error_mean_ratio(&e, c), (ref[c] + d[c]) / ref[c], 1e-12);
  }
  cr_expect_float_eq(e.rel_mse, all, 1e-12);
  ss_image_destroy(img);
  ss_image_destroy(r);
}

/* Pixels outside the mask are wrong by 1000; inside, half are off by +1 and
 * half by -1 (mean unbiased, RMSE 1). */
Test(image_metrics, only_masked_pixels_count) {
  ss_image *img = filled(4, 2, 1000.0f, 1000.0f, 1000.0f), *r = filled(4, 2, 1.0f, 1.0f, 1.0f);
  ss_image *mask = ss_image_create(4, 2, 1);
  for (int x = 0; x < 4; ++x) {
    *ss_image_pixel(mask, x, 0) = 1.0f;
    float v = x % 2 ? 0.0f : 2.0f;
    float *p = ss_image_pixel(img, x, 0);
    p[0] = p[1] = p[2] = v;
  }
  ss_image_error e;
  ss_error err;
  cr_assert_eq(ss_image_error_compute(img, r, mask, &e, &err), SS_OK, "%s", err.message);
  cr_expect_eq(e.pixels, 4u);
  cr_expect_float_eq(e.rmse[1], 1.0, 1e-12);
  cr_expect_float_eq(e.rel_mse, 1.0 / (1.01 * 1.01), 1e-12);
  cr_expect_float_eq(ss_image_error_mean_ratio(&e, 0), 1.0, 1e-12);
  ss_image_destroy(img);
  ss_image_destroy(r);
  ss_image_destroy(mask);
}

Test(image_metrics, different_sizes_and_empty_masks_are_refused) {
  ss_image *a = filled(4, 2, 1, 1, 1), *b = filled(2, 4, 1, 1, 1);
  ss_image *mask = ss_image_create(4, 2, 1);
  ss_image_error e;
  ss_error err;
  cr_expect_eq(ss_image_error_compute(a, b, NULL, &e, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "4 x 2") && strstr(err.message, "2 x 4"), "%s", err.message);
  cr_expect_eq(ss_image_error_compute(a, a, mask, &e, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "no pixel"), "%s", err.message);
  cr_expect_eq(ss_image_error_compute(a, a, b, &e, &err), SS_ERR_INVALID_ARGUMENT);
  ss_image_destroy(a);
  ss_image_destroy(b);
  ss_image_destroy(mask);
}

/* Relative error 0 maps to the first colour stop, >= the maximum to red;
 * pixels outside the mask are grey whatever their error. */
Test(error_map, colours_follow_the_relative_error_and_the_mask) {
  ss_image *img = filled(3, 1, 1.0f, 1.0f, 1.0f), *ref = filled(3, 1, 1.0f, 1.0f, 1.0f);
  float *p = ss_image_pixel(img, 1, 0);
  p[0] = p[1] = p[2] = 9.0f;
  ss_image *mask = ss_image_create(3, 1, 1);
  mask->data[0] = mask->data[1] = 1.0f;
  ss_image *map = ss_error_map(img, ref, mask);
  cr_assert_not_null(map);
  ss_rgb zero = ss_error_map_colour(0.0), red = ss_error_map_colour(SS_ERROR_MAP_MAX);
  for (int c = 0; c < 3; ++c) {
    cr_expect_float_eq(ss_image_pixel(map, 0, 0)[c], zero.c[c], 1e-7);
    cr_expect_float_eq(ss_image_pixel(map, 1, 0)[c], red.c[c], 1e-7);
    cr_expect_float_eq(ss_image_pixel(map, 2, 0)[c], 0.2, 1e-7);
  }
  cr_expect(red.c[0] == 1.0 && red.c[1] == 0.0 && red.c[2] == 0.0);
  ss_image_destroy(img);
  ss_image_destroy(ref);
  ss_image_destroy(mask);
  ss_image_destroy(map);
}

/* Pixels that are means of n exponential samples (mean mu_c, variance
 * mu_c^2): the estimated relative standard error squared is the relMSE the
 * mean image actually has against the true image mu. 64 x 64 x 3 terms; the
 * relMSE's own relative standard error is about sqrt(2 / 12288 * 9 / n)
 * (heavy exponential tails), so 15 % is over five of them. */
Test(image_metrics, rel_std_error_predicts_the_relmse_against_the_truth) {
  const int w = 64, n = 16;
  const double mu[3] = {0.05, 0.5, 2.0};
  ss_image *img = ss_image_create(w, w, 3), *var = ss_image_create(w, w, 3);
  ss_image *truth = filled(w, w, (float)mu[0], (float)mu[1], (float)mu[2]);
  cr_assert(img && var);
  ss_rng rng;
  ss_rng_seed(&rng, 7, 0);
  for (size_t i = 0; i < (size_t)w * w; ++i) {
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0, sq = 0.0;
      for (int k = 0; k < n; ++k) {
        double x = -mu[c] * log(1.0 - ss_rng_uniform(&rng));
        sum += x;
        sq += x * x;
      }
      double mean = sum / n;
      img->data[3 * i + (size_t)c] = (float)mean;
      var->data[3 * i + (size_t)c] = (float)((sq - n * mean * mean) / (n - 1) / n);
    }
  }
  double e;
  ss_image_error actual;
  ss_error err;
  cr_assert_eq(ss_image_rel_std_error(img, var, NULL, &e, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_image_error_compute(img, truth, NULL, &actual, &err), SS_OK, "%s", err.message);
  cr_expect(fabs(e * e / actual.rel_mse - 1.0) < 0.15, "E^2 %g, relMSE %g", e * e, actual.rel_mse);
  ss_image_destroy(img);
  ss_image_destroy(var);
  ss_image_destroy(truth);
}
