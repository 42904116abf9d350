/* `subsurf compare`'s results.json and results.csv (compare_scene.h). */
#include "cli/compare_scene.h"
#include "cli/result_json.h"
#include "cli/text_buf.h"

#include "subsurf/error_curve.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const channel_names[3] = {"r", "g", "b"};

static cJSON *rgb_array(const double v[3]) { return cJSON_CreateDoubleArray(v, 3); }

void ss_compare_curve_of(const ss_compare_result *r, const ss_compare_result *volpath,
                         ss_compare_curve *c) {
  double t[SS_COMPARE_MAX_PASSES], e[SS_COMPARE_MAX_PASSES], spp[SS_COMPARE_MAX_PASSES];
  for (int k = 0; k < r->num_passes; ++k) {
    t[k] = r->passes[k].seconds;
    e[k] = r->passes[k].rel_mse;
    spp[k] = r->passes[k].spp;
  }
  c->slope = c->intercept = NAN;
  c->points = ss_loglog_fit(t, e, r->num_passes, &c->intercept, &c->slope);
  /* The fit e = c + k / t knows the method's bias floor: a method whose
   * error levels off above volpath's never reaches it (the log-log line
   * would say it does). */
  c->time_to_volpath =
      !volpath ? NAN : ss_error_time_to(t, e, r->num_passes, volpath->error.rel_mse);
  c->converged = ss_error_floor(spp, e, r->num_passes);
}

const ss_compare_result *ss_compare_find_volpath(const ss_compare_result *r, int n) {
  for (int i = 0; i < n; ++i) {
    if (!strcmp(r[i].method.integrator, "volpath")) {
      return &r[i];
    }
  }
  return NULL;
}

/* A number, or null when it is not finite. */
static cJSON *number_or_null(double v) {
  return isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull();
}

static void add_curve(cJSON *m, const ss_compare_curve *c) {
  cJSON *fit = cJSON_AddObjectToObject(m, "fit");
  cJSON_AddNumberToObject(fit, "points", c->points);
  cJSON_AddItemToObject(fit, "slope", number_or_null(c->slope));
  cJSON_AddItemToObject(fit, "intercept", number_or_null(c->intercept));
  cJSON_AddItemToObject(m, "time_to_volpath_error", number_or_null(c->time_to_volpath));
  cJSON_AddItemToObject(m, "converged_rel_mse", number_or_null(c->converged));
}

static cJSON *method_json(const ss_compare_result *r, const ss_compare_result *volpath) {
  cJSON *m = cJSON_CreateObject();
  cJSON_AddStringToObject(m, "method", r->method.text);
  cJSON_AddStringToObject(m, "integrator", r->method.integrator);
  if (r->method.model[0]) {
    cJSON_AddStringToObject(m, "model", r->method.model);
  }
  cJSON_AddStringToObject(m, "image", r->file);
  cJSON_AddNumberToObject(m, "seconds", r->seconds);
  cJSON_AddNumberToObject(m, "prepares", r->prepares);
  cJSON_AddNumberToObject(m, "spp", r->spp);
  cJSON_AddNumberToObject(m, "samples", (double)r->samples);
  cJSON_AddNumberToObject(m, "pixels", (double)r->error.pixels);
  cJSON_AddNumberToObject(m, "rel_mse", r->error.rel_mse);
  cJSON_AddItemToObject(m, "rel_mse_rgb", rgb_array(r->error.rel_mse_c));
  cJSON_AddItemToObject(m, "rmse_rgb", rgb_array(r->error.rmse));
  cJSON_AddItemToObject(m, "mean_rgb", rgb_array(r->error.mean));
  cJSON_AddItemToObject(m, "reference_mean_rgb", rgb_array(r->error.ref_mean));
  cJSON *ratio = cJSON_AddArrayToObject(m, "mean_ratio_rgb");
  for (int c = 0; c < 3; ++c) {
    double v = ss_image_error_mean_ratio(&r->error, c); /* null: a black reference */
    cJSON_AddItemToArray(ratio, isnan(v) ? cJSON_CreateNull() : cJSON_CreateNumber(v));
  }
  cJSON *passes = cJSON_AddArrayToObject(m, "passes");
  for (int k = 0; k < r->num_passes; ++k) {
    cJSON *p = cJSON_CreateObject();
    cJSON_AddNumberToObject(p, "spp", r->passes[k].spp);
    cJSON_AddNumberToObject(p, "seconds", r->passes[k].seconds);
    cJSON_AddNumberToObject(p, "rel_mse", r->passes[k].rel_mse);
    cJSON_AddItemToArray(passes, p);
  }
  ss_compare_curve c;
  ss_compare_curve_of(r, volpath, &c);
  add_curve(m, &c);
  return m;
}

