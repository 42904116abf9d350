/* subsurf model: what a BSSRDF model predicts for the experiment of
 * `subsurf halfspace` (same options, same JSON keys), plus its intrinsic
 * total "rd" and, with --profile-r, its radial profile as the paper defines
 * it. */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/medium_options.h"
#include "cli/model_sum.h"
#include "cli/output_check.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include "subsurf/progress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CMD "model"

typedef struct {
  ss_medium_options medium;
  ss_model_options model;
  const char *name;
  ss_model_sum sum; /* name split into its models */
  const char *json_path;
  double *profile_r;
  int n_profile;
} options;

static void usage(FILE *out) {
  fprintf(
      out,
      "usage: subsurf model --model NAME [options]\n\n"
      "A BSSRDF model's prediction for the experiment of `subsurf halfspace`: a collimated\n"
      "unit-power beam entering at the origin. Writes the same JSON keys (\"reflectance\",\n"
      "\"radial\", \"directions\", ...; errors 0), plus \"rd\", the model's intrinsic total at\n"
      "normal incidence as its paper defines it, and with --profile-r its radial profile.\n"
      "Diffusion models use g through sigma_s' = (1 - g) sigma_s; single scattering uses a\n"
      "Henyey-Greenstein phase function; 'layers' takes its stack from --layers (default:\n"
      "the three-layer skin of Donner & Jensen 2005, index 1.4) and ignores the medium's\n"
      "coefficients; --medium NAME --channel C picks its colour. A model's own options\n"
      "(listed below it) are --name value.\n\n");
  ss_model_list_help(out);
  fprintf(out, "\n");
  ss_medium_options_help(out);
  fprintf(
      out,
      "model:\n"
      "  --model NAME       the model (required); a+b is the sum of two models, e.g.\n"
      "                     dipole+single\n"
      "  --profile-r LIST   radii r1,r2,... for \"profile\": {\"r\", \"value\", \"ms\", \"ss\"}\n"
      "outputs:\n"
      "  --json FILE|-      results as JSON (default: a summary on stdout)\n");
}

static int parse_own(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  if (!strcmp(name, "model")) {
    o->name = value;
  } else if (!strcmp(name, "profile-r")) {
    free(o->profile_r);
    o->profile_r = NULL;
    return ss_parse_radius_list(CMD, name, value, &o->profile_r, &o->n_profile) ? -1 : 1;
  } else if (!strcmp(name, "json")) {
    o->json_path = value;
  } else {
    int rc = ss_medium_options_parse(&o->medium, CMD, name, value);
    return rc ? rc : ss_model_options_parse(&o->model, CMD, name, value);
  }
  return 1;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  return ss_model_options_flag(&o->model, name);
}

/* Returns 0, 1 to exit successfully (--help), or 2 on bad input. */
static int parse_args(options *o, int argc, char **argv) {
  const ss_cli_spec spec = {parse_flag, parse_own, NULL, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 1, &spec, o);
  if (rc != 0) {
    return rc;
  }
  if (!o->name) {
    fprintf(stderr, "subsurf " CMD ": --model: missing; one of the models is required (see "
                    "--help)\n");
    return 2;
  }
  if (ss_model_sum_parse(&o->sum, CMD, "model", o->name) != 0) {
    return 2;
  }
  const ss_bssrdf_ops *ops[SS_MODEL_SUM_MAX];
  for (int j = 0; j < o->sum.n; ++j) {
    ops[j] = ss_bssrdf_model_find(o->sum.parts[j]);
  }
  if (ss_model_options_check(&o->model, CMD, ops, o->sum.n) != 0) {
    return 2;
  }
  if (ss_medium_options_finish(&o->medium, CMD) != 0) {
    return 2;
  }
  return o->json_path ? ss_cli_check_output(CMD, "--json", o->json_path, SS_FILE_JSON) : 0;
}

/* Everything one channel contributes to the JSON output; -1 (printed) when
 * a value is not finite. */
