/* pbrt-v3 scenes: the directives, the graphics state (current transform,
 * material, media, area light, attribute and transform stacks), named
 * coordinate systems, Include/Import and the entry points of scene_io.h.
 * pbrt.h describes the importer's state; docs/pbrt-import.md the mapping. */
#include "io/pbrt.h"

#include "io/scene_file.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_pbrt_fail(ss_pbrt *P, const char *file, int line, const char *fmt, ...) {
  if (P->st != SS_OK) {
    return P->st;
  }
  char msg[SS_ERROR_MESSAGE_SIZE];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  P->st = ss_error_set(P->err, SS_ERR_PARSE, "%s:%d: %s", file, line, msg);
  return P->st;
}

void ss_pbrt_warn(ss_pbrt *P, const char *file, int line, const char *fmt, ...) {
  if (!P->warn || P->st != SS_OK) {
    return;
  }
  char msg[SS_ERROR_MESSAGE_SIZE], full[SS_ERROR_MESSAGE_SIZE + SS_PATH_SIZE];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  snprintf(full, sizeof full, "%s:%d: %s", file, line, msg);
  ss_text_escape_controls(full, sizeof full);
  P->warn(P->user, full);
}

void ss_pbrt_resolve(const ss_pbrt *P, const char *name, char out[SS_PATH_SIZE]) {
  if (name[0] == '/') {
    snprintf(out, SS_PATH_SIZE, "%s", name);
  } else if (snprintf(out, SS_PATH_SIZE, "%s/%s", P->search_dir, name) >= SS_PATH_SIZE) {
    out[0] = '\0';
  }
}

ss_mat4 ss_pbrt_to_world(const ss_pbrt *P, ss_mat4 ctm) { return ss_mat4_mul(P->mirror, ctm); }

/* ---- directive arguments */

static const char *file_of(const ss_pbrt *P) { return P->lex ? P->lex->file : "?"; }

static void expect_string(ss_pbrt *P, const char *directive, char *out, size_t size) {
  ss_pbrt_token t;
  ss_pbrt_next(P, &t);
  if (P->st != SS_OK) {
    return;
  }
  if (t.kind != SS_PBRT_STRING) {
    ss_pbrt_fail(P, file_of(P), t.line, "%s: expected a quoted string, got %s", directive,
                 t.kind == SS_PBRT_EOF ? "end of file" : t.text);
    return;
  }
  if (strlen(t.text) >= size) {
    ss_pbrt_fail(P, file_of(P), t.line, "%s: \"%s\" is longer than %zu bytes", directive, t.text,
                 size - 1);
    return;
  }
  snprintf(out, size, "%s", t.text);
}

/* n numbers, in brackets or not. */
static void expect_numbers(ss_pbrt *P, const char *directive, double *v, int n) {
  ss_pbrt_token t;
  ss_pbrt_peek(P, &t);
  int bracket = t.kind == SS_PBRT_LBRACKET;
  if (bracket) {
    ss_pbrt_next(P, &t);
  }
  for (int i = 0; i < n && P->st == SS_OK; ++i) {
    ss_pbrt_next(P, &t);
    if (t.kind != SS_PBRT_NUMBER && P->st == SS_OK) {
      ss_pbrt_fail(P, file_of(P), t.line, "%s: expected %d numbers, got %s after %d", directive, n,
                   t.kind == SS_PBRT_EOF ? "end of file" : t.text, i);
      return;
    }
    v[i] = t.number;
  }
  if (bracket && P->st == SS_OK) {
    ss_pbrt_next(P, &t);
    if (t.kind != SS_PBRT_RBRACKET) {
      ss_pbrt_fail(P, file_of(P), t.line, "%s: expected ']' after %d numbers, got %s", directive, n,
                   t.kind == SS_PBRT_EOF ? "end of file" : t.text);
    }
  }
}

/* ---- transforms (pbrt-v3 api.cpp: each directive post-multiplies the
 * current transformation matrix, so the last one written applies first) */

static void concat(ss_pbrt *P, ss_mat4 m) { P->gs.ctm = ss_mat4_mul(P->gs.ctm, m); }

