/* pbrt-v3's scene-wide options: Camera "perspective", Film "image",
 * Sampler, Integrator and PixelFilter, and the handedness of pbrt's camera
 * (pbrt.h, docs/pbrt-import.md). */
#include "io/pbrt.h"

#include "subsurf/integrator.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

void ss_pbrt_options_defaults(ss_pbrt *P) {
  ss_scene *s = P->scene;
  P->fov = 90.0; /* pbrt-v3 PerspectiveCamera */
  P->width = 1280;
  P->height = 720; /* pbrt-v3 Film */
  P->crop[1] = P->crop[3] = 1.0;
  s->render.spp = 16; /* pbrt-v3 samplers' pixelsamples */
  s->integrator.max_depth = 5;
  P->integrator_path = 1; /* pbrt-v3's default Integrator is "path" */
  snprintf(P->integrator_file, sizeof P->integrator_file, "%s", P->lex->file);
  snprintf(P->camera_file, sizeof P->camera_file, "%s", P->lex->file);
}

void ss_pbrt_camera(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  if (strcmp(type, "perspective")) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "Camera \"%s\" is not supported; a perspective camera is used", type);
  }
  double v = 0.0;
  if (ss_pbrt_float(P, ps, "fov", &v)) {
    P->fov = v;
  }
  if (ss_pbrt_float(P, ps, "halffov", &v)) {
    P->fov = 2.0 * v;
  }
  if (ss_pbrt_float(P, ps, "lensradius", &v) && v > 0.0) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "Camera: lensradius %g ignored (subsurf's camera is a pinhole: everything is in "
                 "focus)",
                 v);
  }
  ss_pbrt_float(P, ps, "focaldistance", &v); /* meaningful only with a lens */
  if (!ss_mat4_inverse(P->gs.ctm, &P->camera_to_world)) {
    ss_pbrt_fail(P, ps->file, ps->line, "Camera: the current transform is singular");
    return;
  }
  P->has_camera = 1;
  P->camera_line = ps->line;
  snprintf(P->camera_file, sizeof P->camera_file, "%s", ps->file);
  /* pbrt-v3 names the camera's space "camera" (camera to world) */
  ss_mat4 saved = P->gs.ctm;
  P->gs.ctm = P->camera_to_world;
  for (size_t i = 0; i <= P->num_coord_systems; ++i) {
    if (i == P->num_coord_systems || !strcmp(P->coord_systems[i].name, "camera")) {
      if (i < P->num_coord_systems) {
        P->coord_systems[i].m = P->gs.ctm;
      } else {
        void *grown = realloc(P->coord_systems, (i + 1) * sizeof *P->coord_systems);
        if (!grown) {
          ss_pbrt_fail(P, ps->file, ps->line, "out of memory");
          break;
        }
        P->coord_systems = grown;
        snprintf(P->coord_systems[i].name, SS_NAME_SIZE, "camera");
        P->coord_systems[i].m = P->gs.ctm;
        P->num_coord_systems++;
      }
      break;
    }
  }
  P->gs.ctm = saved;
}

void ss_pbrt_film(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  if (strcmp(type, "image") && strcmp(type, "rgb")) {
    ss_pbrt_warn(P, ps->file, ps->line, "Film \"%s\" is not supported; an RGB image is written",
                 type);
  }
  long w = P->width, h = P->height;
  ss_pbrt_int(P, ps, "xresolution", 1, 65536, &w);
  ss_pbrt_int(P, ps, "yresolution", 1, 65536, &h);
  long cap = P->limits.max_resolution;
  w = cap > 0 && w > cap ? cap : w;
  h = cap > 0 && h > cap ? cap : h;
  P->width = (int)w;
  P->height = (int)h;
  static const char *const floats[] = {"float", NULL};
  const ss_pbrt_param *c = ss_pbrt_array(P, ps, "cropwindow", floats);
  if (c) {
    if (c->num_nums != 4 || !(c->nums[0] >= 0.0 && c->nums[0] < c->nums[1] && c->nums[1] <= 1.0 &&
                              c->nums[2] >= 0.0 && c->nums[2] < c->nums[3] && c->nums[3] <= 1.0)) {
      ss_pbrt_fail(P, ps->file, c->line,
                   "Film: \"float cropwindow\" expects [x0 x1 y0 y1] with 0 <= x0 < x1 <= 1 and "
                   "0 <= y0 < y1 <= 1");
      return;
    }
    memcpy(P->crop, c->nums, sizeof P->crop);
  }
  char name[SS_PATH_SIZE];
  if (ss_pbrt_string(P, ps, "filename", name, sizeof name)) {
    char *dot = strrchr(name, '.');
    if (!dot || strcmp(dot, ".exr")) {
      if (dot && !strchr(dot, '/')) {
        *dot = '\0';
      }
      ss_pbrt_warn(P, ps->file, ps->line,
                   "Film: filename written as %s.exr (and a tonemapped %s.png): subsurf writes "
                   "EXR and PNG",
                   name, name);
      if (strlen(name) + 5 > sizeof name) {
        ss_pbrt_fail(P, ps->file, ps->line, "Film: filename too long");
        return;
      }
      strcat(name, ".exr");
    }
    snprintf(P->scene->render.output, sizeof P->scene->render.output, "%s", name);
  }
}

