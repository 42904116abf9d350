/* pbrt-v3 parameter lists: "TYPE NAME" followed by a value or a bracketed
 * array of numbers or strings, up to the next directive (pbrt.h). */
#include "io/pbrt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* pbrt-v3's parameter types; "point", "vector", "normal" and "color" are
 * its spellings of point3, vector3, normal3 and rgb. */
static const char *const number_types[] = {"integer", "float",   "point2", "vector2",   "point3",
                                           "vector3", "normal3", "normal", "point",     "vector",
                                           "rgb",     "color",   "xyz",    "blackbody", NULL};
static const char *const string_types[] = {"string", "texture", "bool", NULL};

static int in_list(const char *s, const char *const *list) {
  for (; *list; ++list) {
    if (!strcmp(s, *list)) {
      return 1;
    }
  }
  return 0;
}

void ss_pbrt_params_free(ss_pbrt_params *ps) {
  for (size_t i = 0; i < ps->n; ++i) {
    free(ps->items[i].nums);
    for (size_t k = 0; k < ps->items[i].num_strs; ++k) {
      free(ps->items[i].strs[k]);
    }
    free(ps->items[i].strs);
  }
  free(ps->items);
  ps->items = NULL;
  ps->n = 0;
}

static int push_number(ss_pbrt *P, ss_pbrt_param *p, size_t *cap, double v) {
  if (p->num_nums == *cap) {
    size_t c = *cap ? 2 * *cap : 16;
    double *grown = realloc(p->nums, c * sizeof *grown);
    if (!grown) {
      ss_pbrt_fail(P, P->lex->file, p->line, "out of memory");
      return 0;
    }
    p->nums = grown;
    *cap = c;
  }
  p->nums[p->num_nums++] = v;
  return 1;
}

static int push_string(ss_pbrt *P, ss_pbrt_param *p, const char *s) {
  char **grown = realloc(p->strs, (p->num_strs + 1) * sizeof *grown);
  char *copy = grown ? strdup(s) : NULL;
  if (!copy) {
    if (grown) {
      p->strs = grown;
    }
    ss_pbrt_fail(P, P->lex->file, p->line, "out of memory");
    return 0;
  }
  p->strs = grown;
  p->strs[p->num_strs++] = copy;
  return 1;
}

/* One value token into p: a number or a string (a bare true/false for
 * bool, as pbrt-v4 writes it). */
static int add_value(ss_pbrt *P, ss_pbrt_param *p, size_t *cap, const ss_pbrt_token *t) {
  int numeric = in_list(p->type, number_types) || !strcmp(p->type, "spectrum");
  int bare_bool = t->kind == SS_PBRT_WORD && !strcmp(p->type, "bool") &&
                  (!strcmp(t->text, "true") || !strcmp(t->text, "false"));
  if (t->kind == SS_PBRT_NUMBER && numeric && !p->num_strs) {
    return push_number(P, p, cap, t->number);
  }
  if ((t->kind == SS_PBRT_STRING && !numeric && !p->num_nums) || bare_bool ||
      (t->kind == SS_PBRT_STRING && !strcmp(p->type, "spectrum") && !p->num_nums)) {
    return push_string(P, p, t->text);
  }
  ss_pbrt_fail(P, P->lex->file, t->line, "parameter \"%s %s\": expected %s, got '%s'", p->type,
               p->name, numeric ? "numbers" : "quoted strings",
               t->kind == SS_PBRT_EOF ? "end of file" : t->text);
  return 0;
}

static void read_param(ss_pbrt *P, ss_pbrt_params *ps, const ss_pbrt_token *decl) {
  ss_pbrt_param p;
  memset(&p, 0, sizeof p);
  p.line = decl->line;
  char extra[8] = "";
  int n = sscanf(decl->text, "%31s %63s %7s", p.type, p.name, extra);
  if (n != 2) {
    ss_pbrt_fail(P, P->lex->file, decl->line,
                 "expected a parameter declaration \"TYPE NAME\", got \"%s\"", decl->text);
    return;
  }
  if (!in_list(p.type, number_types) && !in_list(p.type, string_types) &&
      strcmp(p.type, "spectrum")) {
    ss_pbrt_fail(P, P->lex->file, decl->line,
                 "unknown parameter type '%s' in \"%s\" (integer, float, point2, vector2, "
                 "point3, vector3, normal3, point, vector, normal, rgb, color, xyz, blackbody, "
                 "spectrum, bool, string, texture)",
                 p.type, decl->text);
    return;
  }
  ss_pbrt_param *grown = realloc(ps->items, (ps->n + 1) * sizeof *grown);
  if (!grown) {
    ss_pbrt_fail(P, P->lex->file, decl->line, "out of memory");
    return;
  }
  ps->items = grown;
  ss_pbrt_param *q = &ps->items[ps->n++];
  *q = p;
  size_t cap = 0;
  ss_pbrt_token t;
  ss_pbrt_next(P, &t);
  if (t.kind != SS_PBRT_LBRACKET) {
    add_value(P, q, &cap, &t);
    return;
  }
  for (;;) {
    ss_pbrt_next(P, &t);
    if (P->st != SS_OK || t.kind == SS_PBRT_RBRACKET) {
      break;
    }
    if (t.kind == SS_PBRT_EOF || t.kind == SS_PBRT_LBRACKET ||
        (t.kind == SS_PBRT_WORD && strcmp(q->type, "bool"))) {
      ss_pbrt_fail(P, P->lex->file, t.line,
                   "parameter \"%s %s\": expected ']' to close the "
                   "array opened on line %d, got %s",
                   q->type, q->name, decl->line, t.kind == SS_PBRT_EOF ? "end of file" : t.text);
      break;
    }
    if (!add_value(P, q, &cap, &t)) {
      break;
    }
  }
}

