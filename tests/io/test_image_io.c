/* Image files: EXR and PFM round trips are exact for float data, PNG has the
 * right size and tonemapping, and a failed write reports the path and leaves
 * no file behind. */
#include "subsurf/image_io.h"

#include "io/io_test_dir.h"

#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stb/stb_image.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[64];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "/tmp/subsurf-image-io-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void) {
  DIR *d = opendir(dir);
  if (!d) {
    return;
  }
  struct dirent *e;
  char path[512];
  while ((e = readdir(d)) != NULL) {
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
      snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
      unlink(path);
    }
  }
  closedir(d);
  rmdir(dir);
}

TestSuite(image_io, .init = make_dir, .fini = remove_dir);

/* Values that exercise every bit pattern class a float image can hold:
 * signs, tiny and huge magnitudes, denormals, and values with full mantissas. */
static ss_image *pattern_image(int w, int h, int channels) {
  ss_image *img = ss_image_create(w, h, channels);
  cr_assert_not_null(img);
  uint32_t state = 12345u;
  size_t n = (size_t)w * (size_t)h * (size_t)channels;
  for (size_t i = 0; i < n; ++i) {
    state = state * 1664525u + 1013904223u;
    float v = (float)state / 4294967296.0f;
    switch (i % 5) {
    case 0:
      img->data[i] = v;
      break;
    case 1:
      img->data[i] = -v * 1e-30f;
      break;
    case 2:
      img->data[i] = v * 3e30f;
      break;
    case 3:
      img->data[i] = 1e-40f * v;
      break; /* denormal */
    default:
      img->data[i] = (float)i;
      break;
    }
  }
  return img;
}

static void assert_images_identical(const ss_image *a, const ss_image *b) {
  cr_assert_eq(a->width, b->width);
  cr_assert_eq(a->height, b->height);
  cr_assert_eq(a->channels, b->channels);
  size_t n = (size_t)a->width * (size_t)a->height * (size_t)a->channels;
  cr_assert_eq(memcmp(a->data, b->data, n * sizeof(float)), 0, "pixel data differs");
}

static void round_trip(const char *name, int w, int h, int channels) {
  char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  ss_image *img = pattern_image(w, h, channels);
  ss_error err = {0};
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_OK, "%s", err.message);
  ss_image *back = NULL;
  cr_assert_eq(ss_image_read(path, &back, &err), SS_OK, "%s", err.message);
  assert_images_identical(img, back);
  ss_image_destroy(img);
  ss_image_destroy(back);
  cr_assert_eq(io_test_count_entries(dir), 1, "no temporary file is left beside the output");
}

/* 37 rows: two full 16-line ZIP chunks and a partial one; odd width. */
Test(image_io, exr_round_trip_is_exact_for_one_channel) { round_trip("y.exr", 23, 37, 1); }
Test(image_io, exr_round_trip_is_exact_for_three_channels) { round_trip("rgb.exr", 23, 37, 3); }
Test(image_io, exr_round_trip_is_exact_for_four_channels) { round_trip("rgba.exr", 5, 17, 4); }
Test(image_io, exr_round_trip_is_exact_for_a_single_pixel) { round_trip("p.exr", 1, 1, 3); }
Test(image_io, pfm_round_trip_is_exact_for_one_channel) { round_trip("y.pfm", 23, 37, 1); }
Test(image_io, pfm_round_trip_is_exact_for_three_channels) { round_trip("rgb.pfm", 23, 37, 3); }

Test(image_io, extension_is_case_insensitive) { round_trip("upper.EXR", 4, 3, 3); }

