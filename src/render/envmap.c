/* Environment maps: latitude-longitude lookup and importance sampling
 * (see envmap.h). */
#include "subsurf/envmap.h"

#include "core/cache_file.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>

struct ss_envmap {
  int width, height;
  /* Per pixel, row 0 around `up`: the RGB radiance and the density of
   * (u, v) there, side by side so that a lookup with its density reads one
   * 16-byte cell. */
  float *texels;
  ss_vec3 up, front, right;
  ss_distribution2d dist; /* over (u, v) = (column, row) / size */
};

void ss_envmap_destroy(ss_envmap *m) {
  if (m) {
    free(m->texels);
    ss_distribution2d_free(&m->dist);
    free(m);
  }
}

static int vec_finite(ss_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* Front made perpendicular to up and turned by `rotation` about it
 * (Rodrigues' formula for a vector normal to the axis). */
ss_status ss_envmap_frame_make(ss_vec3 up, ss_vec3 front, double rotation_deg, ss_envmap_frame *out,
                               const char **bad_key, ss_error *err) {
  double lu = ss_vec3_length(up);
  const char *key = !vec_finite(up) || !(lu > 0.0) ? "up"
                    : !vec_finite(front)           ? "front"
                    : !isfinite(rotation_deg)      ? "rotation"
                                                   : NULL;
  ss_vec3 u = ss_vec3_scale(up, 1.0 / lu);
  ss_vec3 f = ss_vec3_madd(front, u, -ss_vec3_dot(front, u));
  double lf = ss_vec3_length(f);
  if (!key && !(lf > 1e-9 * ss_vec3_length(front))) {
    key = "front";
  }
  if (bad_key) {
    *bad_key = key;
  }
  if (key) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "environment map: up must be a non-zero vector, front one not parallel "
                        "to it, rotation finite");
  }
  f = ss_vec3_scale(f, 1.0 / lf);
  ss_vec3 side = ss_vec3_cross(u, f);
  double a = rotation_deg * SS_PI / 180.0;
  out->up = u;
  out->front = ss_vec3_add(ss_vec3_scale(f, cos(a)), ss_vec3_scale(side, sin(a)));
  return SS_OK;
}

/* The radiances, and the density's function: the mean of the channels
 * times sin(theta) at the row's centre, the area element of the (u, v)
 * square on the sphere. */
static ss_status build(ss_envmap *m, const ss_image *img, ss_error *err) {
  size_t n = (size_t)m->width * (size_t)m->height;
  m->texels = malloc(4 * n * sizeof *m->texels);
  double *func = malloc(n * sizeof *func);
  if (!m->texels || !func) {
    free(func);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "environment map: out of memory");
  }
  for (size_t i = 0; i < n; ++i) {
    float *t = m->texels + 4 * i;
    for (int c = 0; c < 3; ++c) {
      float v = img->data[i * (size_t)img->channels + (img->channels == 3 ? (size_t)c : 0)];
      if (!(v >= 0.0f) || !isfinite(v)) {
        free(func);
        return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                            "environment map: pixel (%zu, %zu) is negative or not finite",
                            i % (size_t)m->width, i / (size_t)m->width);
      }
      t[c] = v;
    }
    double theta = SS_PI * ((double)(i / (size_t)m->width) + 0.5) / m->height;
    func[i] = ((double)t[0] + t[1] + t[2]) / 3.0 * sin(theta);
  }
  int rc = ss_distribution2d_init(&m->dist, func, (size_t)m->width, (size_t)m->height);
  free(func);
  if (rc != 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "environment map: every pixel is black (use a uniform environment)");
  }
  for (size_t i = 0; i < n; ++i) {
    double u = ((double)(i % (size_t)m->width) + 0.5) / m->width;
    double v = ((double)(i / (size_t)m->width) + 0.5) / m->height;
    m->texels[4 * i + 3] = (float)ss_distribution2d_pdf(&m->dist, u, v);
  }
  return SS_OK;
}

