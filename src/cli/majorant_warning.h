/* The render command's warning about media whose delta or ratio tracking
 * met sigma_t above the majorant (volume.h): the image is biased then. */
#ifndef SUBSURF_CLI_MAJORANT_WARNING_H
#define SUBSURF_CLI_MAJORANT_WARNING_H

#include "subsurf/scene.h"

#include <stdio.h>

/* One line on `out` per medium of `scene` with a non-zero count, prefixed
 * "subsurf COMMAND: warning:"; returns the number of such media. */
int ss_cli_warn_majorant(FILE *out, const char *command, const ss_scene *scene);

#endif