void ss_pbrt_params_read(ss_pbrt *P, ss_pbrt_params *ps) {
  ps->n = 0;
  ps->items = NULL;
  ss_pbrt_token t;
  for (;;) {
    ss_pbrt_peek(P, &t);
    if (P->st != SS_OK || t.kind != SS_PBRT_STRING) {
      return;
    }
    ss_pbrt_next(P, &t);
    read_param(P, ps, &t);
  }
}

void ss_pbrt_params_report(ss_pbrt *P, const ss_pbrt_params *ps, const char *what) {
  for (size_t i = 0; P->st == SS_OK && i < ps->n; ++i) {
    if (!ps->items[i].used) {
      ss_pbrt_warn(P, ps->file, ps->items[i].line,
                   "%s: parameter \"%s %s\" is not supported (ignored)", what, ps->items[i].type,
                   ps->items[i].name);
    }
  }
}

/* The parameter `name`, marked used; NULL when absent. */
static ss_pbrt_param *find(ss_pbrt *P, ss_pbrt_params *ps, const char *name) {
  if (P->st != SS_OK) {
    return NULL;
  }
  for (size_t i = ps->n; i-- > 0;) {
    if (!strcmp(ps->items[i].name, name)) {
      ps->items[i].used = 1;
      return &ps->items[i];
    }
  }
  return NULL;
}

static int expect(ss_pbrt *P, ss_pbrt_params *ps, const ss_pbrt_param *p, const char *const *types,
                  size_t count) {
  if (!in_list(p->type, types)) {
    ss_pbrt_fail(P, ps->file, p->line, "parameter \"%s %s\": expected type %s%s", p->type, p->name,
                 types[0], types[1] ? " or a synonym" : "");
    return 0;
  }
  size_t have = p->num_nums + p->num_strs;
  if (count && have != count) {
    ss_pbrt_fail(P, ps->file, p->line, "parameter \"%s %s\": expected %zu value%s, got %zu",
                 p->type, p->name, count, count > 1 ? "s" : "", have);
    return 0;
  }
  return 1;
}

int ss_pbrt_float(ss_pbrt *P, ss_pbrt_params *ps, const char *name, double *out) {
  static const char *const types[] = {"float", "integer", NULL};
  ss_pbrt_param *p = find(P, ps, name);
  if (!p || !expect(P, ps, p, types, 1)) {
    return 0;
  }
  *out = p->nums[0];
  return 1;
}

int ss_pbrt_int(ss_pbrt *P, ss_pbrt_params *ps, const char *name, long lo, long hi, long *out) {
  static const char *const types[] = {"integer", NULL};
  ss_pbrt_param *p = find(P, ps, name);
  if (!p || !expect(P, ps, p, types, 1)) {
    return 0;
  }
  double v = p->nums[0];
  if (!(v >= (double)lo && v <= (double)hi) || v != floor(v)) {
    ss_pbrt_fail(P, ps->file, p->line,
                 "parameter \"integer %s\": expected a whole number in "
                 "[%ld, %ld], got %g",
                 name, lo, hi, v);
    return 0;
  }
  *out = (long)v;
  return 1;
}

int ss_pbrt_bool(ss_pbrt *P, ss_pbrt_params *ps, const char *name, int *out) {
  static const char *const types[] = {"bool", NULL};
  ss_pbrt_param *p = find(P, ps, name);
  if (!p || !expect(P, ps, p, types, 1)) {
    return 0;
  }
  if (strcmp(p->strs[0], "true") && strcmp(p->strs[0], "false")) {
    ss_pbrt_fail(P, ps->file, p->line,
                 "parameter \"bool %s\": expected \"true\" or \"false\", "
                 "got \"%s\"",
                 name, p->strs[0]);
    return 0;
  }
  *out = !strcmp(p->strs[0], "true");
  return 1;
}

int ss_pbrt_string(ss_pbrt *P, ss_pbrt_params *ps, const char *name, char *out, size_t size) {
  static const char *const types[] = {"string", NULL};
  ss_pbrt_param *p = find(P, ps, name);
  if (!p || !expect(P, ps, p, types, 1)) {
    return 0;
  }
  if (strlen(p->strs[0]) >= size) {
    ss_pbrt_fail(P, ps->file, p->line, "parameter \"string %s\": longer than %zu bytes", name,
                 size - 1);
    return 0;
  }
  snprintf(out, size, "%s", p->strs[0]);
  return 1;
}

