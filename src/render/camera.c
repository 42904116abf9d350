/* Perspective camera with filter importance sampling (see camera.h). */
#include "subsurf/camera.h"

#include "subsurf/sampling.h"

#include <math.h>
#include <string.h>

ss_filter ss_filter_default(ss_filter_type type) {
  ss_filter f;
  f.type = type;
  f.radius = type == SS_FILTER_BOX ? 0.5 : 1.5;
  f.sigma = 0.5;
  return f;
}

void ss_filter_sample(const ss_filter *f, double u1, double u2, double *dx, double *dy) {
  if (f->type == SS_FILTER_BOX) {
    *dx = (2.0 * u1 - 1.0) * f->radius;
    *dy = (2.0 * u2 - 1.0) * f->radius;
    return;
  }
  /* Radial density of a 2D Gaussian truncated to r < R is proportional to
   * r exp(-r^2 / 2 sigma^2); its inverse CDF is closed form, so the sample
   * is exact and every sample's filter weight f / pdf is the same constant. */
  double s2 = 2.0 * f->sigma * f->sigma;
  double tail = -expm1(-f->radius * f->radius / s2);
  double r = sqrt(-s2 * log1p(-u1 * tail));
  double phi = 2.0 * SS_PI * u2;
  *dx = r * cos(phi);
  *dy = r * sin(phi);
}

int ss_filter_type_from_name(const char *name, ss_filter_type *type) {
  if (!strcmp(name, "box")) {
    *type = SS_FILTER_BOX;
  } else if (!strcmp(name, "gaussian")) {
    *type = SS_FILTER_GAUSSIAN;
  } else {
    return 0;
  }
  return 1;
}

const char *ss_filter_type_name(ss_filter_type type) {
  return type == SS_FILTER_BOX ? "box" : "gaussian";
}

void ss_camera_default(ss_camera *cam) {
  memset(cam, 0, sizeof *cam);
  cam->position = ss_vec3_make(0.0, 0.0, 5.0);
  cam->target = ss_vec3_make(0.0, 0.0, 0.0);
  cam->up = ss_vec3_make(0.0, 1.0, 0.0);
  cam->fov_deg = 30.0;
  cam->width = 256;
  cam->height = 256;
  cam->filter = ss_filter_default(SS_FILTER_BOX);
}

ss_status ss_camera_init(ss_camera *cam, ss_error *err) {
  if (!ss_in_world(cam->position) || !ss_in_world(cam->target) || !ss_in_world(cam->up)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "camera: position, target and up must have coordinates in [-%g, %g]",
                        SS_WORLD_LIMIT, SS_WORLD_LIMIT);
  }
  if (!(cam->fov_deg > 0.0 && cam->fov_deg < 180.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "camera: fov must be in (0, 180) degrees, got %g", cam->fov_deg);
  }
  if (cam->width < 1 || cam->height < 1 || cam->width > 65536 || cam->height > 65536) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "camera: resolution must be in [1, 65536], got %d x %d", cam->width,
                        cam->height);
  }
  if (!(cam->filter.radius > 0.0 && cam->filter.radius <= 16.0) ||
      (cam->filter.type == SS_FILTER_GAUSSIAN && !(cam->filter.sigma > 0.0))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "camera: filter radius must be in (0, 16] pixels and sigma > 0");
  }
  ss_vec3 f = ss_vec3_sub(cam->target, cam->position);
  double len = ss_vec3_length(f);
  if (!(len > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "camera: target equals position");
  }
  f = ss_vec3_scale(f, 1.0 / len);
  ss_vec3 r = ss_vec3_cross(f, cam->up);
  double rl = ss_vec3_length(r);
  if (!(rl > 1e-9 * ss_vec3_length(cam->up))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "camera: up is zero or parallel to the view direction");
  }
  cam->forward = f;
  cam->right = ss_vec3_scale(r, 1.0 / rl);
  cam->up_cam = ss_vec3_cross(cam->right, f);
  cam->tan_half_fov = tan(0.5 * cam->fov_deg * SS_PI / 180.0);
  cam->aspect = (double)cam->width / (double)cam->height;
  return SS_OK;
}

ss_ray ss_camera_generate_ray(const ss_camera *cam, int px, int py, double u1, double u2) {
  double dx, dy;
  ss_filter_sample(&cam->filter, u1, u2, &dx, &dy);
  double x = px + 0.5 + dx, y = py + 0.5 + dy;
  /* Raster to the image plane at unit distance: x right, y up. */
  double sx = (2.0 * x / cam->width - 1.0) * cam->tan_half_fov * cam->aspect;
  double sy = (1.0 - 2.0 * y / cam->height) * cam->tan_half_fov;
  ss_vec3 d = ss_vec3_madd(ss_vec3_madd(cam->forward, cam->right, sx), cam->up_cam, sy);
  ss_ray ray;
  ray.o = cam->position;
  ray.d = ss_vec3_normalize(d);
  ray.tmin = 0.0;
  ray.tmax = INFINITY;
  return ray;
}

int ss_camera_raster(const ss_camera *cam, ss_vec3 dir, double *x, double *y) {
  double z = ss_vec3_dot(dir, cam->forward);
  if (!(z > 0.0)) {
    return 0;
  }
  double sx = ss_vec3_dot(dir, cam->right) / z, sy = ss_vec3_dot(dir, cam->up_cam) / z;
  *x = (sx / (cam->tan_half_fov * cam->aspect) + 1.0) * 0.5 * cam->width;
  *y = (1.0 - sy / cam->tan_half_fov) * 0.5 * cam->height;
  return 1;
}
