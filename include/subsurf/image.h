/* Float image buffers (interleaved channels, row-major, row 0 at the top). */
#ifndef SUBSURF_IMAGE_H
#define SUBSURF_IMAGE_H

#include <stddef.h>

typedef struct {
  int width, height, channels;
  float *data; /* width * height * channels values */
} ss_image;

/* Allocates a zeroed image; returns NULL when out of memory or on a size <= 0. */
ss_image *ss_image_create(int width, int height, int channels);
void ss_image_destroy(ss_image *img);

static inline float *ss_image_pixel(ss_image *img, int x, int y) {
  return img->data + ((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels;
}

#endif
