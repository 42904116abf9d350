/* Stack files of `subsurf layer --stack` (private to src/io and the CLI): a
 * JSON object with the layers from the top, each its optical depth and
 * albedo or its coefficients and thickness, its phase function, and
 * optionally the top face's index and the bottom (docs/layer.md). */
#ifndef SUBSURF_IO_LAYER_STACK_H
#define SUBSURF_IO_LAYER_STACK_H

#include "subsurf/layer.h"

/* "same", "index-matched" or "diffuse:A" (A in [0, 1]); 1 when valid. */
int ss_layer_bottom_parse(const char *text, ss_layer_bottom *bottom, double *albedo);
/* The name ss_layer_bottom_parse reads ("diffuse" without the albedo). */
const char *ss_layer_bottom_name(ss_layer_bottom bottom);

/* Reads `path` into p's layers (and its eta and bottom where the file has
 * them: *eta_set, *bottom_set). Errors read "FILE:LINE: KEY: what". */
ss_status ss_layer_stack_read(const char *path, ss_layer_params *p, int *eta_set, int *bottom_set,
                              ss_error *err);

#endif