Test(image_io, pfm_rows_run_bottom_to_top_and_scale_gives_byte_order) {
  char path[256];
  snprintf(path, sizeof path, "%s/order.pfm", dir);
  ss_image *img = ss_image_create(2, 2, 1);
  img->data[0] = 1.0f; /* top row */
  img->data[1] = 2.0f;
  img->data[2] = 3.0f; /* bottom row */
  img->data[3] = 4.0f;
  ss_error err = {0};
  cr_assert_eq(ss_image_write_pfm(path, img, &err), SS_OK, "%s", err.message);
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f);
  char header[32] = {0};
  cr_assert_eq(fread(header, 1, 13, f), 13u);
  cr_assert_str_eq(header, "Pf\n2 2\n-1.0\n\x00", "little-endian header expected");
  float first;
  fseek(f, 12, SEEK_SET);
  cr_assert_eq(fread(&first, sizeof first, 1, f), 1u);
  cr_assert_eq(first, 3.0f, "the first stored row is the bottom one");
  fclose(f);
  ss_image_destroy(img);
}

Test(image_io, pfm_reader_swaps_big_endian_data) {
  char path[256];
  snprintf(path, sizeof path, "%s/big.pfm", dir);
  FILE *f = fopen(path, "wb");
  cr_assert_not_null(f);
  fputs("Pf\n1 1\n1.0\n", f);
  const unsigned char one_big_endian[4] = {0x3f, 0x80, 0x00, 0x00};
  fwrite(one_big_endian, 1, 4, f);
  fclose(f);
  ss_image *img = NULL;
  ss_error err = {0};
  cr_assert_eq(ss_image_read(path, &img, &err), SS_OK, "%s", err.message);
  cr_assert_eq(img->data[0], 1.0f);
  ss_image_destroy(img);
}

static uint32_t be32(const unsigned char *p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

Test(image_io, png_has_the_right_size_header) {
  char path[256];
  snprintf(path, sizeof path, "%s/out.png", dir);
  ss_image *img = pattern_image(31, 17, 3);
  ss_error err = {0};
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_OK, "%s", err.message);
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f);
  unsigned char head[26];
  cr_assert_eq(fread(head, 1, sizeof head, f), sizeof head);
  fclose(f);
  cr_assert_eq(memcmp(head, "\x89PNG\r\n\x1a\n", 8), 0, "PNG signature");
  cr_assert_eq(memcmp(head + 12, "IHDR", 4), 0);
  cr_assert_eq(be32(head + 16), 31u, "width");
  cr_assert_eq(be32(head + 20), 17u, "height");
  cr_assert_eq(head[24], 8, "8 bits per sample");
  cr_assert_eq(head[25], 2, "colour type 2 (RGB)");
  ss_image_destroy(img);
}

/* Decoded with stb_image: sRGB(0.25) = 0.537 -> 137, sRGB(0.025) -> 44;
 * exposure 1 doubles the light; alpha stays linear and unexposed. */
Test(image_io, png_pixels_are_exposed_clamped_and_srgb_encoded) {
  char path[256];
  snprintf(path, sizeof path, "%s/tone.png", dir);
  ss_image *img = ss_image_create(3, 1, 4);
  const float in[12] = {0.125f, 0.0125f, 2.0f, 0.5f, NAN,  -1.0f,
                        0.0f,   1.0f,    0.0f, 0.0f, 0.0f, 7.0f};
  memcpy(img->data, in, sizeof in);
  ss_error err = {0};
  cr_assert_eq(ss_image_write_png(path, img, 1.0, &err), SS_OK, "%s", err.message);
  int w, h, n;
  unsigned char *px = stbi_load(path, &w, &h, &n, 0);
  cr_assert_not_null(px);
  cr_assert(w == 3 && h == 1 && n == 4);
  const unsigned char expect[12] = {137, 44, 255, 128, 0, 0, 0, 255, 0, 0, 0, 255};
  for (int i = 0; i < 12; ++i) {
    cr_assert_eq(px[i], expect[i], "byte %d: %d, expected %d", i, px[i], expect[i]);
  }
  stbi_image_free(px);
  ss_image_destroy(img);
}

