/* Per-pixel Welford accumulation (see film.h). */
#include "subsurf/film.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

typedef ss_film_pixel_state pixel;

struct ss_film {
  int width, height;
  pixel *pixels;
};

double ss_film_bytes(int width, int height) {
  return (double)width * (double)height * (double)sizeof(pixel);
}

double ss_film_image_bytes(int width, int height) {
  return (double)width * (double)height * 3.0 * (double)sizeof(float);
}

ss_status ss_film_create(int width, int height, ss_film **out, ss_error *err) {
  *out = NULL;
  if (width < 1 || height < 1) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "film: size %d x %d is empty", width, height);
  }
  ss_film *f = malloc(sizeof *f);
  if (!f) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "film: out of memory");
  }
  f->width = width;
  f->height = height;
  f->pixels = calloc((size_t)width * (size_t)height, sizeof *f->pixels);
  if (!f->pixels) {
    free(f);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "film: out of memory for %d x %d pixels", width,
                        height);
  }
  *out = f;
  return SS_OK;
}

void ss_film_destroy(ss_film *film) {
  if (film) {
    free(film->pixels);
    free(film);
  }
}

int ss_film_width(const ss_film *film) { return film->width; }
int ss_film_height(const ss_film *film) { return film->height; }

static pixel *at(const ss_film *f, int x, int y) {
  return f->pixels + (size_t)y * (size_t)f->width + (size_t)x;
}

int ss_film_add_sample(ss_film *film, int x, int y, ss_rgb value) {
  pixel *p = at(film, x, y);
  if (!ss_rgb_is_finite(value)) {
    p->rejected++;
    return 0;
  }
  /* Welford 1962: numerically stable running mean and second moment. */
  p->n++;
  for (int c = 0; c < 3; ++c) {
    double delta = value.c[c] - p->mean[c];
    p->mean[c] += delta / p->n;
    p->m2[c] += delta * (value.c[c] - p->mean[c]);
  }
  return 1;
}

uint64_t ss_film_sample_count(const ss_film *film) {
  uint64_t n = 0;
  for (size_t i = 0; i < (size_t)film->width * (size_t)film->height; ++i) {
    n += film->pixels[i].n;
  }
  return n;
}

uint64_t ss_film_nonfinite_count(const ss_film *film) {
  uint64_t n = 0;
  for (size_t i = 0; i < (size_t)film->width * (size_t)film->height; ++i) {
    n += film->pixels[i].rejected;
  }
  return n;
}

uint32_t ss_film_min_samples(const ss_film *film) {
  uint32_t m = UINT32_MAX;
  for (size_t i = 0; i < (size_t)film->width * (size_t)film->height; ++i) {
    if (film->pixels[i].n < m) {
      m = film->pixels[i].n;
    }
  }
  return m;
}

uint32_t ss_film_pixel_samples(const ss_film *film, int x, int y) { return at(film, x, y)->n; }

uint32_t ss_film_pixel_drawn(const ss_film *film, int x, int y) {
  const pixel *p = at(film, x, y);
  return p->n + p->rejected;
}

uint32_t ss_film_min_drawn(const ss_film *film) {
  uint32_t m = UINT32_MAX;
  for (size_t i = 0; i < (size_t)film->width * (size_t)film->height; ++i) {
    uint32_t d = film->pixels[i].n + film->pixels[i].rejected;
    m = d < m ? d : m;
  }
  return m;
}

void ss_film_get_pixel_state(const ss_film *film, int x, int y, ss_film_pixel_state *out) {
  *out = *at(film, x, y);
}

void ss_film_set_pixel_state(ss_film *film, int x, int y, const ss_film_pixel_state *in) {
  *at(film, x, y) = *in;
}

ss_rgb ss_film_pixel_mean(const ss_film *film, int x, int y) {
  const pixel *p = at(film, x, y);
  return ss_rgb_make(p->mean[0], p->mean[1], p->mean[2]);
}

/* An image holding one statistic of every pixel's accumulation. */
static ss_image *film_to_image(const ss_film *film, float (*stat)(const pixel *p, int c)) {
  ss_image *img = ss_image_create(film->width, film->height, 3);
  if (!img) {
    return NULL;
  }
  for (int y = 0; y < film->height; ++y) {
    for (int x = 0; x < film->width; ++x) {
      const pixel *p = at(film, x, y);
      float *out = ss_image_pixel(img, x, y);
      for (int c = 0; c < 3; ++c) {
        out[c] = stat(p, c);
      }
    }
  }
  return img;
}

/* The nearest float to a finite or infinite double, never Inf. */
static float to_float(double v) { return (float)fmax(-FLT_MAX, fmin(FLT_MAX, v)); }

static int beyond_float(double v) { return !(fabs(v) <= FLT_MAX); }

static double mean_of(const pixel *p, int c) { return p->mean[c]; }

/* Sample variance m2 / (n - 1), divided by n for the mean's variance. */
static double variance_of(const pixel *p, int c) {
  return p->n > 1 ? p->m2[c] / ((double)(p->n - 1) * p->n) : 0.0;
}

static float pixel_mean(const pixel *p, int c) { return to_float(mean_of(p, c)); }

static float pixel_mean_variance(const pixel *p, int c) { return to_float(variance_of(p, c)); }

uint64_t ss_film_clamped_count(const ss_film *film) {
  uint64_t n = 0;
  for (size_t i = 0; i < (size_t)film->width * (size_t)film->height; ++i) {
    for (int c = 0; c < 3; ++c) {
      n += beyond_float(mean_of(&film->pixels[i], c)) +
           beyond_float(variance_of(&film->pixels[i], c));
    }
  }
  return n;
}

ss_image *ss_film_image(const ss_film *film) { return film_to_image(film, pixel_mean); }

ss_image *ss_film_variance_image(const ss_film *film) {
  return film_to_image(film, pixel_mean_variance);
}
