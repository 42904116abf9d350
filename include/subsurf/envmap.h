/* Environment maps: a latitude-longitude (equirectangular) image of the
 * radiance arriving from every direction, importance-sampled by a
 * piecewise-constant 2D distribution over its pixels.
 *
 * The image is W = 2 H pixels; each pixel is a constant radiance over its
 * patch of the sphere (a nearest-pixel lookup, so that the sampling density
 * is exactly proportional to the mean of the channels). Row 0 (the top) is
 * around `up`; the map's centre column faces `front` turned by `rotation`
 * degrees about `up` (right-handed); from the centre, u increases toward
 * front x up, the right of a viewer looking at the centre with `up` up: the
 * map is seen from inside the sphere the way the image looks. */
#ifndef SUBSURF_ENVMAP_H
#define SUBSURF_ENVMAP_H

#include "subsurf/image.h"
#include "subsurf/rgb.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <stdint.h>

typedef struct ss_envmap ss_envmap;

/* The map's orientation: unit up, and the unit direction of the map's
 * centre (front turned by the rotation, perpendicular to up). */
typedef struct {
  ss_vec3 up, front;
} ss_envmap_frame;

/* Builds the frame; `up` must be non-zero and `front` not parallel to it.
 * The message names the key at fault ("up", "front" or "rotation") in
 * *bad_key when bad_key is not NULL. */
ss_status ss_envmap_frame_make(ss_vec3 up, ss_vec3 front, double rotation_deg, ss_envmap_frame *f,
                               const char **bad_key, ss_error *err);

/* Takes ownership of `image` (1 or 3 channels, width twice its height,
 * finite values >= 0, not all zero), destroyed also on failure. */
ss_status ss_envmap_create(ss_image *image, const ss_envmap_frame *frame, ss_envmap **out,
                           ss_error *err);
void ss_envmap_destroy(ss_envmap *map);

/* Radiance arriving from unit direction w, and in *pdf (when not NULL) the
 * solid-angle density with which ss_envmap_sample picks w. */
ss_rgb ss_envmap_eval(const ss_envmap *map, ss_vec3 w, double *pdf);
/* A direction w toward the environment with solid-angle density *pdf
 * (proportional to the mean of the channels over the sphere) and the
 * radiance from it; 0 when the sample falls on a pole, where the density is
 * undefined. */
int ss_envmap_sample(const ss_envmap *map, double u1, double u2, ss_vec3 *w, double *pdf,
                     ss_rgb *radiance);

/* Unit direction of the centre of pixel (x, y) and the solid angle the
 * pixel covers (for tests comparing a pixel with a distant light). */
ss_vec3 ss_envmap_pixel_direction(const ss_envmap *map, int x, int y, double *solid_angle);

/* Mixes the map's pixels and frame into the FNV-1a hash *h (cache keys of
 * results that depend on the lighting). */
void ss_envmap_hash(const ss_envmap *map, uint64_t *h);

#endif
