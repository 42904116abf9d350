/* A model curve "a+b+...": the sum of several models' predictions (e.g.
 * Jensen et al. 2001's complete BSSRDF dipole+single, or Ferrier's
 * multiple-scattering table plus exact single scattering), for `subsurf
 * model` and `subsurf compare-halfspace`. */
#ifndef SUBSURF_CLI_MODEL_SUM_H
#define SUBSURF_CLI_MODEL_SUM_H

#include "cli/model_predict.h"

#define SS_MODEL_SUM_MAX 4

typedef struct {
  const char *name; /* the curve as given, e.g. "dipole+single" */
  char *text;       /* a copy of it, split at '+' */
  int n;
  const char *parts[SS_MODEL_SUM_MAX];
  ss_bssrdf *models[SS_MODEL_SUM_MAX]; /* after ss_model_sum_create */
} ss_model_sum;

/* Splits `name` into registered model names; prints "subsurf CMD: --OPTION:
 * ..." and returns -1 for an unknown or empty part or too many parts. */
int ss_model_sum_parse(ss_model_sum *s, const char *cmd, const char *option, const char *name);
/* Creates every part for the medium of p (ss_model_create); -1 on bad input. */
int ss_model_sum_create(ss_model_sum *s, const char *cmd, const ss_model_options *mo,
                        const ss_halfspace_params *p);
/* The sum of the parts' ss_model_predict results (specular from the first
 * part, absorbed what the sum leaves); -1 when out of memory. */
int ss_model_sum_predict(const ss_model_sum *s, const char *cmd, const ss_halfspace_params *p,
                         int channel, ss_halfspace_result **out);
/* The sum of the parts' intrinsic totals rd. */
double ss_model_sum_rd(const ss_model_sum *s, int channel);
/* 0 when a part is a BRDF (all its light leaves at the entry point): the
 * sum then has no radial profile to compare or plot. */
int ss_model_sum_has_profile(const ss_model_sum *s);
/* The summed profile {"r", "value", "ms", "ss"} (and "t" when every part is
 * a slab) at the given radii. */
cJSON *ss_model_sum_profile_json(const ss_model_sum *s, int channel, const double *r, int n);
/* The summed profile at one radius. */
void ss_model_sum_profile(const ss_model_sum *s, int channel, double r,
                          ss_bssrdf_profile_value *out);
/* Destroys the parts' models (ss_model_sum_create may then run again). */
void ss_model_sum_release(ss_model_sum *s);
/* ss_model_sum_release and frees the copy of the name. */
void ss_model_sum_free(ss_model_sum *s);

#endif
