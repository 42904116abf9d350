/* EXR files of noisy float data read back bit-exactly. Noisy renders compress
 * badly: a ZIP chunk's deflated size lands near its raw size, and OpenEXR
 * 3.1.5 stored a chunk whose deflated size equals the raw size as if it were
 * raw (github.com/AcademySoftwareFoundation/openexr/issues/2306), so the
 * reader decoded zlib bytes as pixels (a
 * 16-row band of garbage). Images here sweep the noise from none to every
 * mantissa bit, row by row, over many sizes, so that many chunks fall on or
 * around that boundary. */
#include "subsurf/image_io.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[64];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "/tmp/subsurf-exr-noisy-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void) { rmdir(dir); }

TestSuite(exr_noisy, .init = make_dir, .fini = remove_dir);

/* A smooth positive value whose low `bits` mantissa bits are random, like a
 * Monte Carlo estimate whose noise reaches that far down. */
static float noisy_value(ss_rng *rng, double smooth, int bits) {
  float v = (float)smooth;
  uint32_t u;
  memcpy(&u, &v, sizeof u);
  uint32_t mask = bits >= 32 ? 0xffffffffu : (1u << bits) - 1u;
  u = (u & ~mask) | (ss_rng_next_u32(rng) & mask);
  memcpy(&v, &u, sizeof v);
  return v;
}

static ss_image *noisy_image(ss_rng *rng, int w, int h, int channels, int bits) {
  ss_image *img = ss_image_create(w, h, channels);
  cr_assert_not_null(img);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w * channels; ++x) {
      double smooth = 0.25 + 0.001 * x + 0.01 * y;
      img->data[(size_t)y * (size_t)(w * channels) + (size_t)x] = noisy_value(rng, smooth, bits);
    }
  }
  return img;
}

static int write_and_compare(const char *path, const ss_image *img) {
  ss_error err = {0};
  cr_assert_eq(ss_image_write_exr(path, img, &err), SS_OK, "%s", err.message);
  ss_image *back = NULL;
  cr_assert_eq(ss_image_read(path, &back, &err), SS_OK, "%s", err.message);
  cr_assert(back->width == img->width && back->height == img->height &&
            back->channels == img->channels);
  size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
  int same = memcmp(img->data, back->data, n * sizeof(float)) == 0;
  ss_image_destroy(back);
  unlink(path);
  return same;
}

Test(exr_noisy, noisy_images_of_many_sizes_read_back_bit_exactly) {
  ss_rng rng;
  ss_rng_seed(&rng, 2306, 0);
  char path[128];
  snprintf(path, sizeof path, "%s/noisy.exr", dir);
  const int channels[3] = {1, 3, 4};
  int bad = 0, total = 0;
  for (int i = 0; i < 1500; ++i) {
    int w = 1 + (int)(ss_rng_next_u32(&rng) % 90u);
    int h = 1 + (int)(ss_rng_next_u32(&rng) % 50u);
    /* 13 or 14 noisy bits put a deflated chunk within bytes of its raw size
     * (zlib stores incompressible data with 11 bytes of overhead); the rest
     * range from smooth to pure noise. */
    uint32_t u = ss_rng_next_u32(&rng);
    int bits = u % 3u ? 13 + (int)(u % 2u) : (int)(u % 33u);
    ss_image *img = noisy_image(&rng, w, h, channels[i % 3], bits);
    bad += !write_and_compare(path, img);
    ++total;
    ss_image_destroy(img);
  }
  cr_assert_eq(bad, 0, "%d of %d images differ after the round trip", bad, total);
}