/* pbrt-v3's LookAt: the world-to-camera matrix of a camera at `eye` whose
 * +x is up x dir (pbrt's left-handed camera space). */
static int look_at(ss_vec3 eye, ss_vec3 target, ss_vec3 up, ss_mat4 *out) {
  ss_vec3 dir = ss_vec3_sub(target, eye);
  if (!(ss_vec3_length2(dir) > 0.0) || !(ss_vec3_length2(up) > 0.0)) {
    return 0;
  }
  dir = ss_vec3_normalize(dir);
  ss_vec3 right = ss_vec3_cross(ss_vec3_normalize(up), dir);
  if (!(ss_vec3_length(right) > 1e-12)) {
    return 0;
  }
  right = ss_vec3_normalize(right);
  ss_vec3 new_up = ss_vec3_cross(dir, right);
  ss_mat4 c2w = ss_mat4_identity();
  const ss_vec3 cols[4] = {right, new_up, dir, eye};
  for (int j = 0; j < 4; ++j) {
    c2w.m[0][j] = cols[j].x;
    c2w.m[1][j] = cols[j].y;
    c2w.m[2][j] = cols[j].z;
  }
  return ss_mat4_inverse(c2w, out);
}

static void transform_directive(ss_pbrt *P, const char *d, int line) {
  double v[16];
  if (!strcmp(d, "Translate")) {
    expect_numbers(P, d, v, 3);
    concat(P, ss_mat4_translate(ss_vec3_make(v[0], v[1], v[2])));
  } else if (!strcmp(d, "Scale")) {
    expect_numbers(P, d, v, 3);
    concat(P, ss_mat4_scale(ss_vec3_make(v[0], v[1], v[2])));
  } else if (!strcmp(d, "Rotate")) {
    expect_numbers(P, d, v, 4);
    if (P->st == SS_OK && !(v[1] * v[1] + v[2] * v[2] + v[3] * v[3] > 0.0)) {
      ss_pbrt_fail(P, file_of(P), line, "Rotate: the axis must not be zero");
      return;
    }
    concat(P, ss_mat4_rotate(v[0], ss_vec3_make(v[1], v[2], v[3])));
  } else if (!strcmp(d, "LookAt")) {
    expect_numbers(P, d, v, 9);
    if (P->st != SS_OK) {
      return;
    }
    ss_mat4 m;
    if (!look_at(ss_vec3_make(v[0], v[1], v[2]), ss_vec3_make(v[3], v[4], v[5]),
                 ss_vec3_make(v[6], v[7], v[8]), &m)) {
      ss_pbrt_fail(P, file_of(P), line,
                   "LookAt: the eye equals the target or up is parallel to the view direction");
      return;
    }
    concat(P, m);
  } else { /* Transform, ConcatTransform: 16 numbers, column-major */
    expect_numbers(P, d, v, 16);
    ss_mat4 m;
    for (int i = 0; i < 16; ++i) {
      m.m[i % 4][i / 4] = v[i];
    }
    if (!strcmp(d, "Transform")) {
      P->gs.ctm = m;
    } else {
      concat(P, m);
    }
  }
}

static void coordinate_system(ss_pbrt *P, const char *name, int set_ctm, int line) {
  for (size_t i = 0; i < P->num_coord_systems; ++i) {
    if (!strcmp(P->coord_systems[i].name, name)) {
      if (set_ctm) {
        P->gs.ctm = P->coord_systems[i].m;
      } else {
        P->coord_systems[i].m = P->gs.ctm;
      }
      return;
    }
  }
  if (set_ctm) {
    ss_pbrt_warn(P, file_of(P), line,
                 "CoordSysTransform: no coordinate system named \"%s\" "
                 "(ignored)",
                 name);
    return;
  }
  void *grown = realloc(P->coord_systems, (P->num_coord_systems + 1) * sizeof *P->coord_systems);
  if (!grown) {
    ss_pbrt_fail(P, file_of(P), line, "out of memory");
    return;
  }
  P->coord_systems = grown;
  snprintf(P->coord_systems[P->num_coord_systems].name, SS_NAME_SIZE, "%s", name);
  P->coord_systems[P->num_coord_systems++].m = P->gs.ctm;
}

/* ---- attribute and transform blocks */