Test(image_io, png_grey_and_rgba_colour_types) {
  char path[256];
  const int channels[2] = {1, 4}, colour_type[2] = {0, 6};
  for (int k = 0; k < 2; ++k) {
    snprintf(path, sizeof path, "%s/c%d.png", dir, channels[k]);
    ss_image *img = ss_image_create(3, 2, channels[k]);
    ss_error err = {0};
    cr_assert_eq(ss_image_write_png(path, img, 0.0, &err), SS_OK, "%s", err.message);
    FILE *f = fopen(path, "rb");
    unsigned char head[26];
    cr_assert_eq(fread(head, 1, sizeof head, f), sizeof head);
    fclose(f);
    cr_assert_eq(head[25], colour_type[k], "%d channels", channels[k]);
    ss_image_destroy(img);
  }
}

Test(image_io, png_tonemapper_survives_nan_and_inf) {
  char path[256];
  snprintf(path, sizeof path, "%s/bad.png", dir);
  ss_image *img = ss_image_create(4, 1, 1);
  img->data[0] = NAN;
  img->data[1] = INFINITY;
  img->data[2] = -INFINITY;
  img->data[3] = 0.5f;
  ss_error err = {0};
  cr_assert_eq(ss_image_write_png(path, img, 0.0, &err), SS_OK, "%s", err.message);
  struct stat sb;
  cr_assert_eq(stat(path, &sb), 0);
  cr_assert_gt(sb.st_size, 26);
  cr_assert_eq(ss_image_write_png(path, img, NAN, &err), SS_ERR_INVALID_ARGUMENT,
               "a NaN exposure is rejected");
  ss_image_destroy(img);
}

static void assert_failed_write_leaves_nothing(const char *path) {
  ss_image *img = pattern_image(4, 4, 3);
  ss_error err = {0};
  ss_status st = ss_image_write(path, img, 0.0, &err);
  cr_assert_eq(st, SS_ERR_IO, "%s: got %s (%s)", path, ss_status_name(st), err.message);
  cr_assert_not_null(strstr(err.message, path), "message '%s' names the path", err.message);
  cr_assert_not_null(strstr(err.message, "No such file or directory"),
                     "message '%s' gives the reason", err.message);
  cr_assert_neq(access(path, F_OK), 0, "no file at %s", path);
  ss_image_destroy(img);
}

Test(image_io, unwritable_path_fails_with_io_error_naming_it) {
  assert_failed_write_leaves_nothing("/nonexistent/x.exr");
  assert_failed_write_leaves_nothing("/nonexistent/x.png");
  assert_failed_write_leaves_nothing("/nonexistent/x.pfm");
}

Test(image_io, a_directory_as_the_target_leaves_nothing_behind) {
  /* The target is a non-empty directory: refused before anything is
   * written, and the directory is left with only what it had. */
  char target[256], inside[300];
  snprintf(target, sizeof target, "%s/busy.exr", dir);
  cr_assert_eq(mkdir(target, 0755), 0);
  snprintf(inside, sizeof inside, "%s/keep", target);
  FILE *f = fopen(inside, "w");
  cr_assert_not_null(f);
  fclose(f);
  ss_image *img = pattern_image(4, 4, 3);
  ss_error err = {0};
  cr_assert_eq(ss_image_write(target, img, 0.0, &err), SS_ERR_IO);
  cr_assert_not_null(strstr(err.message, target), "message '%s' names the path", err.message);
  cr_assert_eq(io_test_count_entries(dir), 1, "only the directory itself remains");
  unlink(inside);
  rmdir(target);
  ss_image_destroy(img);
}

