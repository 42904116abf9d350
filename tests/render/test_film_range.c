/* The film's images are float: a pixel mean beyond the float range is
 * written as the largest float and counted, never as Inf. */
#include "subsurf/film.h"

#include <criterion/criterion.h>
#include <float.h>
#include <math.h>

Test(film_range, means_beyond_float_are_clamped_and_counted) {
  ss_film *film;
  ss_error err;
  cr_assert_eq(ss_film_create(2, 1, &film, &err), SS_OK);
  ss_film_add_sample(film, 0, 0, ss_rgb_make(1e300, 1.0, -1e300));
  ss_film_add_sample(film, 1, 0, ss_rgb_make(0.5, 0.25, 2.0));
  ss_image *img = ss_film_image(film);
  cr_assert_not_null(img);
  const float *p = ss_image_pixel(img, 0, 0);
  cr_expect_eq(p[0], FLT_MAX);
  cr_expect_eq(p[1], 1.0f);
  cr_expect_eq(p[2], -FLT_MAX);
  cr_expect_eq(ss_image_pixel(img, 1, 0)[2], 2.0f);
  cr_expect_eq(ss_film_clamped_count(film), 2);
  ss_image_destroy(img);
  ss_film_destroy(film);
}

Test(film_range, an_ordinary_film_has_nothing_clamped) {
  ss_film *film;
  ss_error err;
  cr_assert_eq(ss_film_create(3, 3, &film, &err), SS_OK);
  for (int i = 0; i < 9; ++i) {
    /* Variances of the mean up to 1e30: within float. */
    ss_film_add_sample(film, i % 3, i / 3, ss_rgb_make(i, 2.0 * i, 1e15));
    ss_film_add_sample(film, i % 3, i / 3, ss_rgb_make(-i, 0.0, 3e15));
  }
  cr_expect_eq(ss_film_clamped_count(film), 0);
  cr_expect_eq(ss_film_bytes(3, 3), 9.0 * ss_film_bytes(1, 1));
  ss_film_destroy(film);
}
