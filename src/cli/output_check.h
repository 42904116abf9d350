/* The command line's side of core/output_plan.h: a command checks all the
 * files it will write at once, before any work, and a refusal is one line
 * and exit code 2. */
#ifndef SUBSURF_CLI_OUTPUT_CHECK_H
#define SUBSURF_CLI_OUTPUT_CHECK_H

#include "core/output_plan.h"

/* Checks and frees the plan; 0, or 2 after printing "subsurf CMD: LABEL:
 * cannot write 'PATH': WHY" (1 when out of memory). */
int ss_cli_check_outputs(ss_output_plan *p, const char *cmd);

/* The same for a command that writes one file (nothing for "-", stdout). */
int ss_cli_check_output(const char *cmd, const char *label, const char *path, ss_file_kind kind);

#endif