static void push(ss_pbrt *P, char kind, const char *d, int line) {
  if (P->depth >= SS_PBRT_STACK_MAX) {
    ss_pbrt_fail(P, file_of(P), line, "%s: more than %d nested blocks", d, SS_PBRT_STACK_MAX);
    return;
  }
  P->gs.num_named = P->num_named;
  P->gs.num_textures = P->num_textures;
  P->stack[P->depth] = P->gs;
  P->stack_kind[P->depth++] = kind;
}

static void pop(ss_pbrt *P, char kind, const char *d, int line) {
  if (P->depth == 0 || P->stack_kind[P->depth - 1] != kind) {
    ss_pbrt_fail(P, file_of(P), line, "%s without a matching %s", d,
                 P->depth == 0 ? (kind == 'a' ? "AttributeBegin" : "TransformBegin")
                 : P->stack_kind[P->depth - 1] == 'a' ? "TransformBegin (an AttributeBegin is "
                                                        "open)"
                                                      : "AttributeBegin (a TransformBegin is "
                                                        "open)");
    return;
  }
  const ss_pbrt_gstate *saved = &P->stack[--P->depth];
  if (kind == 't') {
    P->gs.ctm = saved->ctm;
    return;
  }
  P->gs = *saved;
  /* named materials and textures are part of pbrt-v3's graphics state */
  P->num_named = saved->num_named;
  P->num_textures = saved->num_textures;
}

/* ---- media of the graphics state */

static int medium_index(ss_pbrt *P, const char *name, int line) {
  if (!name[0]) {
    return -1;
  }
  int i = ss_scene_find_medium(P->scene, name);
  if (i < 0) {
    ss_pbrt_fail(P, file_of(P), line,
                 "MediumInterface: no medium named \"%s\" (MakeNamedMedium "
                 "must come first)",
                 name);
  }
  return i;
}

static void medium_interface(ss_pbrt *P, int line) {
  char inside[SS_NAME_SIZE] = "", outside[SS_NAME_SIZE] = "";
  expect_string(P, "MediumInterface", inside, sizeof inside);
  snprintf(outside, sizeof outside, "%s", inside);
  ss_pbrt_token t;
  ss_pbrt_peek(P, &t);
  if (t.kind == SS_PBRT_STRING) {
    expect_string(P, "MediumInterface", outside, sizeof outside);
  }
  P->gs.inside = medium_index(P, inside, line);
  P->gs.outside = medium_index(P, outside, line);
  if (P->st == SS_OK && outside[0]) {
    ss_pbrt_warn(P, file_of(P), line,
                 "MediumInterface: outside medium \"%s\" ignored (subsurf's media fill closed "
                 "shapes; what surrounds them is vacuum)",
                 outside);
  }
}

/* ---- Include and Import */

static void include(ss_pbrt *P, const char *d, int line) {
  char name[SS_PATH_SIZE], path[SS_PATH_SIZE];
  expect_string(P, d, name, sizeof name);
  if (P->st != SS_OK) {
    return;
  }
  ss_pbrt_resolve(P, name, path);
  if (!path[0]) {
    ss_pbrt_fail(P, file_of(P), line, "%s: path too long", d);
    return;
  }
  if (P->include_depth >= SS_PBRT_INCLUDE_MAX) {
    ss_pbrt_fail(P, file_of(P), line, "%s \"%s\": more than %d nested includes (a cycle?)", d, name,
                 SS_PBRT_INCLUDE_MAX);
    return;
  }
  char *text = NULL, dir[SS_PATH_SIZE];
  ss_error sub;
  if (ss_scene_file_read(path, "a pbrt text file", &text, dir, &sub) != SS_OK) {
    ss_pbrt_fail(P, file_of(P), line, "%s \"%s\": %s", d, name, sub.message);
    P->st = sub.status == SS_ERR_IO ? SS_ERR_IO : SS_ERR_PARSE;
    P->err->status = P->st;
    return;
  }
  ss_pbrt_lexer_push(P, text, path);
  ++P->include_depth;
}

/* ---- objects */

