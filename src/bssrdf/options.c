/* Model options by name (bssrdf.h): declarations in each model's ops, values
 * set as text from the CLI and scene files, read back by the model's create()
 * through typed getters. */
#include "subsurf/bssrdf.h"

#include "subsurf/number.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

size_t ss_bssrdf_option_count(const ss_bssrdf_ops *ops) {
  size_t n = 0;
  while (ops->options && ops->options[n].name) {
    ++n;
  }
  return n;
}

const ss_bssrdf_option *ss_bssrdf_option_find(const ss_bssrdf_ops *ops, const char *name) {
  for (size_t i = 0; name && i < ss_bssrdf_option_count(ops); ++i) {
    if (!strcmp(ops->options[i].name, name)) {
      return &ops->options[i];
    }
  }
  return NULL;
}

void ss_bssrdf_option_names(const ss_bssrdf_ops *ops, char *buf, size_t size) {
  if (size == 0) {
    return;
  }
  snprintf(buf, size, "%s", ss_bssrdf_option_count(ops) ? "" : "none");
  size_t used = strlen(buf);
  for (size_t i = 0; i < ss_bssrdf_option_count(ops) && used + 1 < size; ++i) {
    int n = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", ops->options[i].name);
    if (n < 0) {
      break;
    }
    used += (size_t)n;
  }
}

static int has_range(const ss_bssrdf_option *o) { return o->lo != 0.0 || o->hi != 0.0; }

/* "a number in (0, inf]" and the like: what a value must be. */
static void describe_kind(const ss_bssrdf_option *o, char *buf, size_t size) {
  static const char *const kinds[] = {"a number", "a whole number", "true or false", "text",
                                      "one of"};
  if (o->type == SS_BSSRDF_OPTION_CHOICE) {
    snprintf(buf, size, "one of %s", o->choices);
  } else if (has_range(o)) {
    snprintf(buf, size, "%s in %c%g, %g%c", kinds[o->type],
             o->range & SS_BSSRDF_LO_OPEN ? '(' : '[', o->lo, o->hi,
             o->range & SS_BSSRDF_HI_OPEN ? ')' : ']');
  } else {
    snprintf(buf, size, "%s", kinds[o->type]);
  }
}

void ss_bssrdf_option_describe(const ss_bssrdf_option *o, char *buf, size_t size) {
  char kind[256];
  describe_kind(o, kind, sizeof kind);
  snprintf(buf, size, "%s, default %s", kind, o->def[0] ? o->def : "none");
}

static int in_range(const ss_bssrdf_option *o, double v) {
  if (!has_range(o)) {
    return !isnan(v);
  }
  int lo_ok = o->range & SS_BSSRDF_LO_OPEN ? v > o->lo : v >= o->lo;
  int hi_ok = o->range & SS_BSSRDF_HI_OPEN ? v < o->hi : v <= o->hi;
  return lo_ok && hi_ok;
}

static int parse_bool(const char *t, double *v) {
  static const char *const yes[] = {"true", "1", "yes", "on"}, *const no[] = {"false", "0", "no",
                                                                              "off"};
  for (int i = 0; i < 4; ++i) {
    if (!strcasecmp(t, yes[i]) || !strcasecmp(t, no[i])) {
      *v = !strcasecmp(t, yes[i]);
      return 1;
    }
  }
  return 0;
}

static int parse_choice(const char *choices, const char *t, double *v) {
  size_t len = strlen(t);
  int index = 0;
  for (const char *c = choices; *c; ++index) {
    const char *bar = strchr(c, '|');
    size_t n = bar ? (size_t)(bar - c) : strlen(c);
    if (n == len && !strncmp(c, t, n)) {
      *v = index;
      return 1;
    }
    c += n + (bar != NULL);
  }
  return 0;
}

/* The number a value stands for; 0 when the text is not a valid value. */
static int parse_number(const ss_bssrdf_option *o, const char *t, double *v) {
  switch (o->type) {
  case SS_BSSRDF_OPTION_DOUBLE:
    /* number.h's grammar, plus "inf" for ranges open to infinity. */
    if (!strcmp(t, "inf")) {
      *v = INFINITY;
      return in_range(o, *v);
    }
    return ss_number_parse(t, v) && in_range(o, *v);
  case SS_BSSRDF_OPTION_INT:
    return ss_number_parse(t, v) && *v == floor(*v) && in_range(o, *v);
  case SS_BSSRDF_OPTION_BOOL:
    return parse_bool(t, v);
  case SS_BSSRDF_OPTION_CHOICE:
    return parse_choice(o->choices, t, v);
  case SS_BSSRDF_OPTION_STRING:
    *v = 0.0;
    return 1;
  }
  return 0;
}

static ss_status bad_value(const ss_bssrdf_ops *ops, const ss_bssrdf_option *o, const char *text,
                           ss_error *err) {
  char kind[256];
  describe_kind(o, kind, sizeof kind);
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: option %s: expected %s, got '%s'",
                      ops->name, o->name, kind, text);
}

