/* The monotonic clock of progress reports and timings; image buffers. */
#include "subsurf/image.h"
#include "subsurf/progress.h"

#include <criterion/criterion.h>
#include <time.h>

static void sleep_seconds(double s) {
  struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
  nanosleep(&ts, NULL);
}

Test(progress, seconds_is_monotonic_and_advances) {
  double t0 = ss_seconds();
  sleep_seconds(0.02);
  double t1 = ss_seconds();
  cr_assert(t1 - t0 >= 0.019 && t1 - t0 < 1.0, "slept 20 ms, clock advanced %g s", t1 - t0);
}

Test(image, create_zeroes_and_rejects_bad_sizes) {
  ss_image *img = ss_image_create(3, 2, 4);
  cr_assert_not_null(img);
  cr_assert_eq(img->width, 3);
  cr_assert_eq(img->height, 2);
  cr_assert_eq(img->channels, 4);
  for (int i = 0; i < 3 * 2 * 4; ++i) {
    cr_assert_eq(img->data[i], 0.0f);
  }
  ss_image_pixel(img, 2, 1)[3] = 7.0f;
  cr_assert_eq(img->data[(1 * 3 + 2) * 4 + 3], 7.0f, "row-major, interleaved");
  ss_image_destroy(img);
  cr_assert_null(ss_image_create(0, 2, 1));
  cr_assert_null(ss_image_create(2, -1, 1));
  cr_assert_null(ss_image_create(2, 2, 0));
  cr_assert_null(ss_image_create(1 << 30, 1 << 30, 1 << 30), "size overflow");
  ss_image_destroy(NULL);
}