void ss_pbrt_sampler(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  long spp = P->scene->render.spp, seed = 0, xs = 4, ys = 4;
  if (!strcmp(type, "stratified")) {
    ss_pbrt_int(P, ps, "xsamples", 1, 1L << 15, &xs);
    ss_pbrt_int(P, ps, "ysamples", 1, 1L << 15, &ys);
    int jitter;
    ss_pbrt_bool(P, ps, "jitter", &jitter);
    spp = xs * ys;
  } else {
    ss_pbrt_int(P, ps, "pixelsamples", 1, 1L << 30, &spp);
  }
  if (ss_pbrt_int(P, ps, "seed", 0, 1L << 52, &seed)) { /* pbrt-v4's */
    P->scene->render.seed = (uint64_t)seed;
  }
  P->scene->render.spp = (int)spp;
  if (strcmp(type, "random")) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "Sampler \"%s\": subsurf draws independent random samples (other noise, the "
                 "same expected image)",
                 type);
  }
}

void ss_pbrt_integrator(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  P->integrator_line = ps->line;
  snprintf(P->integrator_file, sizeof P->integrator_file, "%s", ps->file);
  P->integrator_path = !strcmp(type, "path");
  if (strcmp(type, "path") && strcmp(type, "volpath")) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "Integrator \"%s\" is not supported; volpath (the exact volumetric path tracer) "
                 "renders the scene",
                 type);
  }
  long depth = 5;
  ss_pbrt_int(P, ps, "maxdepth", 0, 100000000, &depth);
  P->scene->integrator.max_depth = (int)depth;
}

void ss_pbrt_pixel_filter(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  ss_filter *f = &P->scene->camera.filter;
  double xw = 0.5, yw = 0.5, alpha = 2.0;
  if (!strcmp(type, "gaussian")) {
    xw = yw = 2.0;
  }
  ss_pbrt_float(P, ps, "xwidth", &xw);
  ss_pbrt_float(P, ps, "ywidth", &yw);
  if (!(xw > 0.0 && yw > 0.0 && xw <= 16.0 && yw <= 16.0)) {
    ss_pbrt_fail(P, ps->file, ps->line, "PixelFilter: xwidth and ywidth must lie in (0, 16]");
    return;
  }
  if (xw != yw) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "PixelFilter: xwidth %g and ywidth %g differ; subsurf's filters are square or "
                 "round, radius %g is used",
                 xw, yw, fmax(xw, yw));
  }
  if (!strcmp(type, "box")) {
    *f = ss_filter_default(SS_FILTER_BOX);
    f->radius = fmax(xw, yw);
  } else if (!strcmp(type, "gaussian")) {
    ss_pbrt_float(P, ps, "alpha", &alpha);
    if (!(alpha > 0.0)) {
      ss_pbrt_fail(P, ps->file, ps->line, "PixelFilter \"gaussian\": alpha must be > 0");
      return;
    }
    *f = ss_filter_default(SS_FILTER_GAUSSIAN);
    f->radius = fmax(xw, yw);
    /* pbrt-v3's exp(-alpha x^2) - exp(-alpha w^2) per axis is approximated by
     * the radially symmetric exp(-r^2 / (2 sigma^2)), sigma^2 = 1 / (2 alpha) */
    f->sigma = sqrt(0.5 / alpha);
    ss_pbrt_warn(P, ps->file, ps->line,
                 "PixelFilter \"gaussian\": approximated by a round Gaussian of sigma %g pixels "
                 "truncated at radius %g (pbrt-v3's is separable and shifted to 0 at the edge)",
                 f->sigma, f->radius);
  } else {
    *f = ss_filter_default(SS_FILTER_BOX);
    ss_pbrt_warn(P, ps->file, ps->line,
                 "PixelFilter \"%s\" is not supported; a box filter of radius 0.5 is used", type);
  }
}

