/* pbrt-v3's Texture directive: "constant", "scale" of constants,
 * "imagemap" and "checkerboard" (2D) become constants or scene textures
 * (texture.h); other classes are replaced by a constant with a warning
 * (pbrt.h, docs/pbrt-import.md). */
#include "io/pbrt.h"

#include "subsurf/texture_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void add_texture(ss_pbrt *P, const ss_pbrt_params *ps, const ss_pbrt_texture *t) {
  void *grown = realloc(P->textures, (P->num_textures + 1) * sizeof *P->textures);
  if (!grown) {
    ss_pbrt_fail(P, ps->file, ps->line, "out of memory");
    return;
  }
  P->textures = grown;
  P->textures[P->num_textures++] = *t;
}

/* An input of a procedural texture: constants only. */
static ss_rgb constant_input(ss_pbrt *P, ss_pbrt_params *ps, const char *what, const char *name,
                             int is_float, double fallback) {
  ss_rgb v = ss_rgb_gray(fallback);
  const ss_texture *tex = NULL;
  if (ss_pbrt_texturable(P, ps, name, is_float, &v, &tex) && tex) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: \"%s\" must be a constant (nested textures are not supported); %g is used",
                 what, name, fallback);
    v = ss_rgb_gray(fallback);
  }
  return v;
}

/* pbrt-v3's "uv" mapping st = (su u + du, sv v + dv): the texture's own
 * transform. */
static void uv_mapping(ss_pbrt *P, ss_pbrt_params *ps, const char *what, ss_texture *tex) {
  char mapping[SS_NAME_SIZE] = "uv";
  ss_pbrt_string(P, ps, "mapping", mapping, sizeof mapping);
  if (strcmp(mapping, "uv")) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: mapping \"%s\" is not supported; the mesh's (u, v) are used", what, mapping);
  }
  double scale[2] = {1.0, 1.0}, offset[2] = {0.0, 0.0};
  ss_pbrt_float(P, ps, "uscale", &scale[0]);
  ss_pbrt_float(P, ps, "vscale", &scale[1]);
  ss_pbrt_float(P, ps, "udelta", &offset[0]);
  ss_pbrt_float(P, ps, "vdelta", &offset[1]);
  ss_texture_set_transform(tex, scale, offset);
}

static ss_texture *image_texture(ss_pbrt *P, ss_pbrt_params *ps, const char *what, int is_float) {
  char name[SS_PATH_SIZE] = "", path[SS_PATH_SIZE];
  if (!ss_pbrt_string(P, ps, "filename", name, sizeof name)) {
    ss_pbrt_fail(P, ps->file, ps->line, "%s: needs \"string filename\"", what);
    return NULL;
  }
  ss_pbrt_resolve(P, name, path);
  const char *dot = strrchr(name, '.');
  /* pbrt-v3 decodes 8-bit formats as sRGB unless told otherwise */
  int gamma = dot && (!strcmp(dot, ".png") || !strcmp(dot, ".tga"));
  ss_pbrt_bool(P, ps, "gamma", &gamma);
  double scale = 1.0;
  int invert = 0;
  ss_pbrt_float(P, ps, "scale", &scale);
  ss_pbrt_bool(P, ps, "invert", &invert);
  char wrap_name[SS_NAME_SIZE] = "repeat";
  ss_pbrt_string(P, ps, "wrap", wrap_name, sizeof wrap_name);
  ss_wrap wrap = SS_WRAP_REPEAT;
  if (!strcmp(wrap_name, "clamp")) {
    wrap = SS_WRAP_CLAMP;
  } else if (strcmp(wrap_name, "repeat")) {
    ss_pbrt_warn(P, ps->file, ps->line, "%s: wrap \"%s\" is not supported; \"clamp\" is used", what,
                 wrap_name);
    wrap = SS_WRAP_CLAMP;
  }
  if (P->st != SS_OK) {
    return NULL;
  }
  ss_image *img = NULL;
  ss_error e;
  if (ss_texture_image_read(path, gamma && !is_float, &img, &e) != SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "%s: %s", what, e.message);
    return NULL;
  }
  size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
  for (size_t i = 0; i < n; ++i) {
    img->data[i] = (float)(invert ? 1.0 - scale * img->data[i] : scale * img->data[i]);
  }
  ss_texture *tex = NULL;
  if (ss_texture_create_image(img, wrap, &tex, &e) != SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "%s: %s", what, e.message);
    return NULL;
  }
  return tex;
}

void ss_pbrt_texture_directive(ss_pbrt *P, const char *name, const char *kind, const char *type,
                               ss_pbrt_params *ps) {
  ss_pbrt_texture t;
  memset(&t, 0, sizeof t);
  if (strcmp(kind, "float") && strcmp(kind, "spectrum") && strcmp(kind, "color")) {
    ss_pbrt_fail(P, ps->file, ps->line,
                 "Texture \"%s\": expected the kind \"float\" or \"spectrum\", got \"%s\"", name,
                 kind);
    return;
  }
  snprintf(t.name, sizeof t.name, "%s", name);
  t.is_float = !strcmp(kind, "float");
  char what[3 * SS_NAME_SIZE];
  snprintf(what, sizeof what, "Texture \"%s\" \"%s\"", name, type);
  ss_texture *tex = NULL;
  if (!strcmp(type, "constant")) {
    t.value = constant_input(P, ps, what, "value", t.is_float, 1.0);
  } else if (!strcmp(type, "scale")) {
    ss_rgb a = constant_input(P, ps, what, "tex1", t.is_float, 1.0);
    ss_rgb b = constant_input(P, ps, what, "tex2", t.is_float, 1.0);
    t.value = ss_rgb_make(a.c[0] * b.c[0], a.c[1] * b.c[1], a.c[2] * b.c[2]);
  } else if (!strcmp(type, "imagemap")) {
    tex = image_texture(P, ps, what, t.is_float);
  } else if (!strcmp(type, "checkerboard")) {
    long dim = 2;
    ss_pbrt_int(P, ps, "dimension", 2, 3, &dim);
    if (dim == 3) {
      ss_pbrt_warn(P, ps->file, ps->line,
                   "%s: a 3D checkerboard is not supported; the 2D one in (u, v) is used", what);
    }
    ss_rgb a = constant_input(P, ps, what, "tex1", t.is_float, 1.0);
    ss_rgb b = constant_input(P, ps, what, "tex2", t.is_float, 0.0);
    ss_error e;
    if (P->st == SS_OK && ss_texture_create_checker(a, b, &tex, &e) != SS_OK) {
      ss_pbrt_fail(P, ps->file, ps->line, "%s: %s", what, e.message);
    }
  } else {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: texture class \"%s\" is not supported; the constant 0.5 is used", what, type);
    t.value = ss_rgb_gray(0.5);
  }
  if (tex) {
    uv_mapping(P, ps, what, tex);
    ss_error e;
    if (ss_scene_add_texture(P->scene, tex, &e) != SS_OK) { /* takes it, also on failure */
      ss_pbrt_fail(P, ps->file, ps->line, "%s: %s", what, e.message);
      return;
    }
    t.tex = tex;
  }
  if (P->st == SS_OK) {
    add_texture(P, ps, &t);
  }
}
