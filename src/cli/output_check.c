#include "cli/output_check.h"

#include <stdio.h>

int ss_cli_check_outputs(ss_output_plan *p, const char *cmd) {
  ss_error err;
  ss_status st = ss_output_plan_check(p, &err);
  ss_output_plan_free(p);
  if (st != SS_OK) {
    fprintf(stderr, "subsurf %s: %s\n", cmd, err.message);
    return st == SS_ERR_NO_MEMORY ? 1 : 2;
  }
  return 0;
}

int ss_cli_check_output(const char *cmd, const char *label, const char *path, ss_file_kind kind) {
  ss_output_plan p;
  ss_output_plan_init(&p);
  ss_output_plan_add(&p, label, path, kind, 0, 0);
  return ss_cli_check_outputs(&p, cmd);
}
