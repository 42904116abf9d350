/* The camera's conventions (what other renderers must match to reproduce a
 * scene) and the reconstruction filters' sampling. */
#include <criterion/criterion.h>

#include "subsurf/camera.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/stats.h"

#include <math.h>

static ss_camera default_camera(void) {
  ss_camera cam;
  ss_camera_default(&cam);
  cam.width = 200;
  cam.height = 100;
  ss_error err;
  cr_assert_eq(ss_camera_init(&cam, &err), SS_OK, "%s", err.message);
  return cam;
}

Test(camera, plus_x_is_right_and_plus_y_is_up_seen_from_plus_z) {
  ss_camera cam = default_camera();
  double x, y;
  cr_assert(ss_camera_raster(&cam, ss_vec3_sub(ss_vec3_make(0.5, 0.2, 0), cam.position), &x, &y));
  cr_expect_gt(x, 100.0, "+x must be in the right half");
  cr_expect_lt(y, 50.0, "+y must be in the top half (row 0 is the top)");
}

Test(camera, vertical_fov_spans_the_image_height) {
  ss_camera cam = default_camera();
  /* A point at the top edge of the 30 degree vertical field of view. */
  ss_vec3 d = ss_vec3_make(0, tan(15.0 * SS_PI / 180.0), -1);
  double x, y;
  cr_assert(ss_camera_raster(&cam, d, &x, &y));
  cr_expect_float_eq(y, 0.0, 1e-9);
  cr_expect_float_eq(x, 100.0, 1e-9);
}

Test(camera, rays_pass_through_their_pixel) {
  ss_camera cam = default_camera();
  ss_rng rng;
  ss_rng_seed(&rng, 1, 1);
  for (int i = 0; i < 1000; ++i) {
    int px = (int)(ss_rng_uniform(&rng) * 200), py = (int)(ss_rng_uniform(&rng) * 100);
    ss_ray r = ss_camera_generate_ray(&cam, px, py, ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    cr_assert_float_eq(ss_vec3_length(r.d), 1.0, 1e-12);
    double x, y;
    cr_assert(ss_camera_raster(&cam, r.d, &x, &y));
    cr_expect(x >= px - 1e-9 && x <= px + 1 + 1e-9 && y >= py - 1e-9 && y <= py + 1 + 1e-9,
              "ray of pixel (%d, %d) lands at (%g, %g)", px, py, x, y);
  }
}

Test(camera, gaussian_filter_samples_have_the_truncated_gaussian_variance) {
  ss_filter f = ss_filter_default(SS_FILTER_GAUSSIAN);
  ss_rng rng;
  ss_rng_seed(&rng, 2, 2);
  ss_running_stats r2;
  ss_running_stats_init(&r2);
  for (int i = 0; i < 200000; ++i) {
    double dx, dy;
    ss_filter_sample(&f, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &dx, &dy);
    cr_assert(dx * dx + dy * dy <= f.radius * f.radius * (1 + 1e-12));
    ss_running_stats_add(&r2, dx * dx + dy * dy);
  }
  /* E[r^2] of a 2D Gaussian truncated at R: 2 s^2 - R^2 e / (1 - e), e = exp(-R^2 / 2 s^2). */
  double s2 = f.sigma * f.sigma, R2 = f.radius * f.radius, e = exp(-R2 / (2 * s2));
  double expected = 2 * s2 - R2 * e / (1 - e);
  cr_expect(fabs(r2.mean - expected) < 4 * ss_running_stats_stderr(&r2), "E[r^2] %g vs %g", r2.mean,
            expected);
}

Test(camera, invalid_cameras_are_rejected) {
  ss_camera cam;
  ss_error err;
  ss_camera_default(&cam);
  cam.target = cam.position;
  cr_expect_eq(ss_camera_init(&cam, &err), SS_ERR_INVALID_ARGUMENT);
  ss_camera_default(&cam);
  cam.up = ss_vec3_make(0, 0, 1);
  cr_expect_eq(ss_camera_init(&cam, &err), SS_ERR_INVALID_ARGUMENT);
  ss_camera_default(&cam);
  cam.fov_deg = 180;
  cr_expect_eq(ss_camera_init(&cam, &err), SS_ERR_INVALID_ARGUMENT);
}