int ss_pbrt_point(ss_pbrt *P, ss_pbrt_params *ps, const char *name, ss_vec3 *out) {
  static const char *const types[] = {"point",  "point3",  "vector", "vector3",
                                      "normal", "normal3", NULL};
  ss_pbrt_param *p = find(P, ps, name);
  if (!p || !expect(P, ps, p, types, 3)) {
    return 0;
  }
  *out = ss_vec3_make(p->nums[0], p->nums[1], p->nums[2]);
  return 1;
}

/* A spectrum of (wavelength, value) pairs or a file: its mean value, the
 * closest grey (subsurf renders in RGB). */
static int approximate_spectrum(ss_pbrt *P, ss_pbrt_params *ps, const ss_pbrt_param *p,
                                ss_rgb *out) {
  if (p->num_strs) {
    ss_pbrt_warn(P, ps->file, p->line,
                 "parameter \"spectrum %s\": spectrum files are not read "
                 "(ignored; the default value is used)",
                 p->name);
    return 0;
  }
  if (p->num_nums < 2 || p->num_nums % 2) {
    ss_pbrt_fail(P, ps->file, p->line,
                 "parameter \"spectrum %s\": expected (wavelength, value) "
                 "pairs",
                 p->name);
    return 0;
  }
  double sum = 0.0;
  for (size_t i = 1; i < p->num_nums; i += 2) {
    sum += p->nums[i];
  }
  double mean = sum / (double)(p->num_nums / 2);
  ss_pbrt_warn(P, ps->file, p->line,
               "parameter \"spectrum %s\": approximated by the grey of its mean value %g", p->name,
               mean);
  *out = ss_rgb_gray(mean);
  return 1;
}

int ss_pbrt_rgb(ss_pbrt *P, ss_pbrt_params *ps, const char *name, ss_rgb *out) {
  static const char *const types[] = {"rgb", "color", "spectrum", "blackbody", "float", NULL};
  ss_pbrt_param *p = find(P, ps, name);
  if (!p || !expect(P, ps, p, types, 0)) {
    return 0;
  }
  if (!strcmp(p->type, "spectrum")) {
    return approximate_spectrum(P, ps, p, out);
  }
  if (!strcmp(p->type, "blackbody")) {
    if (p->num_nums < 1 || p->num_nums > 2) {
      ss_pbrt_fail(P, ps->file, p->line,
                   "parameter \"blackbody %s\": expected [temperature] or "
                   "[temperature scale]",
                   name);
      return 0;
    }
    double scale = p->num_nums == 2 ? p->nums[1] : 1.0;
    ss_pbrt_warn(P, ps->file, p->line,
                 "parameter \"blackbody %s\": approximated by white of value %g (subsurf has no "
                 "spectral emission)",
                 name, scale);
    *out = ss_rgb_gray(scale);
    return 1;
  }
  if (!strcmp(p->type, "float")) {
    if (p->num_nums != 1) {
      ss_pbrt_fail(P, ps->file, p->line, "parameter \"float %s\": expected 1 value", name);
      return 0;
    }
    *out = ss_rgb_gray(p->nums[0]);
    return 1;
  }
  if (p->num_nums != 3) {
    ss_pbrt_fail(P, ps->file, p->line, "parameter \"%s %s\": expected 3 values, got %zu", p->type,
                 name, p->num_nums);
    return 0;
  }
  *out = ss_rgb_make(p->nums[0], p->nums[1], p->nums[2]);
  return 1;
}

const ss_pbrt_param *ss_pbrt_array(ss_pbrt *P, ss_pbrt_params *ps, const char *name,
                                   const char *const *types) {
  ss_pbrt_param *p = find(P, ps, name);
  if (!p || !expect(P, ps, p, types, 0)) {
    return NULL;
  }
  return p;
}

int ss_pbrt_texturable(ss_pbrt *P, ss_pbrt_params *ps, const char *name, int is_float,
                       ss_rgb *value, const ss_texture **tex) {
  *tex = NULL;
  ss_pbrt_param *p = find(P, ps, name);
  if (!p) {
    return 0;
  }
  if (strcmp(p->type, "texture")) {
    p->used = 0;
    if (is_float) {
      double v = 0.0;
      int got = ss_pbrt_float(P, ps, name, &v);
      *value = ss_rgb_gray(v);
      return got;
    }
    return ss_pbrt_rgb(P, ps, name, value);
  }
  if (p->num_strs != 1) {
    ss_pbrt_fail(P, ps->file, p->line, "parameter \"texture %s\": expected one texture name", name);
    return 0;
  }
  for (size_t i = P->num_textures; i-- > 0;) {
    const ss_pbrt_texture *t = &P->textures[i];
    if (!strcmp(t->name, p->strs[0]) && t->is_float == is_float) {
      *value = t->value;
      *tex = t->tex;
      return 1;
    }
  }
  ss_pbrt_fail(P, ps->file, p->line, "parameter \"texture %s\": no %s texture named \"%s\"", name,
               is_float ? "float" : "spectrum", p->strs[0]);
  return 0;
}
