/* subsurf compare-halfspace: the Monte Carlo reference and BSSRDF models on
 * identical bins, with a table of relative errors and a profile plot. */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/medium_options.h"
#include "cli/model_sum.h"
#include "cli/output_check.h"
#include "cli/profile_plot.h"
#include "cli/progress_bar.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CMD "compare-halfspace"
#define MAX_MODELS 16

typedef struct {
  ss_medium_options medium;
  ss_model_options model;
  char *models_text;
  const char *models[MAX_MODELS];
  ss_model_sum curves[MAX_MODELS]; /* a curve may be a sum of models, "a+b" */
  int n_models;
  const char *plot_path, *json_path;
  int quiet;
} options;

static void usage(FILE *out) {
  ss_halfspace_params d;
  ss_halfspace_params_default(&d);
  fprintf(out,
          "usage: subsurf compare-halfspace --models A,B,... [options]\n\n"
          "Runs `subsurf halfspace` and `subsurf model` for each model with the same medium and\n"
          "bins; prints each model's relative error in total reflectance (and in units of the\n"
          "reference's standard error) and in the radial profile (over the bins whose reference\n"
          "standard error is below 10%%), and plots the profiles.\n\n");
  ss_model_list_help(out);
  fprintf(out, "\n");
  ss_medium_options_help(out);
  fprintf(out,
          "reference run:\n"
          "  --paths N          light paths (default %.0f)\n"
          "  --seed N           random seed (default 0)\n"
          "  --threads N        OpenMP threads (default 0: all cores)\n"
          "  --time-limit S     stop the reference after S seconds (default 0: none)\n"
          "  --max-depth N      scattering events before a path is cut (default %.0f)\n"
          "  --quiet            no progress bar\n"
          "models:\n"
          "  --models LIST      comma-separated model names (required); a+b plots the sum\n"
          "                     of two models, e.g. dipole+single or table-gwc+single; a\n"
          "                     model option (listed above) goes to every model that has it\n"
          "outputs:\n"
          "  --plot FILE        log-log profile plot: .svg, .pdf or .ps (default: none)\n"
          "  --json FILE|-      reference, models and errors as JSON\n",
          (double)d.paths, (double)d.max_depth);
}

static void free_curves(options *o) {
  for (int k = 0; k < o->n_models; ++k) {
    ss_model_sum_free(&o->curves[k]);
  }
  o->n_models = 0;
}

static int split_models(options *o, const char *value) {
  if (!ss_cli_name_list_ok(value, ",+")) {
    fprintf(stderr,
            "subsurf " CMD ": --models: expected model names joined by ',' or '+' with no "
            "empty name, got '%s'\n",
            value);
    return -1;
  }
  free_curves(o);
  free(o->models_text);
  o->models_text = strdup(value);
  if (!o->models_text) {
    fprintf(stderr, "subsurf " CMD ": out of memory\n");
    return -1;
  }
  for (char *tok = o->models_text;;) {
    char *comma = strchr(tok, ',');
    if (comma) {
      *comma = '\0';
    }
    if (o->n_models == MAX_MODELS) {
      fprintf(stderr, "subsurf " CMD ": --models: at most %d models\n", MAX_MODELS);
      return -1;
    }
    if (!*tok) {
      fprintf(stderr,
              "subsurf " CMD ": --models: expected a comma-separated list of models, "
              "got '%s'\n",
              value);
      return -1;
    }
    o->models[o->n_models] = tok;
    if (ss_model_sum_parse(&o->curves[o->n_models++], CMD, "models", tok) != 0) {
      return -1;
    }
    if (!comma) {
      return 0;
    }
    tok = comma + 1;
  }
}

static int parse_own(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  if (!strcmp(name, "models")) {
    return split_models(o, value) ? -1 : 1;
  } else if (!strcmp(name, "plot")) {
    if (!ss_profile_plot_supported(value)) {
      fprintf(stderr, "subsurf " CMD ": --plot: expected a .svg, .pdf or .ps file, got '%s'\n",
              value);
      return -1;
    }
    o->plot_path = value;
  } else if (!strcmp(name, "json")) {
    o->json_path = value;
  } else {
    int rc = ss_medium_options_parse_run(&o->medium, CMD, name, value);
    rc = rc ? rc : ss_medium_options_parse(&o->medium, CMD, name, value);
    return rc ? rc : ss_model_options_parse(&o->model, CMD, name, value);
  }
  return 1;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  if (!strcmp(name, "quiet")) {
    o->quiet = 1;
  } else {
    return ss_model_options_flag(&o->model, name);
  }
  return 1;
}

