#include "cli/args.h"

#include "subsurf/number.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int ss_cli_parse(const char *cmd, int argc, char **argv, int first, const ss_cli_spec *spec,
                 void *ctx) {
  for (int i = first; i < argc; ++i) {
    const char *arg = argv[i];
    if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
      spec->usage(stdout);
      return 1;
    }
    if (arg[0] != '-' || arg[1] == '\0') {
      if (spec->positional && spec->positional(ctx, arg)) {
        continue;
      }
      fprintf(stderr, "subsurf %s: unexpected argument '%s' (see --help)\n", cmd, arg);
      return 2;
    }
    int is_long = arg[1] == '-';
    const char *body = arg + (is_long ? 2 : 1);
    const char *eq = is_long ? strchr(body, '=') : NULL;
    char name[64];
    snprintf(name, sizeof name, "%.*s", eq ? (int)(eq - body) : (int)strlen(body), body);
    if (!eq && spec->flag && spec->flag(ctx, name)) {
      continue;
    }
    const char *value;
    if (eq) {
      value = eq + 1;
    } else if (i + 1 < argc) {
      value = argv[++i];
    } else {
      fprintf(stderr, "subsurf %s: %s: missing value (or unknown flag; see --help)\n", cmd, arg);
      return 2;
    }
    if (value[0] == '\0') { /* no option takes an empty text (a file, a list, a number) */
      fprintf(stderr, "subsurf %s: %s%s: expected a value, got an empty text\n", cmd,
              is_long ? "--" : "-", name);
      return 2;
    }
    int rc = spec->option(ctx, name, value);
    if (rc == 0) {
      fprintf(stderr, "subsurf %s: unknown option '%s%s' (see --help)\n", cmd, is_long ? "--" : "-",
              name);
      return 2;
    }
    if (rc < 0) {
      return 2;
    }
  }
  return 0;
}

int ss_parse_double(const char *cmd, const char *name, const char *text, double *out) {
  if (!ss_number_parse(text, out)) {
    fprintf(stderr, "subsurf %s: --%s: expected a finite decimal number, got '%s'\n", cmd, name,
            text);
    return -1;
  }
  return 0;
}

int ss_parse_double_in(const char *cmd, const char *name, const char *text, double lo, double hi,
                       double *out) {
  double v;
  if (!ss_number_parse(text, &v) || !(v >= lo && v <= hi)) {
    fprintf(stderr, "subsurf %s: --%s: expected a number in [%g, %g], got '%s'\n", cmd, name, lo,
            hi, text);
    return -1;
  }
  *out = v;
  return 0;
}

int ss_parse_u64(const char *cmd, const char *name, const char *text, unsigned long long *out) {
  double v;
  /* 2^64 is the first double above the range of unsigned long long. */
  if (!ss_number_parse(text, &v) || !(v >= 0.0) || v >= 0x1p64 || v != floor(v)) {
    fprintf(stderr, "subsurf %s: --%s: expected a whole number >= 0, got '%s'\n", cmd, name, text);
    return -1;
  }
  *out = (unsigned long long)v;
  return 0;
}

int ss_parse_int(const char *cmd, const char *name, const char *text, int lo, int hi, int *out) {
  double v;
  if (!ss_number_parse(text, &v) || !(v >= lo && v <= hi) || v != floor(v)) {
    fprintf(stderr, "subsurf %s: --%s: expected a whole number in [%d, %d], got '%s'\n", cmd, name,
            lo, hi, text);
    return -1;
  }
  *out = (int)v;
  return 0;
}

int ss_parse_arg(const char *cmd, const ss_arg *args, const char *name, const char *text,
                 double *out) {
  const ss_arg *a = ss_arg_find(args, name);
  ss_error err;
  if (!a) {
    fprintf(stderr, "subsurf %s: --%s: not a number argument\n", cmd, name);
    return -1;
  }
  if (ss_arg_parse(a, text, out, &err) != SS_OK) {
    fprintf(stderr, "subsurf %s: --%s: %s\n", cmd, name, err.message);
    return -1;
  }
  return 0;
}

int ss_cli_number_list(const char *text, double lo, double hi, double *out, int max) {
  int n = 0;
  for (const char *s = text;; ++n) {
    const char *comma = strchr(s, ',');
    size_t len = comma ? (size_t)(comma - s) : strlen(s);
    double v;
    if (n == max || !ss_number_parse_n(s, len, &v) || !(v >= lo && v <= hi)) {
      return -1;
    }
    out[n] = v;
    if (!comma) {
      return n + 1;
    }
    s = comma + 1;
  }
}

int ss_cli_name_list_ok(const char *text, const char *seps) {
  size_t run = 0;
  for (const char *c = text;; ++c) {
    if (*c == '\0' || strchr(seps, *c)) {
      if (run == 0) {
        return 0;
      }
      if (*c == '\0') {
        return 1;
      }
      run = 0;
    } else {
      ++run;
    }
  }
}