ss_status ss_envmap_create(ss_image *img, const ss_envmap_frame *frame, ss_envmap **out,
                           ss_error *err) {
  *out = NULL;
  if (!img || (img->channels != 1 && img->channels != 3) || img->height < 1 ||
      img->width != 2 * img->height) {
    ss_status st =
        img ? ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                           "environment map: %d x %d pixels with %d channel(s); a "
                           "latitude-longitude map is twice as wide as high, grey or RGB",
                           img->width, img->height, img->channels)
            : ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "environment map: no image");
    ss_image_destroy(img);
    return st;
  }
  ss_envmap *m = calloc(1, sizeof *m);
  if (!m) {
    ss_image_destroy(img);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "environment map: out of memory");
  }
  m->width = img->width;
  m->height = img->height;
  m->up = frame->up;
  m->front = frame->front;
  m->right = ss_vec3_cross(m->front, m->up);
  ss_status st = build(m, img, err);
  ss_image_destroy(img);
  if (st != SS_OK) {
    ss_envmap_destroy(m);
    return st;
  }
  *out = m;
  return SS_OK;
}

/* The cell of the pixel holding (u, v) in [0, 1]^2. */
static const float *texel(const ss_envmap *m, double u, double v) {
  int x = (int)fmin(fmax(floor(u * m->width), 0.0), m->width - 1.0);
  int y = (int)fmin(fmax(floor(v * m->height), 0.0), m->height - 1.0);
  return m->texels + 4 * ((size_t)y * (size_t)m->width + (size_t)x);
}

static ss_rgb texel_rgb(const float *t) { return ss_rgb_make(t[0], t[1], t[2]); }

/* (u, v) of direction w: theta from up = v pi, azimuth from front toward
 * right = 2 pi (u - 1/2). */
static void direction_to_uv(const ss_envmap *m, ss_vec3 w, double *u, double *v,
                            double *sin_theta) {
  double c = fmin(fmax(ss_vec3_dot(w, m->up), -1.0), 1.0);
  double a = atan2(ss_vec3_dot(w, m->right), ss_vec3_dot(w, m->front));
  *u = a / (2.0 * SS_PI) + 0.5;
  *v = acos(c) / SS_PI;
  *sin_theta = sqrt(fmax(0.0, 1.0 - c * c));
}

static ss_vec3 uv_to_direction(const ss_envmap *m, double u, double v, double *sin_theta) {
  double theta = SS_PI * v, a = 2.0 * SS_PI * (u - 0.5);
  double st = sin(theta);
  *sin_theta = st;
  ss_vec3 h = ss_vec3_add(ss_vec3_scale(m->front, cos(a)), ss_vec3_scale(m->right, sin(a)));
  return ss_vec3_madd(ss_vec3_scale(m->up, cos(theta)), h, st);
}

ss_rgb ss_envmap_eval(const ss_envmap *m, ss_vec3 w, double *pdf) {
  double u, v, st;
  direction_to_uv(m, w, &u, &v, &st);
  const float *t = texel(m, u, v);
  if (pdf) {
    *pdf = st > 0.0 ? t[3] / (2.0 * SS_PI * SS_PI * st) : 0.0;
  }
  return texel_rgb(t);
}

int ss_envmap_sample(const ss_envmap *m, double u1, double u2, ss_vec3 *w, double *pdf,
                     ss_rgb *radiance) {
  double u, v, pdf_uv, st;
  ss_distribution2d_sample(&m->dist, u1, u2, &u, &v, &pdf_uv);
  *w = uv_to_direction(m, u, v, &st);
  const float *t = texel(m, u, v);
  if (!(st > 0.0) || !(t[3] > 0.0f)) {
    return 0;
  }
  /* The (u, v) square covers the sphere with dw = 2 pi^2 sin(theta) du dv;
   * the density of (u, v) is the cell's, as ss_envmap_eval reads it. */
  *pdf = t[3] / (2.0 * SS_PI * SS_PI * st);
  *radiance = texel_rgb(t);
  return 1;
}

ss_vec3 ss_envmap_pixel_direction(const ss_envmap *m, int x, int y, double *solid_angle) {
  double st;
  /* The band between the row's two polar angles, cut into width sectors. */
  double c0 = cos(SS_PI * y / m->height), c1 = cos(SS_PI * (y + 1) / m->height);
  *solid_angle = 2.0 * SS_PI / m->width * (c0 - c1);
  return uv_to_direction(m, (x + 0.5) / m->width, (y + 0.5) / m->height, &st);
}

void ss_envmap_hash(const ss_envmap *m, uint64_t *h) {
  ss_hash_int(h, m->width), ss_hash_int(h, m->height);
  ss_hash_bytes(h, m->texels, 4 * (size_t)m->width * (size_t)m->height * sizeof *m->texels);
  ss_hash_bytes(h, &m->up, sizeof m->up), ss_hash_bytes(h, &m->front, sizeof m->front);
}