static int parse_args(options *o, int argc, char **argv) {
  const ss_cli_spec spec = {parse_flag, parse_own, NULL, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 1, &spec, o);
  if (rc != 0) {
    return rc;
  }
  if (o->n_models == 0) {
    fprintf(stderr, "subsurf " CMD ": --models: missing; name at least one model (see --help)\n");
    return 2;
  }
  const ss_bssrdf_ops *chosen[MAX_MODELS * SS_MODEL_SUM_MAX];
  int n_chosen = 0;
  for (int k = 0; k < o->n_models; ++k) {
    for (int j = 0; j < o->curves[k].n; ++j) {
      chosen[n_chosen++] = ss_bssrdf_model_find(o->curves[k].parts[j]);
    }
  }
  if (ss_model_options_check(&o->model, CMD, chosen, n_chosen) != 0) {
    return 2;
  }
  if (o->medium.channel == SS_CHANNEL_ALL) {
    fprintf(stderr, "subsurf " CMD ": --channel: compares one channel at a time; pick r, g or b\n");
    return 2;
  }
  if (ss_medium_options_finish(&o->medium, CMD) != 0) {
    return 2;
  }
  ss_medium_options_select_channel(&o->medium, o->medium.channel);
  ss_output_plan p;
  ss_output_plan_init(&p);
  if (o->json_path) {
    ss_output_plan_add(&p, "--json", o->json_path, SS_FILE_JSON, 0, 0);
  }
  if (o->plot_path) {
    ss_output_plan_add(&p, "--plot", o->plot_path, ss_file_kind_of_name(o->plot_path, SS_FILE_PS),
                       0, 0);
  }
  return ss_cli_check_outputs(&p, CMD);
}

typedef struct {
  double rel_total, z_total;
  double mean_rel, max_rel;
  int significant, within5;
} errors;

/* Profile errors over the bins the reference resolves (stderr < 10%). */
static errors compare(const ss_halfspace_result *ref, const ss_halfspace_result *m) {
  errors e = {0};
  e.rel_total = m->reflectance.value / ref->reflectance.value - 1.0;
  e.z_total = ref->reflectance.error > 0.0
                  ? (m->reflectance.value - ref->reflectance.value) / ref->reflectance.error
                  : 0.0;
  for (int i = 0; i < ref->rbins; ++i) {
    ss_estimate r = ref->radial[i];
    if (!(r.value > 0.0) || r.error > 0.1 * r.value) {
      continue;
    }
    double rel = fabs(m->radial[i].value / r.value - 1.0);
    e.mean_rel += rel;
    e.max_rel = fmax(e.max_rel, rel);
    e.significant++;
    e.within5 += rel <= 0.05;
  }
  if (e.significant) {
    e.mean_rel /= e.significant;
  }
  return e;
}

/* A curve without a profile (a BRDF: all its light leaves at the entry
 * point) has only its totals compared. */
static cJSON *errors_json(errors e, int has_profile) {
  cJSON *j = cJSON_CreateObject();
  cJSON_AddNumberToObject(j, "reflectance_relative", e.rel_total);
  cJSON_AddNumberToObject(j, "reflectance_z", e.z_total);
  if (!has_profile) {
    cJSON_AddStringToObject(j, "profile", "none: a BRDF has no radial profile");
    return j;
  }
  cJSON_AddNumberToObject(j, "profile_mean_relative", e.mean_rel);
  cJSON_AddNumberToObject(j, "profile_max_relative", e.max_rel);
  cJSON_AddNumberToObject(j, "profile_bins_compared", e.significant);
  cJSON_AddNumberToObject(j, "profile_bins_within_5_percent", e.within5);
  return j;
}

static void print_errors(const char *name, double reflectance, double rd, errors e,
                         int has_profile) {
  printf("%-17s %11.6f %+8.2f%% %8.1f %9.5f ", name, reflectance, 100.0 * e.rel_total, e.z_total,
         rd);
  if (has_profile) {
    printf("%10.2f%% %9.2f%% %6d/%d\n", 100.0 * e.mean_rel, 100.0 * e.max_rel, e.within5,
           e.significant);
  } else {
    printf("  (a BRDF: no radial profile)\n");
  }
}

/* The profile plot of the reference and every curve that has a profile. */
static int write_plot(const options *o, const ss_halfspace_params *p,
                      const ss_halfspace_result *ref, ss_halfspace_result *const *pred,
                      const int *has_profile) {
  double *rc = malloc((size_t)ref->rbins * sizeof *rc);
  double *vals = malloc((size_t)o->n_models * (size_t)ref->rbins * sizeof *vals);
  if (!rc || !vals) {
    fprintf(stderr, "subsurf " CMD ": out of memory\n");
    free(rc);
    free(vals);
    return 1;
  }
  for (int i = 0; i < ref->rbins; ++i) {
    rc[i] = i == 0 ? 0.5 * ref->r_hi[0] : sqrt(ref->r_lo[i] * ref->r_hi[i]);
  }
  const double *curves[MAX_MODELS];
  const char *names[MAX_MODELS];
  int n = 0;
  for (int k = 0; k < o->n_models; ++k) {
    if (!has_profile[k]) {
      continue;
    }
    for (int i = 0; i < ref->rbins; ++i) {
      vals[(size_t)n * (size_t)ref->rbins + (size_t)i] = pred[k]->radial[i].value;
    }
    curves[n] = vals + (size_t)n * (size_t)ref->rbins;
    names[n++] = o->models[k];
  }
  char title[160];
  snprintf(title, sizeof title, "albedo %.4g, eta %.3g, theta_i %.0f deg",
           p->medium.sigma_s.c[p->channel] /
               (p->medium.sigma_s.c[p->channel] + p->medium.sigma_a.c[p->channel]),
           p->eta, p->theta_i * 180.0 / 3.14159265358979);
  int status = 0;
  if (ss_profile_plot_write(CMD, o->plot_path, title, rc, ref->radial, ref->rbins, curves, names,
                            n) != 0) {
    status = 1;
  } else {
    fprintf(stderr, "wrote %s\n", o->plot_path);
  }
  free(vals);
  free(rc);
  return status;
}