Test(image_io, unsupported_extension_is_rejected) {
  char path[256];
  snprintf(path, sizeof path, "%s/out.jpg", dir);
  ss_image *img = pattern_image(2, 2, 3);
  ss_error err = {0};
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_not_null(strstr(err.message, path), "message '%s' names the path", err.message);
  cr_assert_neq(access(path, F_OK), 0);
  cr_assert_eq(ss_image_format_supported("a.exr"), 1);
  cr_assert_eq(ss_image_format_supported("a.PNG"), 1);
  cr_assert_eq(ss_image_format_supported("a.pfm"), 1);
  cr_assert_eq(ss_image_format_supported("a.jpg"), 0);
  cr_assert_eq(ss_image_format_supported("exr"), 0);
  cr_assert_eq(ss_image_format_supported("dir.exr/file"), 0);
  ss_image_destroy(img);
}

Test(image_io, bad_channel_counts_are_rejected) {
  char path[256];
  snprintf(path, sizeof path, "%s/two.exr", dir);
  ss_image *img = ss_image_create(2, 2, 2);
  ss_error err = {0};
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_neq(access(path, F_OK), 0);
  ss_image_destroy(img);
  img = ss_image_create(2, 2, 4);
  snprintf(path, sizeof path, "%s/rgba.pfm", dir);
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_ERR_UNSUPPORTED, "PFM has no alpha");
  cr_assert_neq(access(path, F_OK), 0);
  ss_image_destroy(img);
}

Test(image_io, reading_garbage_or_missing_files_fails_cleanly) {
  char path[256];
  snprintf(path, sizeof path, "%s/garbage.exr", dir);
  FILE *f = fopen(path, "wb");
  fputs("this is not an image", f);
  fclose(f);
  ss_image *img = (ss_image *)1;
  ss_error err = {0};
  cr_assert_eq(ss_image_read(path, &img, &err), SS_ERR_PARSE);
  cr_assert_null(img);
  cr_assert_not_null(strstr(err.message, path));
  snprintf(path, sizeof path, "%s/missing.exr", dir);
  cr_assert_eq(ss_image_read(path, &img, &err), SS_ERR_IO);
  cr_assert_not_null(strstr(err.message, path));
  /* A truncated EXR: the header survives, the pixel data does not. */
  char full[256];
  snprintf(full, sizeof full, "%s/full.exr", dir);
  ss_image *good = pattern_image(16, 40, 3);
  cr_assert_eq(ss_image_write_exr(full, good, &err), SS_OK, "%s", err.message);
  ss_image_destroy(good);
  cr_assert_eq(truncate(full, 400), 0);
  ss_status st = ss_image_read(full, &img, &err);
  cr_assert_neq(st, SS_OK, "a truncated EXR must not read as complete");
  cr_assert_null(img);
  cr_assert_not_null(strstr(err.message, full), "message '%s'", err.message);
}

/* A PNG written by ss_image_write reads back as the linear values it holds:
 * within half an 8-bit sRGB code (at most 0.0045 in linear terms, near 1),
 * whatever the file is named. */
Test(image_io, png_reads_back_as_linear_values_within_half_a_code) {
  char path[256], renamed[256];
  snprintf(path, sizeof path, "%s/ramp.png", dir);
  snprintf(renamed, sizeof renamed, "%s/ramp.img", dir);
  ss_image *img = ss_image_create(16, 3, 3);
  cr_assert_not_null(img);
  for (int i = 0; i < 16 * 3 * 3; ++i) {
    img->data[i] = (float)(i % 17) / 16.0f;
  }
  ss_error err = {0};
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_OK, "%s", err.message);
  cr_assert_eq(rename(path, renamed), 0);
  ss_image *back = NULL;
  cr_assert_eq(ss_image_read(renamed, &back, &err), SS_OK, "%s", err.message);
  cr_assert_eq(back->width, 16);
  cr_assert_eq(back->height, 3);
  cr_assert_eq(back->channels, 3);
  for (int i = 0; i < 16 * 3 * 3; ++i) {
    cr_expect(fabsf(back->data[i] - img->data[i]) <= 0.005f, "%d: %g read as %g", i, img->data[i],
              back->data[i]);
  }
  ss_image_destroy(back);
  ss_image_destroy(img);
}
