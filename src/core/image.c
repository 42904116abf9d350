#include "subsurf/image.h"

#include <stdint.h>
#include <stdlib.h>

ss_image *ss_image_create(int width, int height, int channels) {
  if (width <= 0 || height <= 0 || channels <= 0) {
    return NULL;
  }
  size_t count = (size_t)width * (size_t)height;
  if (count > SIZE_MAX / (size_t)channels / sizeof(float)) {
    return NULL;
  }
  count *= (size_t)channels;
  ss_image *img = malloc(sizeof *img);
  if (!img) {
    return NULL;
  }
  img->data = calloc(count, sizeof *img->data);
  if (!img->data) {
    free(img);
    return NULL;
  }
  img->width = width;
  img->height = height;
  img->channels = channels;
  return img;
}

void ss_image_destroy(ss_image *img) {
  if (img) {
    free(img->data);
    free(img);
  }
}
