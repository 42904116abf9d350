/* pbrt-v3's LightSource "point", "spot", "distant" and "infinite" as scene
 * lights (pbrt.h, docs/pbrt-import.md). */
#include "io/pbrt.h"

#include "subsurf/texture_io.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846

/* The mean radiance over the sphere of pbrt-v3's equirectangular
 * environment map (theta = pi v from the top row, the solid angle of a
 * texel proportional to sin theta). */
static int map_mean(ss_pbrt *P, ss_pbrt_params *ps, const char *name, ss_rgb *mean) {
  char path[SS_PATH_SIZE];
  ss_pbrt_resolve(P, name, path);
  const char *dot = strrchr(name, '.');
  ss_image *img = NULL;
  ss_error e;
  if (ss_texture_image_read(path, dot && !strcmp(dot, ".png"), &img, &e) != SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "LightSource \"infinite\": %s", e.message);
    return 0;
  }
  double sum[3] = {0, 0, 0}, wsum = 0.0;
  for (int y = 0; y < img->height; ++y) {
    double w = sin(PI * (y + 0.5) / img->height);
    for (int x = 0; x < img->width; ++x) {
      const float *p = ss_image_pixel(img, x, y);
      for (int c = 0; c < 3; ++c) {
        sum[c] += w * p[img->channels == 1 ? 0 : c];
      }
      wsum += w;
    }
  }
  ss_image_destroy(img);
  *mean = ss_rgb_make(sum[0] / wsum, sum[1] / wsum, sum[2] / wsum);
  return 1;
}

void ss_pbrt_light(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  ss_light l;
  memset(&l, 0, sizeof l);
  l.shape = -1;
  snprintf(l.name, sizeof l.name, "light%zu", P->scene->num_lights);
  ss_rgb scale = ss_rgb_gray(1.0);
  ss_pbrt_rgb(P, ps, "scale", &scale);
  ss_mat4 xf = ss_pbrt_to_world(P, P->gs.ctm);
  ss_vec3 from = ss_vec3_make(0, 0, 0), to = ss_vec3_make(0, 0, 1);
  ss_pbrt_point(P, ps, "from", &from);
  ss_pbrt_point(P, ps, "to", &to);
  l.value = ss_rgb_gray(1.0);
  if (!strcmp(type, "point")) {
    l.type = SS_LIGHT_POINT;
    ss_pbrt_rgb(P, ps, "I", &l.value);
    l.position = ss_mat4_apply_point(xf, from);
  } else if (!strcmp(type, "spot")) {
    l.type = SS_LIGHT_SPOT;
    double cone = 30.0, delta = 5.0;
    ss_pbrt_rgb(P, ps, "I", &l.value);
    ss_pbrt_float(P, ps, "coneangle", &cone);
    ss_pbrt_float(P, ps, "conedeltaangle", &delta);
    l.position = ss_mat4_apply_point(xf, from);
    l.direction = ss_mat4_apply_vector(xf, ss_vec3_sub(to, from));
    l.cone_angle = cone;
    l.falloff_angle = fmin(fmax(cone - delta, 0.0), cone);
  } else if (!strcmp(type, "distant")) {
    l.type = SS_LIGHT_DIRECTIONAL;
    ss_pbrt_rgb(P, ps, "L", &l.value);
    /* pbrt's light travels from `from` toward `to` */
    l.direction = ss_mat4_apply_vector(xf, ss_vec3_sub(to, from));
  } else if (!strcmp(type, "infinite")) {
    l.type = SS_LIGHT_ENVIRONMENT;
    ss_pbrt_rgb(P, ps, "L", &l.value);
    long samples;
    ss_pbrt_int(P, ps, "nsamples", 1, 1L << 20, &samples); /* noise only */
    ss_pbrt_int(P, ps, "samples", 1, 1L << 20, &samples);
    char map[SS_PATH_SIZE];
    ss_rgb mean;
    if (ss_pbrt_string(P, ps, "mapname", map, sizeof map) && map_mean(P, ps, map, &mean)) {
      ss_pbrt_warn(P, ps->file, ps->line,
                   "LightSource \"infinite\": the map \"%s\" is approximated by its mean "
                   "radiance (%g %g %g): subsurf's environment is uniform",
                   map, mean.c[0], mean.c[1], mean.c[2]);
      l.value =
          ss_rgb_make(l.value.c[0] * mean.c[0], l.value.c[1] * mean.c[1], l.value.c[2] * mean.c[2]);
    }
  } else {
    ss_pbrt_warn(P, ps->file, ps->line, "LightSource \"%s\" is not supported (left out)", type);
    return;
  }
  if (P->st != SS_OK) {
    return;
  }
  l.value =
      ss_rgb_make(l.value.c[0] * scale.c[0], l.value.c[1] * scale.c[1], l.value.c[2] * scale.c[2]);
  if (l.type != SS_LIGHT_POINT && l.type != SS_LIGHT_ENVIRONMENT &&
      !(ss_vec3_length2(l.direction) > 0.0)) {
    ss_pbrt_fail(P, ps->file, ps->line, "LightSource \"%s\": from and to must differ", type);
    return;
  }
  if (l.type != SS_LIGHT_POINT && l.type != SS_LIGHT_ENVIRONMENT) {
    l.direction = ss_vec3_normalize(l.direction);
  }
  ss_error e;
  if (ss_scene_add_light(P->scene, &l, NULL, &e) != SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "LightSource \"%s\": %s", type, e.message);
  }
}