static void object_begin(ss_pbrt *P, int line) {
  char name[SS_NAME_SIZE];
  expect_string(P, "ObjectBegin", name, sizeof name);
  if (P->st != SS_OK) {
    return;
  }
  if (P->object >= 0) {
    ss_pbrt_fail(P, file_of(P), line, "ObjectBegin \"%s\" inside ObjectBegin \"%s\"", name,
                 P->objects[P->object].name);
    return;
  }
  push(P, 'a', "ObjectBegin", line);
  void *grown = realloc(P->objects, (P->num_objects + 1) * sizeof *P->objects);
  if (!grown) {
    ss_pbrt_fail(P, file_of(P), line, "out of memory");
    return;
  }
  P->objects = grown;
  ss_pbrt_object *o = &P->objects[P->num_objects];
  memset(o, 0, sizeof *o);
  snprintf(o->name, sizeof o->name, "%s", name);
  P->object = (int)P->num_objects++;
}

/* ---- the directive loop */

typedef void (*typed_fn)(ss_pbrt *P, const char *type, ss_pbrt_params *ps);

/* A directive's leading strings (names, types). */
typedef struct {
  char s[3][SS_NAME_SIZE];
  typed_fn typed; /* the handler of a typed directive */
} leading;

typedef void (*params_fn)(ss_pbrt *P, leading *a, ss_pbrt_params *ps);

/* A directive "S0" ... "Sn-1" params...: `fn` gets the strings and the
 * parameter list (when both were read), then the parameters it did not use
 * are reported, naming the directive with the strings in `shown` (bit i:
 * a->s[i]). */
static void with_params(ss_pbrt *P, const char *d, int line, int n, unsigned shown, leading *a,
                        params_fn fn) {
  for (int i = 0; i < n; ++i) {
    expect_string(P, d, a->s[i], SS_NAME_SIZE);
  }
  ss_pbrt_params ps;
  ss_pbrt_params_read(P, &ps);
  snprintf(ps.file, sizeof ps.file, "%s", file_of(P));
  ps.line = line;
  if (P->st == SS_OK) {
    fn(P, a, &ps);
  }
  char what[4 * SS_NAME_SIZE];
  size_t used = (size_t)snprintf(what, sizeof what, "%s", d);
  for (int i = 0; i < n && used < sizeof what; ++i) {
    if (shown >> i & 1u) {
      used += (size_t)snprintf(what + used, sizeof what - used, " \"%s\"", a->s[i]);
    }
  }
  ss_pbrt_params_report(P, &ps, what);
  ss_pbrt_params_free(&ps);
}

static void call_typed(ss_pbrt *P, leading *a, ss_pbrt_params *ps) { a->typed(P, a->s[0], ps); }

/* A directive "TYPE" params... whose handler reports unused parameters. */
static void typed(ss_pbrt *P, const char *d, int line, typed_fn fn) {
  leading a = {.typed = fn};
  with_params(P, d, line, 1, 1u, &a, call_typed);
}

static void named_material(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  char kind[SS_NAME_SIZE] = "";
  if (!ss_pbrt_string(P, ps, "type", kind, sizeof kind) && P->st == SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "MakeNamedMaterial \"%s\": needs \"string type\"", type);
    return;
  }
  ss_pbrt_material_directive(P, kind, type, ps);
}

static void anonymous_material(ss_pbrt *P, const char *type, ss_pbrt_params *ps) {
  ss_pbrt_material_directive(P, type, NULL, ps);
}

static void use_named_material(ss_pbrt *P, int line) {
  char name[SS_NAME_SIZE];
  expect_string(P, "NamedMaterial", name, sizeof name);
  for (size_t i = P->num_named; P->st == SS_OK && i-- > 0;) {
    if (!strcmp(P->named[i].name, name)) {
      P->gs.material = P->named[i].material;
      return;
    }
  }
  ss_pbrt_fail(P, file_of(P), line, "NamedMaterial: no material named \"%s\"", name);
}

static void call_texture(ss_pbrt *P, leading *a, ss_pbrt_params *ps) {
  ss_pbrt_texture_directive(P, a->s[0], a->s[1], a->s[2], ps);
}

/* Texture "name" "kind" "class" params... (reported as Texture "name" "class"). */
static void texture_directive(ss_pbrt *P, int line) {
  leading a = {.typed = NULL};
  with_params(P, "Texture", line, 3, 1u | 4u, &a, call_texture);
}

