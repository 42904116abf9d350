/* The film: per-pixel RGB accumulation in double precision.
 *
 * Camera samples are importance-sampled from the reconstruction filter
 * (camera.h), so each sample belongs to exactly one pixel with weight 1 and
 * the pixel value is the mean of its samples. Each pixel keeps Welford's
 * running mean and second moment per channel (for the optional variance
 * image: the variance of the pixel mean). Samples with a NaN or infinite
 * component are counted and dropped, never accumulated.
 *
 * A pixel may be written by one thread at a time (the renderer gives every
 * pixel to one tile); samples arrive in a fixed order per pixel, so the
 * result does not depend on scheduling. */
#ifndef SUBSURF_FILM_H
#define SUBSURF_FILM_H

#include "subsurf/image.h"
#include "subsurf/rgb.h"
#include "subsurf/status.h"

#include <stdint.h>

typedef struct ss_film ss_film;

/* One pixel's whole accumulation state (checkpoint.h saves and restores it
 * bit for bit). */
typedef struct {
  uint32_t n;        /* accepted samples */
  uint32_t rejected; /* NaN/Inf samples */
  double mean[3];
  double m2[3];
} ss_film_pixel_state;

/* Bytes a width x height film allocates (callers check that it fits before
 * rendering), and bytes of one 3-channel float image of that size. */
double ss_film_bytes(int width, int height);
double ss_film_image_bytes(int width, int height);

ss_status ss_film_create(int width, int height, ss_film **out, ss_error *err);
void ss_film_destroy(ss_film *film);
int ss_film_width(const ss_film *film);
int ss_film_height(const ss_film *film);

/* Adds one sample to pixel (x, y); returns 0 (and counts it) when the
 * sample is not finite. */
int ss_film_add_sample(ss_film *film, int x, int y, ss_rgb value);

/* Samples accumulated and samples rejected as NaN/Inf, over all pixels. */
uint64_t ss_film_sample_count(const ss_film *film);
uint64_t ss_film_nonfinite_count(const ss_film *film);
/* Smallest number of accepted samples of any pixel. */
uint32_t ss_film_min_samples(const ss_film *film);
uint32_t ss_film_pixel_samples(const ss_film *film, int x, int y);
/* Samples drawn for pixel (x, y), accepted or rejected: the index of its
 * next sample. */
uint32_t ss_film_pixel_drawn(const ss_film *film, int x, int y);
/* Smallest ss_film_pixel_drawn of any pixel (the first unfinished pass). */
uint32_t ss_film_min_drawn(const ss_film *film);
/* Raw state of pixel (x, y), read and written as is. */
void ss_film_get_pixel_state(const ss_film *film, int x, int y, ss_film_pixel_state *out);
void ss_film_set_pixel_state(ss_film *film, int x, int y, const ss_film_pixel_state *in);
/* Mean of pixel (x, y) (black when it has no sample). */
ss_rgb ss_film_pixel_mean(const ss_film *film, int x, int y);

/* A new 3-channel image of the pixel means; NULL when out of memory. */
ss_image *ss_film_image(const ss_film *film);
/* A new 3-channel image of the variance of each pixel mean, s^2 / n
 * (0 where a pixel has fewer than 2 samples); NULL when out of memory. */
ss_image *ss_film_variance_image(const ss_film *film);
/* Both images store floats: a mean or variance beyond the float range is
 * written as +-FLT_MAX, never as Inf. The number of such pixel values (over
 * both images, all channels), for the caller to report. */
uint64_t ss_film_clamped_count(const ss_film *film);

#endif