static void on_progress(void *ctx, uint64_t done, uint64_t total) {
  (void)total;
  ss_progress_update(ctx, done);
}

static int run(options *o) {
  ss_halfspace_params *p = &o->medium.params;
  /* Models first: bad model input must not cost a reference run. */
  for (int k = 0; k < o->n_models; ++k) {
    if (ss_model_sum_create(&o->curves[k], CMD, &o->model, p) != 0) {
      return 2;
    }
  }
  if (o->plot_path && ss_profile_plot_ready(CMD) != 0) {
    return 1;
  }
  p->cancel = ss_cli_install_interrupt_handler();
  ss_progress progress;
  ss_progress_begin(&progress, "halfspace", p->paths, !o->quiet, p->time_limit);
  p->progress = on_progress;
  p->progress_ctx = &progress;
  ss_halfspace_result *ref = NULL, *pred[MAX_MODELS] = {NULL};
  ss_error err;
  ss_status st = ss_halfspace_run(p, &ref, &err);
  ss_progress_end(&progress, ref ? ref->paths : 0);
  int status = 0;
  if (st != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    status = 1;
  } else if (ref->interrupted) {
    fprintf(stderr, "subsurf " CMD ": interrupted; nothing written\n");
    status = 130;
  }
  const int c = o->medium.channel;
  double rd[MAX_MODELS] = {0};
  int has_profile[MAX_MODELS] = {0};
  for (int k = 0; k < o->n_models && status == 0; ++k) {
    if (ss_model_sum_predict(&o->curves[k], CMD, p, c, &pred[k]) != 0) {
      status = 1;
    }
    rd[k] = ss_model_sum_rd(&o->curves[k], c);
    has_profile[k] = ss_model_sum_has_profile(&o->curves[k]);
    ss_model_sum_release(&o->curves[k]);
  }
  if (status == 0 && ss_cli_interrupted()) {
    status = ss_cli_interrupted_exit(CMD, "");
  }
  if (status == 0) {
    printf("reference: halfspace, %llu paths in %.1f s: reflectance %.6f +- %.6f\n",
           (unsigned long long)ref->paths, ref->seconds, ref->reflectance.value,
           ref->reflectance.error);
    printf("%-17s %11s %9s %8s %9s %11s %10s %9s\n", "model", "reflectance", "rel.err", "z", "rd",
           "prof.mean", "prof.max", "within5%");
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "command", CMD);
    cJSON_AddItemToObject(root, "params", ss_medium_options_to_json(&o->medium));
    cJSON *jref = cJSON_AddObjectToObject(root, "reference");
    ss_result_add_json(jref, ref);
    cJSON *jmodels = cJSON_AddObjectToObject(root, "models");
    for (int k = 0; k < o->n_models; ++k) {
      errors e = compare(ref, pred[k]);
      print_errors(o->models[k], pred[k]->reflectance.value, rd[k], e, has_profile[k]);
      cJSON *jm = cJSON_AddObjectToObject(jmodels, o->models[k]);
      ss_result_add_json(jm, pred[k]);
      cJSON_AddNumberToObject(jm, "rd", rd[k]);
      cJSON_AddItemToObject(jm, "errors", errors_json(e, has_profile[k]));
    }
    if (o->json_path) {
      if (ss_json_write_file(root, o->json_path, CMD) != 0) {
        status = 1;
      } else if (strcmp(o->json_path, "-") != 0) {
        fprintf(stderr, "wrote %s\n", o->json_path);
      }
    }
    cJSON_Delete(root);
  }
  if (status == 0 && o->plot_path) {
    status = write_plot(o, p, ref, pred, has_profile);
  }
  ss_halfspace_result_destroy(ref);
  for (int k = 0; k < o->n_models; ++k) {
    ss_halfspace_result_destroy(pred[k]);
  }
  return status;
}

int ss_cmd_compare_halfspace(int argc, char **argv) {
  options o;
  memset(&o, 0, sizeof o);
  ss_medium_options_init(&o.medium);
  ss_model_options_init(&o.model);
  int rc = parse_args(&o, argc, argv);
  if (rc == 0) {
    rc = run(&o);
  } else if (rc == 1) {
    rc = 0;
  }
  free_curves(&o);
  free(o.models_text);
  return rc;
}