static int write_json(const ss_compare_options *o) {
  const char *dir = o->dir;
  const ss_compare_result *r = o->results;
  int n = o->num_methods;
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "scene", o->scene);
  cJSON_AddStringToObject(root, "reference", o->ref.file);
  if (o->ref.rendered) {
    /* The volpath reference's samples, time and estimated relative
     * standard error (its own noise adds about its square to every relMSE). */
    cJSON_AddNumberToObject(root, "reference_spp", o->ref.spp);
    cJSON_AddNumberToObject(root, "reference_seconds", o->ref.seconds);
    cJSON_AddNumberToObject(root, "reference_rel_error", o->ref.rel_error);
  }
  cJSON_AddStringToObject(root, "mask", "first camera hit on a translucent material");
  cJSON *methods = cJSON_AddArrayToObject(root, "methods");
  for (int i = 0; i < n; ++i) {
    cJSON_AddItemToArray(methods, method_json(&r[i], ss_compare_find_volpath(r, n)));
  }
  char path[4096 + 32];
  snprintf(path, sizeof path, "%s/results.json", dir);
  int rc = ss_json_write_file(root, path, "compare");
  cJSON_Delete(root);
  return rc == 0 ? 0 : 1;
}

static int write_csv(const char *dir, const ss_compare_result *r, int n) {
  char path[4096 + 32];
  snprintf(path, sizeof path, "%s/results.csv", dir);
  ss_text_buf b = {0};
  ss_text_printf(&b, "method,seconds,spp,samples,rel_mse");
  for (int c = 0; c < 3; ++c) {
    const char *ch = channel_names[c];
    ss_text_printf(&b, ",rel_mse_%s,rmse_%s,mean_%s,mean_ratio_%s", ch, ch, ch, ch);
  }
  ss_text_printf(&b, ",time_to_volpath_error,converged_rel_mse\n");
  for (int i = 0; i < n; ++i) {
    const ss_image_error *e = &r[i].error;
    /* Method texts hold no ',' (the --methods separator) nor '"'. */
    ss_text_printf(&b, "%s,%.6g,%u,%llu,%.6g", r[i].method.text, r[i].seconds, r[i].spp,
                   r[i].samples, e->rel_mse);
    for (int c = 0; c < 3; ++c) {
      ss_text_printf(&b, ",%.6g,%.6g,%.6g,%.6g", e->rel_mse_c[c], e->rmse[c], e->mean[c],
                     ss_image_error_mean_ratio(e, c));
    }
    ss_compare_curve curve;
    ss_compare_curve_of(&r[i], ss_compare_find_volpath(r, n), &curve);
    /* inf: the fitted line never reaches volpath's error; nan: no volpath. */
    ss_text_printf(&b, ",%.6g,%.6g\n", curve.time_to_volpath, curve.converged);
  }
  ss_error err;
  ss_status st = ss_text_save(&b, path, SS_FILE_CSV, &err);
  ss_text_free(&b);
  if (st != SS_OK) {
    fprintf(stderr, "subsurf compare: %s\n", err.message);
    return 1;
  }
  return 0;
}

int ss_compare_write_results(const ss_compare_options *o) {
  int rc = write_json(o);
  return rc ? rc : write_csv(o->dir, o->results, o->num_methods);
}
