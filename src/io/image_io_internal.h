/* Shared checks of the image writers and readers (not public API). */
#ifndef SUBSURF_IO_IMAGE_IO_INTERNAL_H
#define SUBSURF_IO_IMAGE_IO_INTERNAL_H

#include "subsurf/image.h"
#include "subsurf/status.h"

/* SS_ERR_INVALID_ARGUMENT naming `path` unless `img` has a positive size,
 * data, and 1, 3 or 4 channels. */
ss_status ss_image_io_check(const char *path, const ss_image *img, ss_error *err);

ss_status ss_image_read_exr(const char *path, ss_image **out, ss_error *err);
ss_status ss_image_read_pfm(const char *path, ss_image **out, ss_error *err);
/* A PNG of 8 or 16 bits per channel (grey, or RGB; alpha dropped) as linear
 * values in [0, 1], its codes sRGB-decoded when `srgb` (texture_image.c). */
ss_status ss_image_read_png(const char *path, int srgb, ss_image **out, ss_error *err);

#endif
