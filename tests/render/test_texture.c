/* Texture lookups: bilinear filtering, wrap modes, procedural patterns. */
#include <criterion/criterion.h>

#include "subsurf/texture.h"

#include <math.h>

/* A w x h grey image whose texel (i, j) (j = row from the top) holds
 * 1 + 2 i + 3 j: bilinear interpolation reproduces a linear function exactly. */
static ss_image *linear_image(int w, int h) {
  ss_image *img = ss_image_create(w, h, 1);
  cr_assert_not_null(img);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      *ss_image_pixel(img, i, j) = (float)(1 + 2 * i + 3 * j);
    }
  }
  return img;
}

static double linear_at(double u, double v, int w, int h) {
  double x = u * w - 0.5, y = (1.0 - v) * h - 0.5; /* texel coordinates */
  return 1.0 + 2.0 * x + 3.0 * y;
}

Test(texture, bilinear_reproduces_a_linear_image_exactly_between_texel_centres) {
  ss_image *img = linear_image(5, 4);
  for (int a = 0; a <= 16; ++a) {
    for (int b = 0; b <= 12; ++b) {
      /* u from the first texel centre to the last one, v likewise */
      double u = (0.5 + 4.0 * a / 16.0) / 5.0, v = (0.5 + 3.0 * b / 12.0) / 4.0;
      for (int wrap = 0; wrap < 3; ++wrap) {
        ss_rgb c = ss_texture_image_lookup(img, (ss_wrap)wrap, u, v);
        cr_assert_float_eq(c.c[0], linear_at(u, v, 5, 4), 1e-12, "u %g v %g wrap %d", u, v, wrap);
        cr_assert_eq(c.c[1], c.c[0]); /* grey fills every channel */
      }
    }
  }
  ss_image_destroy(img);
}

Test(texture, texel_centres_return_the_stored_value) {
  ss_image *img = linear_image(3, 2);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) {
      ss_rgb c = ss_texture_image_lookup(img, SS_WRAP_REPEAT, (i + 0.5) / 3, 1.0 - (j + 0.5) / 2);
      cr_assert_eq(c.c[0], 1 + 2 * i + 3 * j);
    }
  }
  ss_image_destroy(img);
}

Test(texture, wrap_indices_repeat_clamp_and_mirror) {
  const int n = 4;
  const int repeat[] = {3, 0, 1, 2, 3, 0, 1, 2, 3, 0}; /* i = -5 .. 4 */
  const int clamp[] = {0, 0, 0, 0, 0, 0, 1, 2, 3, 3};  /* i = -5 .. 4 */
  const int mirror[] = {3, 3, 2, 1, 0, 0, 1, 2, 3, 3}; /* i = -5 .. 4 */
  for (int i = -5; i <= 4; ++i) {
    cr_assert_eq(ss_texture_wrap_index(i, n, SS_WRAP_REPEAT), repeat[i + 5], "i %d", i);
    cr_assert_eq(ss_texture_wrap_index(i, n, SS_WRAP_CLAMP), clamp[i + 5], "i %d", i);
    cr_assert_eq(ss_texture_wrap_index(i, n, SS_WRAP_MIRROR), mirror[i + 5], "i %d", i);
  }
}

Test(texture, wrapped_lookups_have_the_wrap_modes_symmetries) {
  ss_image *img = linear_image(4, 3);
  for (int k = 0; k <= 20; ++k) {
    double u = -1.3 + 0.17 * k, v = 0.9 - 0.11 * k;
    ss_rgb a = ss_texture_image_lookup(img, SS_WRAP_REPEAT, u, v);
    ss_rgb b = ss_texture_image_lookup(img, SS_WRAP_REPEAT, u + 3.0, v - 2.0);
    cr_assert_float_eq(a.c[0], b.c[0], 1e-9, "repeat has period 1 (u %g)", u);
    ss_rgb m0 = ss_texture_image_lookup(img, SS_WRAP_MIRROR, u, v);
    ss_rgb m1 = ss_texture_image_lookup(img, SS_WRAP_MIRROR, -u, 2.0 - v);
    cr_assert_float_eq(m0.c[0], m1.c[0], 1e-9, "mirror is even about 0 and 1 (u %g)", u);
    ss_rgb c0 = ss_texture_image_lookup(img, SS_WRAP_CLAMP, u, v);
    double cu = fmin(fmax(u, 0.5 / 4), 3.5 / 4), cv = fmin(fmax(v, 0.5 / 3), 2.5 / 3);
    cr_assert_float_eq(c0.c[0], linear_at(cu, cv, 4, 3), 1e-9, "clamp (u %g v %g)", u, v);
  }
  /* Across the seam, repeat blends the last and the first column. */
  ss_rgb seam = ss_texture_image_lookup(img, SS_WRAP_REPEAT, 0.0, 1.0 - 0.5 / 3);
  cr_assert_float_eq(seam.c[0], 0.5 * (1.0 + 7.0), 1e-12);
  ss_image_destroy(img);
}

Test(texture, huge_and_nan_coordinates_stay_inside_the_image) {
  ss_image *img = linear_image(4, 3);
  const double us[] = {1e300, -1e300, NAN, INFINITY, 123456789.25};
  for (int k = 0; k < 5; ++k) {
    for (int wrap = 0; wrap < 3; ++wrap) {
      ss_rgb c = ss_texture_image_lookup(img, (ss_wrap)wrap, us[k], us[(k + 1) % 5]);
      cr_assert(c.c[0] >= 1.0 && c.c[0] <= 1 + 2 * 3 + 3 * 2, "u %g: %g", us[k], c.c[0]);
    }
  }
  ss_image_destroy(img);
}

