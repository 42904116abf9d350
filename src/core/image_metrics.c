/* Image error metrics (image_metrics.h). */
#include "subsurf/image_metrics.h"

#include <math.h>
#include <string.h>

static ss_status check_sizes(const ss_image *img, const ss_image *ref, const ss_image *mask,
                             ss_error *err) {
  if (img->width != ref->width || img->height != ref->height) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "the image is %d x %d but the reference is %d x %d", img->width,
                        img->height, ref->width, ref->height);
  }
  if (img->channels < 3 || ref->channels < 3) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "images need 3 channels (RGB), got %d and %d",
                        img->channels, ref->channels);
  }
  if (mask && (mask->width != img->width || mask->height != img->height || mask->channels != 1)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "the mask is %d x %d x %d, expected %d x %d x 1", mask->width, mask->height,
                        mask->channels, img->width, img->height);
  }
  return SS_OK;
}

ss_status ss_image_error_compute(const ss_image *img, const ss_image *ref, const ss_image *mask,
                                 ss_image_error *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  ss_status st = check_sizes(img, ref, mask, err);
  if (st != SS_OK) {
    return st;
  }
  double rel[3] = {0}, sq[3] = {0}, sum[3] = {0}, ref_sum[3] = {0};
  size_t n = 0, count = (size_t)img->width * (size_t)img->height;
  for (size_t i = 0; i < count; ++i) {
    if (mask && !(mask->data[i] > 0.5f)) {
      continue;
    }
    const float *v = img->data + i * (size_t)img->channels;
    const float *r = ref->data + i * (size_t)ref->channels;
    for (int c = 0; c < 3; ++c) {
      double d = (double)v[c] - (double)r[c], den = (double)r[c] + SS_REL_MSE_EPSILON;
      /* pbrt-v4 imgtool's relative MSE: (v - ref)^2 / (ref + 0.01)^2. */
      rel[c] += d * d / (den * den);
      sq[c] += d * d;
      sum[c] += v[c];
      ref_sum[c] += r[c];
    }
    ++n;
  }
  if (n == 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "the mask holds no pixel");
  }
  out->pixels = n;
  for (int c = 0; c < 3; ++c) {
    out->rel_mse_c[c] = rel[c] / (double)n;
    out->rmse[c] = sqrt(sq[c] / (double)n);
    out->mean[c] = sum[c] / (double)n;
    out->ref_mean[c] = ref_sum[c] / (double)n;
    out->rel_mse += out->rel_mse_c[c] / 3.0;
  }
  return SS_OK;
}

double ss_image_error_mean_ratio(const ss_image_error *e, int c) {
  return e->ref_mean[c] != 0.0 ? e->mean[c] / e->ref_mean[c] : NAN;
}

ss_status ss_image_rel_std_error(const ss_image *img, const ss_image *variance,
                                 const ss_image *mask, double *out, ss_error *err) {
  ss_status st = check_sizes(img, variance, mask, err);
  if (st != SS_OK) {
    return st;
  }
  double sum = 0.0;
  size_t n = 0, count = (size_t)img->width * (size_t)img->height;
  for (size_t i = 0; i < count; ++i) {
    if (mask && !(mask->data[i] > 0.5f)) {
      continue;
    }
    const float *v = img->data + i * (size_t)img->channels;
    const float *s2 = variance->data + i * (size_t)variance->channels;
    for (int c = 0; c < 3; ++c) {
      /* E[(v - mu)^2] / (v + 0.01)^2: relMSE's terms with the pixel's
       * variance for its squared error. */
      double den = (double)v[c] + SS_REL_MSE_EPSILON;
      sum += (double)s2[c] / (den * den);
    }
    ++n;
  }
  if (n == 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "the mask holds no pixel");
  }
  *out = sqrt(sum / (3.0 * (double)n));
  return SS_OK;
}