static const ss_bssrdf_option *declared(const ss_bssrdf_ops *ops, const char *name, ss_error *err) {
  const ss_bssrdf_option *o = ss_bssrdf_option_find(ops, name);
  if (!o) {
    char names[512];
    ss_bssrdf_option_names(ops, names, sizeof names);
    ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: unknown option '%s' (options: %s)", ops->name,
                 name ? name : "(null)", names);
  }
  return o;
}

static ss_bssrdf_option_value *slot(ss_bssrdf_params *p, const char *name) {
  for (int i = 0; i < p->n_options; ++i) {
    if (!strcmp(p->options[i].name, name)) {
      return &p->options[i];
    }
  }
  return p->n_options < SS_BSSRDF_MAX_OPTIONS ? &p->options[p->n_options++] : NULL;
}

static ss_status store(ss_bssrdf_params *p, const ss_bssrdf_ops *ops, const ss_bssrdf_option *o,
                       double number, const char *text, ss_error *err) {
  if (strlen(text) >= SS_BSSRDF_OPTION_TEXT) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: option %s: value longer than %d bytes",
                        ops->name, o->name, SS_BSSRDF_OPTION_TEXT - 1);
  }
  ss_bssrdf_option_value *v = slot(p, o->name);
  if (!v) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: option %s: more than %d options set",
                        ops->name, o->name, SS_BSSRDF_MAX_OPTIONS);
  }
  v->name = o->name;
  v->number = number;
  snprintf(v->text, sizeof v->text, "%s", text);
  return SS_OK;
}

ss_status ss_bssrdf_params_set_option(ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                      const char *name, const char *value, ss_error *err) {
  const ss_bssrdf_option *o = declared(ops, name, err);
  if (!o) {
    return SS_ERR_INVALID_ARGUMENT;
  }
  double number;
  if (!value || !parse_number(o, value, &number)) {
    return bad_value(ops, o, value ? value : "(null)", err);
  }
  return store(p, ops, o, number, value, err);
}

ss_status ss_bssrdf_params_set_option_number(ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                             const char *name, double value, ss_error *err) {
  const ss_bssrdf_option *o = declared(ops, name, err);
  if (!o) {
    return SS_ERR_INVALID_ARGUMENT;
  }
  char text[64];
  snprintf(text, sizeof text, "%.17g", value);
  int ok = o->type == SS_BSSRDF_OPTION_DOUBLE ||
           (o->type == SS_BSSRDF_OPTION_INT && value == floor(value)) ||
           (o->type == SS_BSSRDF_OPTION_BOOL && (value == 0.0 || value == 1.0));
  if (!ok || !in_range(o, value)) {
    return bad_value(ops, o, text, err);
  }
  return store(p, ops, o, value, text, err);
}

void ss_bssrdf_params_clear_options(ss_bssrdf_params *p) {
  p->n_options = 0;
  memset(p->options, 0, sizeof p->options);
}

ss_status ss_bssrdf_params_check_options(const ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                         ss_error *err) {
  for (int i = 0; i < p->n_options; ++i) {
    const ss_bssrdf_option *o = declared(ops, p->options[i].name, err);
    if (!o) {
      return SS_ERR_INVALID_ARGUMENT;
    }
    double number;
    if (!parse_number(o, p->options[i].text, &number)) {
      return bad_value(ops, o, p->options[i].text, err);
    }
  }
  return SS_OK;
}

static const ss_bssrdf_option_value *find_value(const ss_bssrdf_params *p, const char *name) {
  for (int i = 0; i < p->n_options; ++i) {
    if (!strcmp(p->options[i].name, name)) {
      return &p->options[i];
    }
  }
  return NULL;
}

/* The value's number, or the default's (declarations are checked by the
 * registry test, so a default always parses). */
static double number_of(const ss_bssrdf_params *p, const ss_bssrdf_option *opt) {
  const ss_bssrdf_option_value *v = find_value(p, opt->name);
  double number = 0.0;
  if (v) {
    return v->number;
  }
  parse_number(opt, opt->def, &number);
  return number;
}

double ss_bssrdf_params_double(const ss_bssrdf_params *p, const ss_bssrdf_option *opt) {
  return number_of(p, opt);
}

int ss_bssrdf_params_int(const ss_bssrdf_params *p, const ss_bssrdf_option *opt) {
  return (int)number_of(p, opt);
}

int ss_bssrdf_params_bool(const ss_bssrdf_params *p, const ss_bssrdf_option *opt) {
  return number_of(p, opt) != 0.0;
}

int ss_bssrdf_params_choice(const ss_bssrdf_params *p, const ss_bssrdf_option *opt) {
  return (int)number_of(p, opt);
}

const char *ss_bssrdf_params_string(const ss_bssrdf_params *p, const ss_bssrdf_option *opt) {
  const ss_bssrdf_option_value *v = find_value(p, opt->name);
  return v ? v->text : opt->def;
}