static void call_medium(ss_pbrt *P, leading *a, ss_pbrt_params *ps) {
  ss_pbrt_named_medium(P, a->s[0], ps);
}

static void medium_directive(ss_pbrt *P, int line) {
  leading a = {.typed = NULL};
  with_params(P, "MakeNamedMedium", line, 1, 1u, &a, call_medium);
}

/* Directives allowed only between WorldBegin and WorldEnd (pbrt-v3 ignores
 * them elsewhere with an error message; so does subsurf, with a warning). */
static int world_only(ss_pbrt *P, const char *d, int line) {
  if (P->in_world) {
    return 1;
  }
  ss_pbrt_warn(P, file_of(P), line, "%s before WorldBegin is ignored (as pbrt-v3 does)", d);
  return 0;
}

/* Skips a directive's parameter list (and its leading strings). */
static void skip_args(ss_pbrt *P) {
  ss_pbrt_token t;
  for (;;) {
    ss_pbrt_peek(P, &t);
    if (P->st != SS_OK || t.kind == SS_PBRT_EOF || t.kind == SS_PBRT_WORD) {
      return;
    }
    ss_pbrt_next(P, &t);
    if (t.kind == SS_PBRT_LBRACKET) {
      do {
        ss_pbrt_next(P, &t);
      } while (P->st == SS_OK && t.kind != SS_PBRT_RBRACKET && t.kind != SS_PBRT_EOF);
    }
  }
}

static void options_only(ss_pbrt *P, const char *d, int line, typed_fn fn) {
  if (P->in_world) {
    ss_pbrt_fail(P, file_of(P), line, "%s must come before WorldBegin", d);
    return;
  }
  typed(P, d, line, fn);
}

static void world_begin(ss_pbrt *P, int line);

/* Directives of pbrt-v3 (and v2's and v4's) that subsurf reads past. */
static int is_unsupported(const char *d) {
  static const char *const names[] = {"ActiveTransform",
                                      "TransformTimes",
                                      "SurfaceIntegrator",
                                      "VolumeIntegrator",
                                      "Renderer",
                                      "Volume",
                                      "ColorSpace",
                                      "Option",
                                      "Attribute",
                                      "MakeNamedCamera",
                                      NULL};
  for (int i = 0; names[i]; ++i) {
    if (!strcmp(d, names[i])) {
      return 1;
    }
  }
  return 0;
}

