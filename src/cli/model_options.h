/* The model options of `subsurf model` and `subsurf compare-halfspace`,
 * read with no per-model code: `--name value` (or `--name=value`; a bool
 * option also as the flag `--name`) is any option some registered model
 * declares (bssrdf.h), with the declared snake_case name written in
 * kebab-case. Values are recorded while parsing and set on each chosen model
 * that declares the option once the models are known. */
#ifndef SUBSURF_CLI_MODEL_OPTIONS_H
#define SUBSURF_CLI_MODEL_OPTIONS_H

#include "subsurf/bssrdf.h"

#include <cjson/cJSON.h>
#include <stdio.h>

#define SS_MODEL_MAX_ARGS 32

typedef struct {
  int n;
  struct {
    char name[64]; /* snake_case, as declared */
    const char *value;
  } args[SS_MODEL_MAX_ARGS];
} ss_model_options;

void ss_model_options_init(ss_model_options *o);

/* Tries `--name value`: 1 when some model declares the option (recorded), 0
 * when none does, -1 after printing an error (too many options). */
int ss_model_options_parse(ss_model_options *o, const char *cmd, const char *name,
                           const char *value);
/* Tries the flag `--name`: 1 when some model declares a bool option `name`
 * (recorded as true), else 0. */
int ss_model_options_flag(ss_model_options *o, const char *name);

/* Every recorded option must belong to one of the n chosen models; prints
 * "subsurf CMD: --name: ..." and returns -1 otherwise. */
int ss_model_options_check(const ss_model_options *o, const char *cmd,
                           const ss_bssrdf_ops *const *models, int n);
/* Sets the recorded options `ops` declares on p; prints the model's message
 * and returns -1 on a bad value. */
int ss_model_options_apply(const ss_model_options *o, const char *cmd, const ss_bssrdf_ops *ops,
                           ss_bssrdf_params *p);

/* {"name": "value", ...}: the model options given, for the JSON output. */
cJSON *ss_model_options_to_json(const ss_model_options *o);

/* The registry for --help: each model's summary, then its options. */
void ss_model_list_help(FILE *out);

#endif
