/* The flat interface's number arguments (ffi.h): the command line's own
 * tables, read from text with the command line's words. */
#include "subsurf/ffi.h"

#include "subsurf/halfspace.h"
#include "subsurf/render.h"

#include <stdio.h>
#include <string.h>

int ss_ffi_arg_parse(const char *command, const char *name, const char *text, double *value,
                     char *err, size_t err_size) {
  const ss_arg *table = NULL;
  if (command && !strcmp(command, "halfspace")) {
    table = ss_halfspace_args;
  } else if (command && !strcmp(command, "render")) {
    table = ss_render_args;
  }
  const ss_arg *a = table ? ss_arg_find(table, name) : NULL;
  ss_error e;
  ss_status st = SS_ERR_INVALID_ARGUMENT;
  if (!a) {
    ss_error_set(&e, st, "no number argument '%s' of '%s'", name ? name : "(null)",
                 command ? command : "(null)");
  } else if (!text) {
    ss_error_set(&e, st, "no text given");
  } else {
    st = ss_arg_parse(a, text, value, &e);
  }
  if (st != SS_OK && err && err_size > 0) {
    snprintf(err, err_size, "%s", e.message);
  }
  return (int)st;
}