static void directive(ss_pbrt *P, const char *d, int line) {
  static const char *const transforms[] = {"Translate", "Scale",           "Rotate", "LookAt",
                                           "Transform", "ConcatTransform", NULL};
  for (int i = 0; transforms[i]; ++i) {
    if (!strcmp(d, transforms[i])) {
      transform_directive(P, d, line);
      return;
    }
  }
  char s[SS_PATH_SIZE];
  if (!strcmp(d, "Identity")) {
    P->gs.ctm = ss_mat4_identity();
  } else if (!strcmp(d, "CoordinateSystem") || !strcmp(d, "CoordSysTransform")) {
    expect_string(P, d, s, SS_NAME_SIZE);
    if (P->st == SS_OK)
      coordinate_system(P, s, !strcmp(d, "CoordSysTransform"), line);
  } else if (!strcmp(d, "AttributeBegin") || !strcmp(d, "TransformBegin")) {
    push(P, d[0] == 'A' ? 'a' : 't', d, line);
  } else if (!strcmp(d, "AttributeEnd") || !strcmp(d, "TransformEnd")) {
    pop(P, d[0] == 'A' ? 'a' : 't', d, line);
  } else if (!strcmp(d, "ReverseOrientation")) {
    P->gs.reverse = !P->gs.reverse;
  } else if (!strcmp(d, "Camera")) {
    options_only(P, d, line, ss_pbrt_camera);
  } else if (!strcmp(d, "Film")) {
    options_only(P, d, line, ss_pbrt_film);
  } else if (!strcmp(d, "Sampler")) {
    options_only(P, d, line, ss_pbrt_sampler);
  } else if (!strcmp(d, "Integrator")) {
    options_only(P, d, line, ss_pbrt_integrator);
  } else if (!strcmp(d, "PixelFilter")) {
    options_only(P, d, line, ss_pbrt_pixel_filter);
  } else if (!strcmp(d, "WorldBegin")) {
    world_begin(P, line);
  } else if (!strcmp(d, "WorldEnd")) {
    if (!P->in_world || P->world_ended) {
      ss_pbrt_fail(P, file_of(P), line, "WorldEnd without WorldBegin");
    } else if (P->depth > 0) {
      ss_pbrt_fail(P, file_of(P), line, "WorldEnd with %d %s still open", P->depth,
                   P->stack_kind[P->depth - 1] == 'a' ? "AttributeBegin" : "TransformBegin");
    }
    P->world_ended = 1;
  } else if (!strcmp(d, "Include") || !strcmp(d, "Import")) {
    include(P, d, line);
  } else if (!strcmp(d, "MakeNamedMedium")) {
    medium_directive(P, line);
  } else if (!strcmp(d, "MediumInterface")) {
    medium_interface(P, line);
  } else if (!strcmp(d, "Accelerator")) {
    skip_args(P); /* subsurf's accelerator is Embree's BVH: no difference in the image */
  } else if (is_unsupported(d)) {
    ss_pbrt_warn(P, file_of(P), line, "%s is not supported (ignored)", d);
    ss_pbrt_token t;
    ss_pbrt_peek(P, &t);
    if (!strcmp(d, "ActiveTransform") && t.kind == SS_PBRT_WORD) {
      ss_pbrt_next(P, &t); /* StartTime, EndTime or All */
    }
    skip_args(P);
  } else if (!world_only(P, d, line)) {
    skip_args(P);
  } else if (!strcmp(d, "Shape")) {
    typed(P, d, line, ss_pbrt_shape);
  } else if (!strcmp(d, "Material")) {
    typed(P, d, line, anonymous_material);
  } else if (!strcmp(d, "MakeNamedMaterial")) {
    typed(P, d, line, named_material);
  } else if (!strcmp(d, "NamedMaterial")) {
    use_named_material(P, line);
  } else if (!strcmp(d, "Texture")) {
    texture_directive(P, line);
  } else if (!strcmp(d, "LightSource")) {
    typed(P, d, line, ss_pbrt_light);
  } else if (!strcmp(d, "AreaLightSource")) {
    typed(P, d, line, ss_pbrt_area_light);
  } else if (!strcmp(d, "ObjectBegin")) {
    object_begin(P, line);
  } else if (!strcmp(d, "ObjectEnd")) {
    if (P->object < 0) {
      ss_pbrt_fail(P, file_of(P), line, "ObjectEnd without ObjectBegin");
      return;
    }
    pop(P, 'a', d, line);
    P->object = -1;
  } else if (!strcmp(d, "ObjectInstance")) {
    expect_string(P, d, s, SS_NAME_SIZE);
    if (P->st == SS_OK)
      ss_pbrt_object_instance(P, s, file_of(P), line);
  } else {
    ss_pbrt_fail(P, file_of(P), line, "unknown directive '%s'", d);
  }
}

static void world_begin(ss_pbrt *P, int line) {
  if (P->in_world) {
    ss_pbrt_fail(P, file_of(P), line, "WorldBegin inside the world block");
    return;
  }
  if (P->depth > 0) {
    ss_pbrt_fail(P, file_of(P), line, "WorldBegin with %d blocks still open", P->depth);
    return;
  }
  P->in_world = 1;
  P->gs.ctm = ss_mat4_identity();
  coordinate_system(P, "world", 0, line);
  ss_pbrt_finish_options(P);
}

