/* Error metrics of an image against a reference of the same size, over the
 * pixels of a mask (a one-channel image: a pixel counts when its value is
 * > 0.5; NULL: every pixel). Channels 0..2 are R, G, B.
 *
 * relMSE is pbrt-v4 imgtool's: mean over pixels of (v - ref)^2 / (ref +
 * 0.01)^2, per channel and over all three channels. */
#ifndef SUBSURF_IMAGE_METRICS_H
#define SUBSURF_IMAGE_METRICS_H

#include "subsurf/image.h"
#include "subsurf/status.h"

#include <stddef.h>

/* The offset in relMSE's denominator (pbrt-v4 imgtool). */
#define SS_REL_MSE_EPSILON 0.01

typedef struct {
  size_t pixels;  /* pixels of the mask */
  double rel_mse; /* over all three channels */
  double rel_mse_c[3];
  double rmse[3];     /* sqrt(mean (v - ref)^2) */
  double mean[3];     /* mean of the image */
  double ref_mean[3]; /* mean of the reference */
} ss_image_error;

/* Fills *out. SS_ERR_INVALID_ARGUMENT when the sizes differ, an image has
 * fewer than 3 channels, the mask is not one channel of the same size or
 * holds no pixel; the message gives both sizes. */
ss_status ss_image_error_compute(const ss_image *img, const ss_image *ref, const ss_image *mask,
                                 ss_image_error *out, ss_error *err);

/* The relative standard error of a Monte Carlo image over the mask, from
 * `variance`, the variance of each pixel mean (film.h):
 *     sqrt(mean over pixels and channels of variance / (img + 0.01)^2),
 * the square root of the relMSE the image's own noise is expected to have
 * against the noise-free image. SS_ERR_INVALID_ARGUMENT as above. */
ss_status ss_image_rel_std_error(const ss_image *img, const ss_image *variance,
                                 const ss_image *mask, double *out, ss_error *err);

/* mean / ref_mean of channel c (NaN when the reference's mean is 0). */
double ss_image_error_mean_ratio(const ss_image_error *e, int c);

#endif
