/* Command-line parsing shared by the subcommands: "--name value",
 * "--name=value", "-o value" (short options are named by their letter),
 * value-less flags, positional arguments and --help/-h. Each command supplies
 * the callbacks that know its own options. No option takes an empty value.
 *
 * Every number on the command line goes through the one strict grammar of
 * subsurf/number.h (decimal, finite, nothing around it). Whole numbers use
 * the same grammar and must be integral ("1e6" is a valid path count). */
#ifndef SUBSURF_CLI_ARGS_H
#define SUBSURF_CLI_ARGS_H

#include "subsurf/arg.h"

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

/* The option parsers print "subsurf CMD: --NAME: expected ..., got 'TEXT'"
 * and return -1 on failure, 0 on success. */
int ss_parse_double(const char *cmd, const char *name, const char *text, double *out);
/* A number in [lo, hi]. */
int ss_parse_double_in(const char *cmd, const char *name, const char *text, double lo, double hi,
                       double *out);
int ss_parse_u64(const char *cmd, const char *name, const char *text, unsigned long long *out);
int ss_parse_int(const char *cmd, const char *name, const char *text, int lo, int hi, int *out);

/* Reads argument `name` of the table `args` (subsurf/arg.h, which the flat
 * interface reads too); prints "subsurf CMD: --NAME: expected ..., got
 * 'TEXT'" and returns -1 on failure, 0 on success. */
int ss_parse_arg(const char *cmd, const ss_arg *args, const char *name, const char *text,
                 double *out);

/* Splits "a,b,c" into at most `max` numbers in [lo, hi] (no empty field).
 * Returns the count, or -1 (nothing printed) when malformed. */
int ss_cli_number_list(const char *text, double lo, double hi, double *out, int max);

/* 1 when `text` is a non-empty list of non-empty names separated by any of
 * the characters in `seps` ("a,b+c"; not ",a", "a,,b" or "a+"). */
int ss_cli_name_list_ok(const char *text, const char *seps);

#endif
