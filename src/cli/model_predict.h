/* What a BSSRDF model predicts for the half-space experiment, in the shape of
 * a half-space result (same bins, same JSON keys), for `subsurf model` and
 * `subsurf compare-halfspace`. */
#ifndef SUBSURF_CLI_MODEL_PREDICT_H
#define SUBSURF_CLI_MODEL_PREDICT_H

#include "cli/model_options.h"

#include "subsurf/bssrdf.h"
#include "subsurf/halfspace.h"

#include <cjson/cJSON.h>
#include <stdio.h>

/* Creates model `name` for the medium of `p` (one channel, copied to all
 * three) with the options of `mo` it declares; a slab thickness of `p` goes
 * to the model's "thickness" option (an error for a model without one).
 * Prints "subsurf CMD: ..." and returns -1 on bad input. */
int ss_model_create(const char *cmd, const char *name, const ss_model_options *mo,
                    const ss_halfspace_params *p, ss_bssrdf **out);

/* Fills a result with the binning of ss_halfspace_run(p) from the model's
 * channel `channel` (models built from p have three equal channels; layers
 * carries its own colours): totals, radial annulus averages and
 * exact-direction radiance, errors 0; the specular reflection is Fresnel's
 * at the model's entry face. Returns -1 when out of memory (message printed). */
int ss_model_predict(const char *cmd, const ss_bssrdf *b, const ss_halfspace_params *p, int channel,
                     ss_halfspace_result **out);

/* Parses "a,b,c" into numbers > 0 (malloc'd). Prints and returns -1 on error. */
int ss_parse_radius_list(const char *cmd, const char *name, const char *text, double **out, int *n);

#endif
