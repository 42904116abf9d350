/* subsurf compare-halfspace: the Monte Carlo reference and BSSRDF models on
 * identical bins, with a table of relative errors and a profile plot. */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/medium_options.h"
#include "cli/model_predict.h"
#include "cli/profile_plot.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include "subsurf/progress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CMD "compare-halfspace"
#define MAX_MODELS 16
/* A curve may be the sum of models, "a+b" (e.g. dipole+single: Jensen et
 * al.'s complete BSSRDF S_d + S^(1)). */
#define MAX_PARTS 4

typedef struct {
  ss_medium_options medium;
  ss_model_options model;
  char *models_text, *parts_text;
  const char *models[MAX_MODELS];
  const char *parts[MAX_MODELS][MAX_PARTS];
  int n_parts[MAX_MODELS];
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
          "                     of two models, e.g. dipole+single or table-gwc+single\n"
          "  --min-distance     dipole family: evaluate R_d at max(r, 1/sigma_t')\n"
          "  --beam-samples N   photon beam diffusion samples (default 100)\n"
          "  --table FILE       tabulated models: the table file\n"
          "outputs:\n"
          "  --plot FILE        log-log profile plot: .svg, .pdf or .ps (default: none)\n"
          "  --json FILE|-      reference, models and errors as JSON\n",
          (double)d.paths, (double)d.max_depth);
}

/* Splits one curve's name "a+b+..." (in place) into its models. */
static int split_parts(options *o, int k, char *curve) {
  o->n_parts[k] = 0;
  for (char *save = NULL, *tok = strtok_r(curve, "+", &save); tok;
       tok = strtok_r(NULL, "+", &save)) {
    if (o->n_parts[k] == MAX_PARTS) {
      fprintf(stderr, "subsurf " CMD ": --models: at most %d models in a sum, got '%s'\n",
              MAX_PARTS, o->models[k]);
      return -1;
    }
    if (!ss_bssrdf_model_find(tok)) {
      char names[512];
      ss_bssrdf_model_names(names, sizeof names);
      fprintf(stderr, "subsurf " CMD ": --models: unknown model '%s'; known models: %s\n", tok,
              names);
      return -1;
    }
    o->parts[k][o->n_parts[k]++] = tok;
  }
  if (o->n_parts[k] == 0) {
    fprintf(stderr, "subsurf " CMD ": --models: expected a model name, got '%s'\n", o->models[k]);
    return -1;
  }
  return 0;
}

static int split_models(options *o, const char *value) {
  free(o->models_text);
  free(o->parts_text);
  o->models_text = strdup(value);
  o->parts_text = strdup(value);
  o->n_models = 0;
  if (!o->models_text || !o->parts_text) {
    fprintf(stderr, "subsurf " CMD ": out of memory\n");
    return -1;
  }
  char *save_parts = NULL, *curve = strtok_r(o->parts_text, ",", &save_parts);
  for (char *save = NULL, *tok = strtok_r(o->models_text, ",", &save); tok;
       tok = strtok_r(NULL, ",", &save), curve = strtok_r(NULL, ",", &save_parts)) {
    if (o->n_models == MAX_MODELS) {
      fprintf(stderr, "subsurf " CMD ": --models: at most %d models\n", MAX_MODELS);
      return -1;
    }
    o->models[o->n_models] = tok;
    if (split_parts(o, o->n_models, curve) != 0) {
      return -1;
    }
    o->n_models++;
  }
  if (o->n_models == 0) {
    fprintf(stderr, "subsurf " CMD ": --models: expected a comma-separated list, got '%s'\n",
            value);
    return -1;
  }
  return 0;
}

