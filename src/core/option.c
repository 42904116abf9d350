/* Typed options by name (option.h): declarations in the code that reads
 * them, values set as text from the CLI and scene files, read back through
 * typed getters. */
#include "subsurf/option.h"

#include "subsurf/number.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

size_t ss_option_count(const ss_option *list) {
  size_t n = 0;
  while (list && list[n].name) {
    ++n;
  }
  return n;
}

const ss_option *ss_option_find(const ss_option *list, const char *name) {
  for (size_t i = 0; name && i < ss_option_count(list); ++i) {
    if (!strcmp(list[i].name, name)) {
      return &list[i];
    }
  }
  return NULL;
}

void ss_option_names(const ss_option *list, char *buf, size_t size) {
  if (size == 0) {
    return;
  }
  size_t count = ss_option_count(list);
  snprintf(buf, size, "%s", count ? "" : "none");
  size_t used = strlen(buf);
  for (size_t i = 0; i < count && used + 1 < size; ++i) {
    int n = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", list[i].name);
    if (n < 0) {
      break;
    }
    used += (size_t)n;
  }
}

static int has_range(const ss_option *o) { return o->lo != 0.0 || o->hi != 0.0; }

void ss_option_expected(const ss_option *o, char *buf, size_t size) {
  static const char *const kinds[] = {"a number", "a whole number", "true or false", "text",
                                      "one of"};
  if (o->type == SS_OPTION_CHOICE) {
    snprintf(buf, size, "one of %s", o->choices);
  } else if (has_range(o)) {
    /* A whole number's bounds in full (100000000, not 1e+08). */
    char lo[32], hi[32];
    if (o->type == SS_OPTION_INT) {
      ss_number_format(o->lo, lo, sizeof lo);
      ss_number_format(o->hi, hi, sizeof hi);
    } else {
      snprintf(lo, sizeof lo, "%g", o->lo);
      snprintf(hi, sizeof hi, "%g", o->hi);
    }
    snprintf(buf, size, "%s in %c%s, %s%c", kinds[o->type],
             o->range & SS_OPTION_LO_OPEN ? '(' : '[', lo, hi,
             o->range & SS_OPTION_HI_OPEN ? ')' : ']');
  } else {
    snprintf(buf, size, "%s", kinds[o->type]);
  }
}

void ss_option_describe(const ss_option *o, char *buf, size_t size) {
  char kind[256];
  ss_option_expected(o, kind, sizeof kind);
  snprintf(buf, size, "%s, default %s", kind, o->def[0] ? o->def : "none");
}

static int in_range(const ss_option *o, double v) {
  if (!has_range(o)) {
    return !isnan(v);
  }
  int lo_ok = o->range & SS_OPTION_LO_OPEN ? v > o->lo : v >= o->lo;
  int hi_ok = o->range & SS_OPTION_HI_OPEN ? v < o->hi : v <= o->hi;
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

int ss_option_parse(const ss_option *o, const char *t, double *v) {
  switch (o->type) {
  case SS_OPTION_DOUBLE:
    /* number.h's grammar, plus "inf" for ranges open to infinity. */
    if (!strcmp(t, "inf")) {
      *v = INFINITY;
      return in_range(o, *v);
    }
    return ss_number_parse(t, v) && in_range(o, *v);
  case SS_OPTION_INT:
    return ss_number_parse(t, v) && *v == floor(*v) && in_range(o, *v);
  case SS_OPTION_BOOL:
    return parse_bool(t, v);
  case SS_OPTION_CHOICE:
    return parse_choice(o->choices, t, v);
  case SS_OPTION_STRING:
    *v = 0.0;
    return 1;
  }
  return 0;
}

int ss_option_number_ok(const ss_option *o, double value) {
  int ok = o->type == SS_OPTION_DOUBLE || (o->type == SS_OPTION_INT && value == floor(value)) ||
           (o->type == SS_OPTION_BOOL && (value == 0.0 || value == 1.0));
  return ok && in_range(o, value);
}

static ss_status bad_value(const char *owner, const ss_option *o, const char *text, ss_error *err) {
  char kind[256];
  ss_option_expected(o, kind, sizeof kind);
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: option %s: expected %s, got '%s'", owner,
                      o->name, kind, text);
}

