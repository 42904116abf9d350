/* Command-line parsing shared by the subcommands: "--name value",
 * "--name=value", "-o value" (short options are named by their letter),
 * value-less flags, positional arguments and --help/-h. Each command supplies
 * the callbacks that know its own options. */
#ifndef SUBSURF_CLI_ARGS_H
#define SUBSURF_CLI_ARGS_H

#include <stdio.h>

typedef struct {
  /* 1 when `name` is a flag of the command (and records it), else 0. */
  int (*flag)(void *ctx, const char *name);
  /* 1 when taken, 0 when not an option of the command, -1 on a bad value
   * (the callback has printed why). */
  int (*option)(void *ctx, const char *name, const char *value);
  /* 1 when taken, 0 when unexpected; NULL when the command takes none. */
  int (*positional)(void *ctx, const char *arg);
  void (*usage)(FILE *out);
} ss_cli_spec;

/* Parses argv[first..argc-1]. Returns 0 to go on, 1 after printing the help
 * (exit 0), 2 after printing one line about bad input (exit 2). */
int ss_cli_parse(const char *cmd, int argc, char **argv, int first, const ss_cli_spec *spec,
                 void *ctx);

#endif