static int parse_own(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  if (!strcmp(name, "models")) {
    return split_models(o, value) ? -1 : 1;
  } else if (!strcmp(name, "beam-samples")) {
    return ss_parse_int(CMD, name, value, 1, 1000000, &o->model.beam_samples) ? -1 : 1;
  } else if (!strcmp(name, "table")) {
    o->model.table_path = value;
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
    return rc ? rc : ss_medium_options_parse(&o->medium, CMD, name, value);
  }
  return 1;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  if (!strcmp(name, "quiet")) {
    o->quiet = 1;
  } else if (!strcmp(name, "min-distance")) {
    o->model.min_distance = 1;
  } else {
    return 0;
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
  if (o->medium.channel == SS_CHANNEL_ALL) {
    fprintf(stderr, "subsurf " CMD ": --channel: compares one channel at a time; pick r, g or b\n");
    return 2;
  }
  if (ss_medium_options_finish(&o->medium, CMD) != 0) {
    return 2;
  }
  ss_medium_options_select_channel(&o->medium, o->medium.channel);
  if (o->json_path && ss_check_output_path(o->json_path, CMD, "json") != 0) {
    return 2;
  }
  if (o->plot_path && ss_check_output_path(o->plot_path, CMD, "plot") != 0) {
    return 2;
  }
  return 0;
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

static cJSON *errors_json(errors e) {
  cJSON *j = cJSON_CreateObject();
  cJSON_AddNumberToObject(j, "reflectance_relative", e.rel_total);
  cJSON_AddNumberToObject(j, "reflectance_z", e.z_total);
  cJSON_AddNumberToObject(j, "profile_mean_relative", e.mean_rel);
  cJSON_AddNumberToObject(j, "profile_max_relative", e.max_rel);
  cJSON_AddNumberToObject(j, "profile_bins_compared", e.significant);
  cJSON_AddNumberToObject(j, "profile_bins_within_5_percent", e.within5);
  return j;
}

static void on_progress(void *ctx, uint64_t done, uint64_t total) {
  (void)total;
  ss_progress_update(ctx, done);
}

/* Adds a model's prediction to another's (a curve "a+b"). */
static void add_prediction(ss_halfspace_result *sum, const ss_halfspace_result *r) {
  sum->reflectance.value += r->reflectance.value;
  sum->transmittance.value += r->transmittance.value;
  sum->absorbed.value =
      1.0 - sum->specular.value - sum->reflectance.value - sum->transmittance.value;
  for (int i = 0; i < sum->rbins; ++i) {
    sum->radial[i].value += r->radial[i].value;
  }
  for (int i = 0; i < sum->n_theta_o * sum->xbins; ++i) {
    sum->directions[i].value += r->directions[i].value;
  }
  for (int i = 0; sum->map && r->map && i < sum->ybins * sum->xbins; ++i) {
    sum->map[i].value += r->map[i].value;
  }
}

static void destroy_models(ss_bssrdf *models[][MAX_PARTS]) {
  for (int k = 0; k < MAX_MODELS; ++k) {
    for (int j = 0; j < MAX_PARTS; ++j) {
      ss_bssrdf_destroy(models[k][j]);
      models[k][j] = NULL;
    }
  }
}

/* The prediction of curve k, summing its models; rd is the sum of theirs. */
static int predict_curve(ss_bssrdf *const *parts, int n_parts, const ss_halfspace_params *p,
                         ss_halfspace_result **out, double *rd) {
  *rd = 0.0;
  for (int j = 0; j < n_parts; ++j) {
    ss_halfspace_result *r = NULL;
    if (ss_model_predict(CMD, parts[j], p, &r) != 0) {
      return -1;
    }
    double v[SS_BSSRDF_CHANNELS];
    ss_bssrdf_rd(parts[j], v);
    *rd += v[0];
    if (j == 0) {
      *out = r;
    } else {
      add_prediction(*out, r);
      ss_halfspace_result_destroy(r);
    }
  }
  return 0;
}

static int run(options *o) {
  ss_halfspace_params *p = &o->medium.params;
  /* Models first: bad model input must not cost a reference run. */
  ss_bssrdf *models[MAX_MODELS][MAX_PARTS] = {{NULL}};
  for (int k = 0; k < o->n_models; ++k) {
    for (int j = 0; j < o->n_parts[k]; ++j) {
      if (ss_model_create(CMD, o->parts[k][j], &o->model, p, &models[k][j]) != 0) {
        destroy_models(models);
        return 2;
      }
    }
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
  double rd[MAX_MODELS];
  for (int k = 0; k < o->n_models && status == 0; ++k) {
    if (predict_curve(models[k], o->n_parts[k], p, &pred[k], &rd[k]) != 0) {
      status = 1;
    }
  }
  destroy_models(models);
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
      printf("%-17s %11.6f %+8.2f%% %8.1f %9.5f %10.2f%% %9.2f%% %6d/%d\n", o->models[k],
             pred[k]->reflectance.value, 100.0 * e.rel_total, e.z_total, rd[k], 100.0 * e.mean_rel,
             100.0 * e.max_rel, e.within5, e.significant);
      cJSON *jm = cJSON_AddObjectToObject(jmodels, o->models[k]);
      ss_result_add_json(jm, pred[k]);
      cJSON_AddNumberToObject(jm, "rd", rd[k]);
      cJSON_AddItemToObject(jm, "errors", errors_json(e));
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
    double *rc = malloc((size_t)ref->rbins * sizeof *rc);
    const double *curves[MAX_MODELS];
    if (!rc) {
      fprintf(stderr, "subsurf " CMD ": out of memory\n");
      status = 1;
    } else {
      for (int i = 0; i < ref->rbins; ++i) {
        rc[i] = i == 0 ? 0.5 * ref->r_hi[0] : sqrt(ref->r_lo[i] * ref->r_hi[i]);
      }
      double *vals = malloc((size_t)o->n_models * (size_t)ref->rbins * sizeof *vals);
      if (!vals) {
        status = 1;
      } else {
        for (int k = 0; k < o->n_models; ++k) {
          for (int i = 0; i < ref->rbins; ++i) {
            vals[(size_t)k * (size_t)ref->rbins + (size_t)i] = pred[k]->radial[i].value;
          }
          curves[k] = vals + (size_t)k * (size_t)ref->rbins;
        }
        char title[160];
        snprintf(title, sizeof title, "albedo %.4g, eta %.3g, theta_i %.0f deg",
                 p->sigma_s / (p->sigma_s + p->sigma_a), p->eta,
                 p->theta_i * 180.0 / 3.14159265358979);
        if (ss_profile_plot_write(CMD, o->plot_path, title, rc, ref->radial, ref->rbins, curves,
                                  o->models, o->n_models) != 0) {
          status = 1;
        } else {
          fprintf(stderr, "wrote %s\n", o->plot_path);
        }
        free(vals);
      }
      free(rc);
    }
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
  free(o.models_text);
  free(o.parts_text);
  return rc;
}
