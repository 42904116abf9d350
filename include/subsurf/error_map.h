/* A false-colour map of the per-pixel relative error |v - ref| / (ref +
 * 0.01), averaged over R, G, B: 0 is dark blue, then cyan, green, yellow,
 * and SS_ERROR_MAP_MAX or more is red. Pixels outside the mask (one channel,
 * > 0.5 counts; NULL: all) are mid grey. */
#ifndef SUBSURF_ERROR_MAP_H
#define SUBSURF_ERROR_MAP_H

#include "subsurf/image.h"
#include "subsurf/rgb.h"

#define SS_ERROR_MAP_MAX 1.0
/* The grey (linear) of pixels outside the mask. */
#define SS_ERROR_MAP_OUTSIDE 0.2

/* The colour of relative error e (clamped to [0, SS_ERROR_MAP_MAX]). */
ss_rgb ss_error_map_colour(double e);

/* A new RGB image, or NULL when out of memory or the sizes differ (the
 * caller checks sizes with ss_image_error_compute first). */
ss_image *ss_error_map(const ss_image *img, const ss_image *ref, const ss_image *mask);

#endif
