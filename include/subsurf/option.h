/* Typed options declared by the code that reads them: BSSRDF models
 * (bssrdf.h) and integrators (integrator.h) each list theirs, and
 * everything outside (the CLI, scene files, Python) sets them by name, as
 * text, through one contract, so that no reader knows a model or an
 * integrator by name.
 *
 * Option names are snake_case ("beam_samples"): scene files use them as
 * keys, the CLI as --kebab-case ("--beam-samples"). Values are text:
 *   double  a number, "inf"/"-inf" allowed when the range allows
 *   int     a whole number
 *   bool    true|false|1|0|yes|no|on|off
 *   string  any text (e.g. a file path, meta "FILE"; "" for none)
 *   choice  one of `choices` ("a|b|c"); the getter returns its index */
#ifndef SUBSURF_OPTION_H
#define SUBSURF_OPTION_H

#include "subsurf/status.h"

#include <stddef.h>

typedef enum {
  SS_OPTION_DOUBLE,
  SS_OPTION_INT,
  SS_OPTION_BOOL,
  SS_OPTION_STRING,
  SS_OPTION_CHOICE,
} ss_option_type;

/* Range flags: exclusive ends of [lo, hi]. */
enum {
  SS_OPTION_LO_OPEN = 1u << 0,
  SS_OPTION_HI_OPEN = 1u << 1,
};

/* One declared option; a list ends with an entry whose name is NULL. */
typedef struct {
  const char *name;
  ss_option_type type;
  const char *def;     /* the default, written as a value */
  double lo, hi;       /* range of double and int options (both 0: none) */
  unsigned range;      /* SS_OPTION_LO_OPEN | SS_OPTION_HI_OPEN */
  const char *choices; /* choice options: "a|b|c" */
  const char *help;    /* one line for --help and docs */
  const char *meta;    /* the value's name in --help ("FILE"); NULL: from the type */
} ss_option;

#define SS_OPTION_TEXT 1024

/* A value set by name: the declaration's name, the parsed number (double,
 * int, bool 0/1, choice index) and the text as given. */
typedef struct {
  const char *name;
  double number;
  char text[SS_OPTION_TEXT];
} ss_option_value;

size_t ss_option_count(const ss_option *list);
/* The declaration of option `name` in `list`, NULL when it has none. */
const ss_option *ss_option_find(const ss_option *list, const char *name);
/* "a, b, c" (the option names) for error messages; "none" when none. */
void ss_option_names(const ss_option *list, char *buf, size_t size);
/* "a whole number in [6, 384]": what a value must be. */
void ss_option_expected(const ss_option *o, char *buf, size_t size);
/* "a whole number in [6, 384], default 100" for --help and error messages. */
void ss_option_describe(const ss_option *o, char *buf, size_t size);
/* 1 and the value's number when `text` is a valid value of `o`, else 0. */
int ss_option_parse(const ss_option *o, const char *text, double *number);
/* 1 when the number is a valid value of a double, int or bool option. */
int ss_option_number_ok(const ss_option *o, double value);

/* Setting by name into `values`, of which `*n` are set and at most `max`
 * fit (`owner` names the model or integrator in messages): fails
 * (SS_ERR_INVALID_ARGUMENT) for a name `list` does not declare ("pbd:
 * unknown option 'thicknes' (options: beam_samples)") or a value of the
 * wrong type or out of range ("pbd: option beam_samples: expected a whole
 * number in [6, 384], got '3'"). Setting a name again replaces the value. */
ss_status ss_option_set(ss_option_value *values, int *n, int max, const char *owner,
                        const ss_option *list, const char *name, const char *value, ss_error *err);
/* For double, int and bool options (bool: 0 or 1). */
ss_status ss_option_set_number(ss_option_value *values, int *n, int max, const char *owner,
                               const ss_option *list, const char *name, double value,
                               ss_error *err);
/* SS_OK when every value set is declared by `list` and valid. */
ss_status ss_option_check(const ss_option_value *values, int n, const char *owner,
                          const ss_option *list, ss_error *err);

/* Typed getters: the value set under opt->name, or opt->def. */
const ss_option_value *ss_option_value_find(const ss_option_value *values, int n, const char *name);
double ss_option_get_number(const ss_option_value *values, int n, const ss_option *opt);
/* The text set, or opt->def ("" when the option is empty). */
const char *ss_option_get_text(const ss_option_value *values, int n, const ss_option *opt);

#endif
