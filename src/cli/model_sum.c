#include "cli/model_sum.h"

#include <stdlib.h>
#include <string.h>

int ss_model_sum_parse(ss_model_sum *s, const char *cmd, const char *option, const char *name) {
  memset(s, 0, sizeof *s);
  s->name = name;
  s->text = strdup(name);
  if (!s->text) {
    fprintf(stderr, "subsurf %s: out of memory\n", cmd);
    return -1;
  }
  for (char *part = s->text;;) {
    char *plus = strchr(part, '+');
    if (plus) {
      *plus = '\0';
    }
    if (s->n == SS_MODEL_SUM_MAX) {
      fprintf(stderr, "subsurf %s: --%s: at most %d models in a sum, got '%s'\n", cmd, option,
              SS_MODEL_SUM_MAX, name);
      return -1;
    }
    if (!*part) {
      fprintf(stderr, "subsurf %s: --%s: expected a model name or a sum a+b, got '%s'\n", cmd,
              option, name);
      return -1;
    }
    if (!ss_bssrdf_model_find(part)) {
      char names[512];
      ss_bssrdf_model_names(names, sizeof names);
      fprintf(stderr, "subsurf %s: --%s: unknown model '%s'; known models: %s\n", cmd, option, part,
              names);
      return -1;
    }
    s->parts[s->n++] = part;
    if (!plus) {
      return 0;
    }
    part = plus + 1;
  }
}

int ss_model_sum_create(ss_model_sum *s, const char *cmd, const ss_model_options *mo,
                        const ss_halfspace_params *p) {
  for (int j = 0; j < s->n; ++j) {
    if (ss_model_create(cmd, s->parts[j], mo, p, &s->models[j]) != 0) {
      return -1;
    }
  }
  return 0;
}

/* Adds a model's prediction to another's. */
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

int ss_model_sum_predict(const ss_model_sum *s, const char *cmd, const ss_halfspace_params *p,
                         int channel, ss_halfspace_result **out) {
  *out = NULL;
  for (int j = 0; j < s->n; ++j) {
    ss_halfspace_result *r = NULL;
    if (ss_model_predict(cmd, s->models[j], p, channel, &r) != 0) {
      ss_halfspace_result_destroy(*out);
      *out = NULL;
      return -1;
    }
    if (j == 0) {
      *out = r;
    } else {
      add_prediction(*out, r);
      ss_halfspace_result_destroy(r);
    }
  }
  return 0;
}

double ss_model_sum_rd(const ss_model_sum *s, int channel) {
  double sum = 0.0;
  for (int j = 0; j < s->n; ++j) {
    double v[SS_BSSRDF_CHANNELS];
    ss_bssrdf_rd(s->models[j], v);
    sum += v[channel];
  }
  return sum;
}

int ss_model_sum_has_profile(const ss_model_sum *s) {
  for (int j = 0; j < s->n; ++j) {
    if (ss_bssrdf_flags(s->models[j]) & SS_BSSRDF_BRDF) {
      return 0;
    }
  }
  return 1;
}

void ss_model_sum_profile(const ss_model_sum *s, int channel, double r,
                          ss_bssrdf_profile_value *out) {
  memset(out, 0, sizeof *out);
  for (int j = 0; j < s->n; ++j) {
    ss_bssrdf_profile_value v;
    ss_bssrdf_profile(s->models[j], channel, r, &v);
    out->value += v.value;
    out->ms += v.ms;
    out->ss += v.ss;
    out->t += v.t;
  }
}

static int all_slabs(const ss_model_sum *s) {
  for (int j = 0; j < s->n; ++j) {
    if (!(ss_bssrdf_flags(s->models[j]) & SS_BSSRDF_SLAB)) {
      return 0;
    }
  }
  return 1;
}

cJSON *ss_model_sum_profile_json(const ss_model_sum *s, int channel, const double *r, int n) {
  cJSON *j = cJSON_CreateObject();
  cJSON *rs = cJSON_AddArrayToObject(j, "r"), *value = cJSON_AddArrayToObject(j, "value");
  cJSON *ms = cJSON_AddArrayToObject(j, "ms"), *ss = cJSON_AddArrayToObject(j, "ss");
  cJSON *t = all_slabs(s) ? cJSON_AddArrayToObject(j, "t") : NULL;
  for (int i = 0; i < n; ++i) {
    ss_bssrdf_profile_value v;
    ss_model_sum_profile(s, channel, r[i], &v);
    cJSON_AddItemToArray(rs, cJSON_CreateNumber(r[i]));
    cJSON_AddItemToArray(value, cJSON_CreateNumber(v.value));
    cJSON_AddItemToArray(ms, cJSON_CreateNumber(v.ms));
    cJSON_AddItemToArray(ss, cJSON_CreateNumber(v.ss));
    if (t) {
      cJSON_AddItemToArray(t, cJSON_CreateNumber(v.t));
    }
  }
  return j;
}

void ss_model_sum_release(ss_model_sum *s) {
  for (int j = 0; j < s->n; ++j) {
    ss_bssrdf_destroy(s->models[j]);
    s->models[j] = NULL;
  }
}

void ss_model_sum_free(ss_model_sum *s) {
  ss_model_sum_release(s);
  free(s->text);
  s->text = NULL;
}
