#include "cli/args.h"

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
    int rc = spec->option(ctx, name, value);
    if (rc == 0) {
      fprintf(stderr, "subsurf %s: unknown option '%s%s' (see --help)\n", cmd,
              is_long ? "--" : "-", name);
      return 2;
    }
    if (rc < 0) {
      return 2;
    }
  }
  return 0;
}