Test(texture, checker_alternates_by_cell_parity_and_scale_sets_the_cell_count) {
  ss_texture *t;
  ss_error err;
  cr_assert_eq(ss_texture_create_checker(ss_rgb_gray(0.25), ss_rgb_gray(0.75), &t, &err), SS_OK);
  const double scale[2] = {4.0, 2.0}, offset[2] = {0.0, 0.0};
  ss_texture_set_transform(t, scale, offset);
  for (int i = -4; i < 8; ++i) {
    for (int j = -2; j < 4; ++j) {
      ss_texcoord tc = {(i + 0.5) / 4.0, (j + 0.5) / 2.0, ss_vec3_make(0, 0, 0)};
      double expect = ((i + j) % 2 + 2) % 2 ? 0.75 : 0.25;
      cr_assert_eq(ss_texture_eval(t, tc).c[0], expect, "cell (%d, %d)", i, j);
    }
  }
  ss_rgb lo, hi;
  ss_texture_range(t, &lo, &hi);
  cr_assert_eq(lo.c[0], 0.25);
  cr_assert_eq(hi.c[2], 0.75);
  ss_texture_destroy(t);
}

Test(texture, gradient_noise_vanishes_on_the_lattice_and_is_bounded) {
  for (int k = 0; k < 50; ++k) {
    ss_vec3 lattice = ss_vec3_make(k - 25, 3 * k, -k);
    cr_assert_eq(ss_gradient_noise(lattice, 7u), 0.0);
  }
  double mean = 0.0, lo = 1.0, hi = -1.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    ss_vec3 p = ss_vec3_make(0.0137 * k, 0.291 * (k % 97), 0.53 * (k % 13));
    double x = ss_gradient_noise(p, 3u);
    mean += x / n;
    lo = fmin(lo, x);
    hi = fmax(hi, x);
  }
  cr_assert(lo >= -1.0 && hi <= 1.0);
  cr_assert(hi - lo > 0.8, "the noise varies: range [%g, %g]", lo, hi);
  cr_assert(fabs(mean) < 0.05, "mean %g", mean);
}

Test(texture, noise_is_a_function_of_point_and_seed) {
  ss_noise_params q = {
      .octaves = 5, .lacunarity = 2.0, .gain = 0.5, .lo = 0.0, .hi = 1.0, .seed = 1u};
  ss_vec3 p = ss_vec3_make(0.3, 1.7, -2.2);
  double a = ss_noise_fbm(&q, p);
  cr_assert_eq(ss_noise_fbm(&q, p), a);
  q.seed = 2u;
  cr_assert_neq(ss_noise_fbm(&q, p), a);
  cr_assert(a >= 0.0 && a <= 1.0);
}

Test(texture, noise_texture_blends_a_to_b_over_its_range) {
  ss_noise_params q = {
      .octaves = 3, .lacunarity = 2.0, .gain = 0.5, .lo = 0.45, .hi = 0.55, .seed = 9u, .world = 1};
  ss_texture *t;
  ss_error err;
  cr_assert_eq(
      ss_texture_create_noise(ss_rgb_make(0.1, 0.2, 0.3), ss_rgb_make(0.9, 0.8, 0.7), &q, &t, &err),
      SS_OK);
  cr_assert_not(ss_texture_uses_uv(t));
  for (int k = 0; k < 200; ++k) {
    ss_texcoord tc = {0, 0, ss_vec3_make(0.07 * k, 0.5, 0.01 * k)};
    double n = ss_noise_fbm(&q, tc.p), s = fmin(fmax((n - 0.45) / 0.1, 0.0), 1.0);
    ss_rgb c = ss_texture_eval(t, tc);
    cr_assert_float_eq(c.c[0], 0.1 + 0.8 * s, 1e-12);
    cr_assert_float_eq(c.c[2], 0.3 + 0.4 * s, 1e-12);
  }
  q.octaves = 0;
  ss_texture *bad;
  cr_assert_eq(ss_texture_create_noise(ss_rgb_gray(0), ss_rgb_gray(1), &q, &bad, &err),
               SS_ERR_INVALID_ARGUMENT);
  ss_texture_destroy(t);
}

Test(texture, nested_inputs_replace_the_colours) {
  ss_texture *inner, *outer;
  ss_error err;
  cr_assert_eq(ss_texture_create_checker(ss_rgb_gray(0.1), ss_rgb_gray(0.2), &inner, &err), SS_OK);
  cr_assert_eq(ss_texture_create_checker(ss_rgb_gray(0.5), ss_rgb_gray(0.9), &outer, &err), SS_OK);
  ss_texture_set_input(outer, 1, inner);
  ss_texcoord odd = {1.5, 0.5, ss_vec3_make(0, 0, 0)}, even = {0.5, 0.5, ss_vec3_make(0, 0, 0)};
  cr_assert_eq(ss_texture_eval(outer, even).c[0], 0.5);
  cr_assert_eq(ss_texture_eval(outer, odd).c[0], 0.2); /* inner's odd cell */
  ss_rgb lo, hi;
  ss_texture_range(outer, &lo, &hi);
  cr_assert_eq(lo.c[0], 0.1);
  cr_assert_eq(hi.c[0], 0.5);
  ss_texture_destroy(outer);
  ss_texture_destroy(inner);
}