static int add_channel(cJSON *obj, const options *o, int c, const ss_halfspace_result *r) {
  ss_result_add_json(obj, r);
  cJSON_AddNumberToObject(obj, "rd", ss_model_sum_rd(&o->sum, c));
  if (o->n_profile > 0) {
    cJSON_AddItemToObject(obj, "profile",
                          ss_model_sum_profile_json(&o->sum, c, o->profile_r, o->n_profile));
  }
  return ss_json_check_finite(obj, CMD);
}

static void print_summary(const options *o, const ss_halfspace_result *r, int c) {
  printf("%s, channel %s (%.3f s)\n", o->name, ss_channel_name(c), r->seconds);
  printf("  %-14s %.6f\n", "reflectance", r->reflectance.value);
  printf("  %-14s %.6f\n", "transmittance", r->transmittance.value);
  printf("  %-14s %.6f\n", "specular", r->specular.value);
  printf("  %-14s %.6f\n", "rd", ss_model_sum_rd(&o->sum, c));
  for (int i = 0; i < o->n_profile; ++i) {
    ss_bssrdf_profile_value v;
    ss_model_sum_profile(&o->sum, c, o->profile_r[i], &v);
    printf("  profile r=%-8g %.6g (ms %.6g, ss %.6g)\n", o->profile_r[i], v.value, v.ms, v.ss);
  }
}

int ss_cmd_model(int argc, char **argv) {
  options o;
  memset(&o, 0, sizeof o);
  ss_medium_options_init(&o.medium);
  ss_model_options_init(&o.model);
  int rc = parse_args(&o, argc, argv);
  if (rc != 0) {
    ss_model_sum_free(&o.sum);
    free(o.profile_r);
    return rc == 1 ? 0 : rc;
  }
  ss_cli_install_interrupt_handler();
  int nres = ss_medium_options_channel_count(&o.medium);
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "command", CMD);
  cJSON_AddStringToObject(root, "model", o.name);
  cJSON_AddItemToObject(root, "options", ss_model_options_to_json(&o.model));
  cJSON *channels = NULL;
  int status = 0;
  for (int i = 0; i < nres && status == 0; ++i) {
    int c = ss_medium_options_channel_at(&o.medium, i);
    ss_medium_options one = o.medium;
    ss_medium_options_select_channel(&one, c);
    if (ss_model_sum_create(&o.sum, CMD, &o.model, &one.params) != 0) {
      status = 2;
      break;
    }
    double t0 = ss_seconds();
    ss_halfspace_result *r = NULL;
    if (ss_model_sum_predict(&o.sum, CMD, &one.params, c, &r) != 0) {
      status = 1;
      break;
    }
    r->seconds = ss_seconds() - t0;
    if (ss_cli_interrupted()) {
      ss_halfspace_result_destroy(r);
      ss_model_sum_release(&o.sum);
      status = ss_cli_interrupted_exit(CMD, "");
      break;
    }
    if (nres == 1) {
      one.channel = o.medium.channel;
      cJSON_AddItemToObject(root, "params", ss_medium_options_to_json(&one));
      status = add_channel(root, &o, c, r) ? 1 : 0;
    } else {
      if (!channels) {
        cJSON_AddItemToObject(root, "params", ss_medium_options_to_json(&o.medium));
        channels = cJSON_AddObjectToObject(root, "channels");
      }
      one.channel = c;
      cJSON *ch = cJSON_AddObjectToObject(channels, ss_channel_name(c));
      cJSON_AddItemToObject(ch, "params", ss_medium_options_to_json(&one));
      status = add_channel(ch, &o, c, r) ? 1 : 0;
    }
    if (status == 0 && (!o.json_path || strcmp(o.json_path, "-") != 0)) {
      print_summary(&o, r, o.medium.medium ? c : 0);
    }
    ss_halfspace_result_destroy(r);
    ss_model_sum_release(&o.sum);
  }
  if (status == 0 && o.json_path) {
    if (ss_json_write_file(root, o.json_path, CMD) != 0) {
      status = 1;
    } else if (strcmp(o.json_path, "-") != 0) {
      fprintf(stderr, "wrote %s\n", o.json_path);
    }
  }
  cJSON_Delete(root);
  ss_model_sum_free(&o.sum);
  free(o.profile_r);
  return status;
}
