/* False-colour relative-error maps (error_map.h). */
#include "subsurf/error_map.h"

#include "subsurf/image_metrics.h"
#include "subsurf/table_index.h"

#include <math.h>

ss_rgb ss_error_map_colour(double e) {
  static const double stops[5][3] = {
      {0.0, 0.0, 0.5}, {0.0, 0.8, 1.0}, {0.0, 0.8, 0.0}, {1.0, 1.0, 0.0}, {1.0, 0.0, 0.0}};
  double x = 4.0 * fmin(fmax(e / SS_ERROR_MAP_MAX, 0.0), 1.0);
  int i = ss_table_cell_clamped(x, 4);
  double f = x - i;
  ss_rgb c;
  for (int k = 0; k < 3; ++k) {
    c.c[k] = (1.0 - f) * stops[i][k] + f * stops[i + 1][k];
  }
  return c;
}

ss_image *ss_error_map(const ss_image *img, const ss_image *ref, const ss_image *mask) {
  if (img->width != ref->width || img->height != ref->height || img->channels < 3 ||
      ref->channels < 3) {
    return NULL;
  }
  ss_image *map = ss_image_create(img->width, img->height, 3);
  size_t n = map ? (size_t)img->width * (size_t)img->height : 0;
  for (size_t i = 0; i < n; ++i) {
    const float *v = img->data + i * (size_t)img->channels;
    const float *r = ref->data + i * (size_t)ref->channels;
    double e = 0.0;
    for (int c = 0; c < 3; ++c) {
      e += fabs((double)v[c] - r[c]) / ((double)r[c] + SS_REL_MSE_EPSILON) / 3.0;
    }
    ss_rgb colour = mask && !(mask->data[i] > 0.5f) ? ss_rgb_gray(SS_ERROR_MAP_OUTSIDE)
                                                    : ss_error_map_colour(e);
    for (int c = 0; c < 3; ++c) {
      map->data[3 * i + (size_t)c] = (float)colour.c[c];
    }
  }
  return map;
}
