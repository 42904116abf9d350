/* The perspective camera and its pixel reconstruction filter.
 *
 * Camera space: +x to the image's right, +y to the image's up (the projection
 * of `up` onto the image plane), looking along +z toward `target`; pixel
 * (0, 0) is the top-left corner of the image, so a camera at (0, 0, 5) looking
 * at the origin with up +y sees +x on the right and +y at the top.
 *
 * The reconstruction filter is applied by importance sampling (filter
 * importance sampling, Ernst et al. 2006): each camera sample is drawn with a
 * density proportional to the filter around its pixel's centre and carries
 * weight 1, so the film averages samples per pixel and no sample ever touches
 * a neighbouring pixel (tiles then need no synchronisation). */
#ifndef SUBSURF_CAMERA_H
#define SUBSURF_CAMERA_H

#include "subsurf/accel.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

typedef enum {
  SS_FILTER_BOX,      /* uniform over [-radius, radius]^2 */
  SS_FILTER_GAUSSIAN, /* exp(-r^2 / (2 sigma^2)) truncated to the disk r < radius */
} ss_filter_type;

typedef struct {
  ss_filter_type type;
  double radius; /* pixels; box default 0.5, Gaussian default 1.5 */
  double sigma;  /* Gaussian standard deviation in pixels, default 0.5 */
} ss_filter;

/* Defaults for a type (see above). */
ss_filter ss_filter_default(ss_filter_type type);
/* Offset (dx, dy) from the pixel centre, in pixels, with density
 * proportional to the filter. */
void ss_filter_sample(const ss_filter *f, double u1, double u2, double *dx, double *dy);
/* Parses "box" / "gaussian"; returns 0 on an unknown name. */
int ss_filter_type_from_name(const char *name, ss_filter_type *type);
const char *ss_filter_type_name(ss_filter_type type);

typedef struct {
  /* Set by the caller. */
  ss_vec3 position, target, up;
  double fov_deg; /* vertical field of view, degrees, (0, 180) */
  int width, height;
  ss_filter filter;
  /* Derived by ss_camera_init. */
  ss_vec3 forward, right, up_cam;
  double tan_half_fov, aspect;
} ss_camera;

/* Defaults: at (0, 0, 5) looking at the origin, up +y, 30 deg, 256 x 256, box. */
void ss_camera_default(ss_camera *cam);
/* Validates the fields (finite, fov in (0, 180), resolution >= 1, target !=
 * position, up not parallel to the view direction, filter radius > 0) and
 * derives the frame. The message names the offending field. */
ss_status ss_camera_init(ss_camera *cam, ss_error *err);
/* The primary ray through pixel (px, py) with filter sample (u1, u2):
 * unit direction, tmin 0, tmax infinity. */
ss_ray ss_camera_generate_ray(const ss_camera *cam, int px, int py, double u1, double u2);
/* The continuous-pixel position of a ray through (x, y) in raster units;
 * the inverse map of ss_camera_generate_ray for tests. Returns 0 when the
 * direction points behind the camera. */
int ss_camera_raster(const ss_camera *cam, ss_vec3 dir, double *x, double *y);

#endif