/* pbrt-v3's camera space has +x = up x forward, so an image seen through a
 * proper (det > 0) camera transform is the mirror image of what subsurf's
 * camera (+x = forward x up) sees. That mirror is undone by reflecting the
 * whole world across the plane through the camera spanned by its forward
 * and up directions; a camera transform that mirrors itself (the common
 * "Scale -1 1 1" before LookAt) needs none. */
static void set_mirror(ss_pbrt *P, ss_vec3 pos, ss_vec3 fwd, ss_vec3 up, ss_vec3 right_pbrt) {
  ss_vec3 right = ss_vec3_cross(fwd, up);
  P->mirror = ss_mat4_identity();
  if (ss_vec3_dot(right, right_pbrt) >= 0.0) {
    return;
  }
  ss_vec3 n = ss_vec3_normalize(right);
  ss_mat4 r = ss_mat4_identity();
  const double nv[3] = {n.x, n.y, n.z};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] -= 2.0 * nv[i] * nv[j];
    }
  }
  P->mirror = ss_mat4_mul(ss_mat4_translate(pos),
                          ss_mat4_mul(r, ss_mat4_translate(ss_vec3_scale(pos, -1.0))));
}

void ss_pbrt_finish_options(ss_pbrt *P) {
  ss_camera *cam = &P->scene->camera;
  const ss_mat4 c = P->camera_to_world;
  ss_vec3 pos = ss_mat4_apply_point(c, ss_vec3_make(0, 0, 0));
  ss_vec3 fwd = ss_mat4_apply_vector(c, ss_vec3_make(0, 0, 1));
  ss_vec3 up = ss_mat4_apply_vector(c, ss_vec3_make(0, 1, 0));
  ss_vec3 right = ss_mat4_apply_vector(c, ss_vec3_make(1, 0, 0));
  set_mirror(P, pos, fwd, up, right);
  cam->position = pos;
  cam->target = ss_vec3_add(pos, fwd);
  cam->up = up;
  cam->width = P->width;
  cam->height = P->height;
  /* pbrt-v3: fov spans the shorter image axis (the screen window is [-1, 1]
   * on it); subsurf's fov is vertical */
  double fov = P->fov;
  if (P->height > P->width && fov > 0.0 && fov < 180.0) {
    fov = 2.0 * atan(tan(0.5 * fov * DEG) * (double)P->height / (double)P->width) / DEG;
  }
  cam->fov_deg = fov;
  ss_error e;
  if (ss_camera_init(cam, &e) != SS_OK) {
    ss_pbrt_fail(P, P->camera_file, P->camera_line, "Camera: %s", e.message);
    return;
  }
  /* pbrt-v3 Film: the crop window's pixels are [ceil(res x0), ceil(res x1)) */
  int *crop = P->scene->render.crop;
  crop[0] = (int)ceil(P->width * P->crop[0]);
  crop[2] = (int)ceil(P->width * P->crop[1]);
  crop[1] = (int)ceil(P->height * P->crop[2]);
  crop[3] = (int)ceil(P->height * P->crop[3]);
  if (crop[0] >= crop[2] || crop[1] >= crop[3]) {
    ss_pbrt_fail(P, P->camera_file, P->camera_line, "Film: the crop window holds no pixel");
    return;
  }
  if (crop[0] == 0 && crop[1] == 0 && crop[2] == P->width && crop[3] == P->height) {
    memset(crop, 0, 4 * sizeof *crop);
  }
}

void ss_pbrt_finish_integrator(ss_pbrt *P) {
  ss_integrator_settings *in = &P->scene->integrator;
  const char *name = P->integrator_path ? (P->has_subsurface ? "bssrdf" : "path") : "volpath";
  snprintf(in->name, sizeof in->name, "%s", name);
  if (!P->integrator_path && P->has_subsurface && in->max_depth < 1000) {
    ss_pbrt_warn(P, P->integrator_file, P->integrator_line,
                 "Integrator: maxdepth %d raised to 100000: volpath traces subsurface materials "
                 "as media and counts every scattering event inside (pbrt-v3 counts one bounce "
                 "per BSSRDF sample); --integrator bssrdf renders them as pbrt-v3 does",
                 in->max_depth);
    in->max_depth = 100000;
  }
}
