/* RGB triples in double precision for radiance, throughput and medium
 * coefficients. The renderer works in three colour channels; every per-channel
 * quantity is an ss_rgb so that loops over channels stay explicit. */
#ifndef SUBSURF_RGB_H
#define SUBSURF_RGB_H

#include <math.h>

typedef struct {
  double c[3];
} ss_rgb;

static inline ss_rgb ss_rgb_make(double r, double g, double b) {
  ss_rgb v = {{r, g, b}};
  return v;
}
static inline ss_rgb ss_rgb_gray(double v) { return ss_rgb_make(v, v, v); }
static inline ss_rgb ss_rgb_add(ss_rgb a, ss_rgb b) {
  return ss_rgb_make(a.c[0] + b.c[0], a.c[1] + b.c[1], a.c[2] + b.c[2]);
}
static inline ss_rgb ss_rgb_sub(ss_rgb a, ss_rgb b) {
  return ss_rgb_make(a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]);
}
static inline ss_rgb ss_rgb_mul(ss_rgb a, ss_rgb b) {
  return ss_rgb_make(a.c[0] * b.c[0], a.c[1] * b.c[1], a.c[2] * b.c[2]);
}
static inline ss_rgb ss_rgb_scale(ss_rgb a, double k) {
  return ss_rgb_make(a.c[0] * k, a.c[1] * k, a.c[2] * k);
}
/* a + b * k */
static inline ss_rgb ss_rgb_madd(ss_rgb a, ss_rgb b, double k) {
  return ss_rgb_make(a.c[0] + b.c[0] * k, a.c[1] + b.c[1] * k, a.c[2] + b.c[2] * k);
}
static inline double ss_rgb_average(ss_rgb a) { return (a.c[0] + a.c[1] + a.c[2]) / 3.0; }
static inline double ss_rgb_max(ss_rgb a) {
  double m = a.c[0] > a.c[1] ? a.c[0] : a.c[1];
  return m > a.c[2] ? m : a.c[2];
}
static inline double ss_rgb_min(ss_rgb a) {
  double m = a.c[0] < a.c[1] ? a.c[0] : a.c[1];
  return m < a.c[2] ? m : a.c[2];
}
static inline int ss_rgb_is_black(ss_rgb a) {
  return a.c[0] == 0.0 && a.c[1] == 0.0 && a.c[2] == 0.0;
}
static inline int ss_rgb_is_finite(ss_rgb a) {
  return isfinite(a.c[0]) && isfinite(a.c[1]) && isfinite(a.c[2]);
}
/* Rec. 709 luminance, for Russian roulette and statistics. */
static inline double ss_rgb_luminance(ss_rgb a) {
  return 0.2126 * a.c[0] + 0.7152 * a.c[1] + 0.0722 * a.c[2];
}

#endif
