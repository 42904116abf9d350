/* Options shared by `subsurf halfspace` and the commands that answer the same
 * questions from a model (`subsurf model`, `subsurf compare-halfspace`): the
 * medium, the incidence, the boundary and the binning of the outputs. */
#ifndef SUBSURF_CLI_MEDIUM_OPTIONS_H
#define SUBSURF_CLI_MEDIUM_OPTIONS_H

#include "cli/args.h"

#include "subsurf/halfspace.h"
#include "subsurf/media.h"

#include <cjson/cJSON.h>
#include <stdio.h>

#define SS_CHANNEL_ALL (-1)

typedef struct {
  ss_halfspace_params params; /* resolved for the current channel */
  const ss_medium_preset *medium;
  double scale;
  int channel; /* 0, 1, 2 or SS_CHANNEL_ALL */
  int sigma_s_set, sigma_a_set, eta_set, channel_set;
  double sigma_s, sigma_a, g; /* as given on the command line */
  ss_medium_flakes flakes;    /* --flakes and its parameters */
} ss_medium_options;

void ss_medium_options_init(ss_medium_options *o);

/* Tries `--name value`. Returns 1 when the option is one of ours (and valid),
 * 0 when it is not ours, -1 on a bad value (the error is printed). */
int ss_medium_options_parse(ss_medium_options *o, const char *cmd, const char *name,
                            const char *value);

/* Tries the options of a Monte Carlo reference run: --paths, --time-limit,
 * --seed, --threads, --max-depth. Same return values as above. */
int ss_medium_options_parse_run(ss_medium_options *o, const char *cmd, const char *name,
                                const char *value);

/* Checks the combination; returns 0, or -1 after printing the error. */
int ss_medium_options_finish(ss_medium_options *o, const char *cmd);

/* Resolves the medium (the preset's three channels, or the gray
 * --sigma-s/--sigma-a) into o->params.medium and selects channel c (0..2;
 * 0 without a preset). */
void ss_medium_options_select_channel(ss_medium_options *o, int c);

/* Number of channels to run (1, or 3 for --channel rgb) and the i-th one. */
int ss_medium_options_channel_count(const ss_medium_options *o);
int ss_medium_options_channel_at(const ss_medium_options *o, int i);
const char *ss_channel_name(int c);

void ss_medium_options_help(FILE *out);

/* The "params" object of the JSON output: every input, resolved. */
cJSON *ss_medium_options_to_json(const ss_medium_options *o);

#endif