static void parse(ss_pbrt *P) {
  ss_pbrt_token t;
  while (P->st == SS_OK) {
    ss_pbrt_next(P, &t);
    if (P->st != SS_OK) {
      return;
    }
    if (t.kind == SS_PBRT_EOF) {
      if (P->lex && P->lex->parent) {
        ss_pbrt_lexer_pop(P);
        --P->include_depth;
        continue;
      }
      break;
    }
    if (P->world_ended) {
      ss_pbrt_fail(P, file_of(P), t.line, "'%s' after WorldEnd", t.text);
      return;
    }
    if (t.kind != SS_PBRT_WORD) {
      ss_pbrt_fail(P, file_of(P), t.line, "expected a directive, got %s%s%s",
                   t.kind == SS_PBRT_STRING ? "\"" : "", t.text,
                   t.kind == SS_PBRT_STRING ? "\" (a parameter without a directive?)" : "");
      return;
    }
    directive(P, t.text, t.line);
  }
  if (P->st == SS_OK && !P->world_ended) {
    ss_pbrt_fail(P, file_of(P), P->lex ? P->lex->line : 0, "end of file before %s (truncated?)",
                 P->in_world ? "WorldEnd" : "WorldBegin");
  }
}

static void free_state(ss_pbrt *P) {
  while (ss_pbrt_lexer_pop(P)) {
  }
  for (size_t i = 0; i < P->num_objects; ++i) {
    for (size_t k = 0; k < P->objects[i].n; ++k) {
      ss_mesh_destroy(P->objects[i].shapes[k].mesh);
    }
    free(P->objects[i].shapes);
  }
  free(P->objects);
  free(P->coord_systems);
  free(P->materials);
  free(P->named);
  free(P->textures);
  free(P->made);
}

ss_status ss_scene_parse_pbrt(const char *text, const char *file, const char *base_dir,
                              ss_scene **out, ss_scene_warning_fn warn, void *user, ss_error *err) {
  return ss_scene_parse_pbrt_limited(text, file, base_dir, NULL, out, warn, user, err);
}

ss_status ss_scene_parse_pbrt_limited(const char *text, const char *file, const char *base_dir,
                                      const ss_pbrt_limits *limits, ss_scene **out,
                                      ss_scene_warning_fn warn, void *user, ss_error *err) {
  *out = NULL;
  ss_pbrt *P = calloc(1, sizeof *P);
  char *copy = strdup(text);
  if (!P || !copy) {
    free(P);
    free(copy);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", file);
  }
  P->err = err;
  P->warn = warn;
  P->user = user;
  P->object = -1;
  if (limits) {
    P->limits = *limits;
  }
  P->mirror = ss_mat4_identity();
  P->camera_to_world = ss_mat4_identity();
  P->gs.ctm = ss_mat4_identity();
  P->gs.inside = P->gs.outside = -1;
  snprintf(P->search_dir, sizeof P->search_dir, "%s", base_dir ? base_dir : ".");
  P->st = ss_scene_create(&P->scene, err);
  ss_pbrt_lexer_push(P, copy, file);
  if (P->st == SS_OK) {
    ss_pbrt_options_defaults(P);
    ss_pbrt_default_material(P);
  }
  parse(P);
  if (P->st == SS_OK) {
    ss_pbrt_finish_integrator(P);
  }
  if (P->st == SS_OK && ss_scene_commit(P->scene, err) != SS_OK) {
    ss_error_prefix(err, "%s: ", file);
    P->st = SS_ERR_PARSE;
  }
  ss_status st = P->st;
  if (st == SS_OK) {
    *out = P->scene;
  } else {
    ss_scene_destroy(P->scene);
  }
  free_state(P);
  free(P);
  return st;
}

ss_status ss_scene_read_pbrt(const char *path, ss_scene **out, ss_scene_warning_fn warn, void *user,
                             ss_error *err) {
  *out = NULL;
  char *text = NULL, dir[SS_PATH_SIZE];
  ss_status st = ss_scene_file_read(path, "a pbrt text file", &text, dir, err);
  if (st != SS_OK) {
    return st;
  }
  st = ss_scene_parse_pbrt(text, path, dir, out, warn, user, err);
  free(text);
  return st;
}

int ss_scene_is_pbrt(const char *path) {
  size_t n = strlen(path);
  return n >= 5 && !strcmp(path + n - 5, ".pbrt");
}

ss_status ss_scene_read(const char *path, ss_scene **out, ss_scene_warning_fn warn, void *user,
                        ss_error *err) {
  return ss_scene_is_pbrt(path) ? ss_scene_read_pbrt(path, out, warn, user, err)
                                : ss_scene_read_json(path, out, err);
}
