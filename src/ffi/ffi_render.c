/* The flat interface's scenes, renders and images (ffi.h over scene_io.h,
 * render.h and image_io.h). */
#include "subsurf/ffi.h"

#include "subsurf/film.h"
#include "subsurf/image_io.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct ss_ffi_scene {
  ss_scene *scene;
};

static int fail(char *err, size_t err_size, ss_status st, const char *message) {
  if (err && err_size > 0) {
    snprintf(err, err_size, "%s", message);
  }
  return (int)st;
}

ss_ffi_scene *ss_ffi_scene_load(const char *path, char *err, size_t err_size) {
  ss_error e;
  ss_ffi_scene *s = calloc(1, sizeof *s);
  if (!s) {
    fail(err, err_size, SS_ERR_NO_MEMORY, "out of memory");
    return NULL;
  }
  if (ss_scene_read(path, &s->scene, NULL, NULL, &e) != SS_OK) {
    fail(err, err_size, e.status, e.message);
    free(s);
    return NULL;
  }
  return s;
}

void ss_ffi_scene_destroy(ss_ffi_scene *s) {
  if (s) {
    ss_scene_destroy(s->scene);
    free(s);
  }
}

void ss_ffi_scene_size(const ss_ffi_scene *s, int *width, int *height) {
  *width = s->scene->camera.width;
  *height = s->scene->camera.height;
}

int ss_ffi_render(ss_ffi_scene *s, const char *integrator, int spp, const uint64_t *seed,
                  int threads, float *rgb, double stats_out[3], char *err, size_t err_size) {
  ss_integrator_settings saved = s->scene->integrator;
  if (integrator && integrator[0]) {
    if (strlen(integrator) >= sizeof s->scene->integrator.name) {
      return fail(err, err_size, SS_ERR_INVALID_ARGUMENT, "integrator name too long");
    }
    snprintf(s->scene->integrator.name, sizeof s->scene->integrator.name, "%s", integrator);
  }
  ss_render_options o;
  ss_render_options_from_scene(s->scene, &o);
  if (spp != 0) {
    o.spp = spp; /* ss_render refuses what is out of range */
  }
  if (seed) {
    o.seed = *seed;
  }
  o.threads = threads;
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_error e;
  ss_status st = ss_render(s->scene, &o, &film, &stats, &e);
  s->scene->integrator = saved;
  if (st != SS_OK) {
    ss_film_destroy(film);
    return fail(err, err_size, st, e.message);
  }
  ss_image *img = ss_film_image(film);
  ss_film_destroy(film);
  if (!img) {
    return fail(err, err_size, SS_ERR_NO_MEMORY, "out of memory for the image");
  }
  size_t n = (size_t)img->width * (size_t)img->height;
  for (size_t i = 0; i < n; i++) {
    for (int c = 0; c < 3; c++) {
      rgb[3 * i + c] = img->data[(size_t)img->channels * i + (size_t)c];
    }
  }
  ss_image_destroy(img);
  if (stats_out) {
    stats_out[0] = stats.seconds;
    stats_out[1] = (double)stats.samples;
    stats_out[2] = (double)stats.nonfinite;
  }
  return 0;
}

int ss_ffi_image_read(const char *path, int *width, int *height, int *channels, float *data,
                      size_t data_floats, char *err, size_t err_size) {
  ss_error e;
  ss_image *img = NULL;
  if (ss_image_read(path, &img, &e) != SS_OK) {
    return fail(err, err_size, e.status, e.message);
  }
  *width = img->width;
  *height = img->height;
  *channels = img->channels;
  size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
  int rc = 0;
  if (data) {
    if (data_floats < n) {
      rc = fail(err, err_size, SS_ERR_INVALID_ARGUMENT, "image buffer too small");
    } else {
      memcpy(data, img->data, n * sizeof *data);
    }
  }
  ss_image_destroy(img);
  return rc;
}