static const ss_option *declared(const char *owner, const ss_option *list, const char *name,
                                 ss_error *err) {
  const ss_option *o = ss_option_find(list, name);
  if (!o) {
    char names[512];
    ss_option_names(list, names, sizeof names);
    ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: unknown option '%s' (options: %s)", owner,
                 name ? name : "(null)", names);
  }
  return o;
}

static ss_option_value *slot(ss_option_value *values, int *n, int max, const char *name) {
  for (int i = 0; i < *n; ++i) {
    if (!strcmp(values[i].name, name)) {
      return &values[i];
    }
  }
  return *n < max ? &values[(*n)++] : NULL;
}

static ss_status store(ss_option_value *values, int *n, int max, const char *owner,
                       const ss_option *o, double number, const char *text, ss_error *err) {
  if (strlen(text) >= SS_OPTION_TEXT) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: option %s: value longer than %d bytes",
                        owner, o->name, SS_OPTION_TEXT - 1);
  }
  ss_option_value *v = slot(values, n, max, o->name);
  if (!v) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: option %s: more than %d options set",
                        owner, o->name, max);
  }
  v->name = o->name;
  v->number = number;
  snprintf(v->text, sizeof v->text, "%s", text);
  return SS_OK;
}

ss_status ss_option_set(ss_option_value *values, int *n, int max, const char *owner,
                        const ss_option *list, const char *name, const char *value, ss_error *err) {
  const ss_option *o = declared(owner, list, name, err);
  if (!o) {
    return SS_ERR_INVALID_ARGUMENT;
  }
  double number;
  if (!value || !ss_option_parse(o, value, &number)) {
    return bad_value(owner, o, value ? value : "(null)", err);
  }
  return store(values, n, max, owner, o, number, value, err);
}

ss_status ss_option_set_number(ss_option_value *values, int *n, int max, const char *owner,
                               const ss_option *list, const char *name, double value,
                               ss_error *err) {
  const ss_option *o = declared(owner, list, name, err);
  if (!o) {
    return SS_ERR_INVALID_ARGUMENT;
  }
  char text[64];
  snprintf(text, sizeof text, "%.17g", value);
  if (!ss_option_number_ok(o, value)) {
    return bad_value(owner, o, text, err);
  }
  return store(values, n, max, owner, o, value, text, err);
}

ss_status ss_option_check(const ss_option_value *values, int n, const char *owner,
                          const ss_option *list, ss_error *err) {
  for (int i = 0; i < n; ++i) {
    const ss_option *o = declared(owner, list, values[i].name, err);
    if (!o) {
      return SS_ERR_INVALID_ARGUMENT;
    }
    double number;
    if (!ss_option_parse(o, values[i].text, &number)) {
      return bad_value(owner, o, values[i].text, err);
    }
  }
  return SS_OK;
}

const ss_option_value *ss_option_value_find(const ss_option_value *values, int n,
                                            const char *name) {
  for (int i = 0; i < n; ++i) {
    if (!strcmp(values[i].name, name)) {
      return &values[i];
    }
  }
  return NULL;
}

/* The value's number, or the default's (declarations are checked by the
 * registry tests, so a default always parses). */
double ss_option_get_number(const ss_option_value *values, int n, const ss_option *opt) {
  const ss_option_value *v = ss_option_value_find(values, n, opt->name);
  double number = 0.0;
  if (v) {
    return v->number;
  }
  ss_option_parse(opt, opt->def, &number);
  return number;
}

const char *ss_option_get_text(const ss_option_value *values, int n, const ss_option *opt) {
  const ss_option_value *v = ss_option_value_find(values, n, opt->name);
  return v ? v->text : opt->def;
}
