#include "cli/result_json.h"

#include "core/atomic_file.h"
#include "subsurf/version.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static cJSON *estimate(ss_estimate e) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddNumberToObject(o, "value", e.value);
  cJSON_AddNumberToObject(o, "stderr", e.error);
  return o;
}

static cJSON *numbers(const double *v, int n) {
  cJSON *a = cJSON_CreateArray();
  for (int i = 0; i < n; ++i) {
    cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
  }
  return a;
}

static void add_estimates(cJSON *obj, const ss_estimate *e, int n) {
  cJSON *value = cJSON_AddArrayToObject(obj, "value");
  cJSON *err = cJSON_AddArrayToObject(obj, "stderr");
  for (int i = 0; i < n; ++i) {
    cJSON_AddItemToArray(value, cJSON_CreateNumber(e[i].value));
    cJSON_AddItemToArray(err, cJSON_CreateNumber(e[i].error));
  }
}

void ss_result_add_json(cJSON *obj, const ss_halfspace_result *r) {
  cJSON_AddNumberToObject(obj, "paths", (double)r->paths);
  cJSON_AddNumberToObject(obj, "seconds", r->seconds);
  cJSON_AddBoolToObject(obj, "partial", r->partial);
  cJSON_AddNumberToObject(obj, "scatter_events", (double)r->scatter_events);
  cJSON_AddItemToObject(obj, "reflectance", estimate(r->reflectance));
  cJSON_AddItemToObject(obj, "transmittance", estimate(r->transmittance));
  cJSON_AddItemToObject(obj, "specular", estimate(r->specular));
  cJSON_AddItemToObject(obj, "absorbed", estimate(r->absorbed));
  cJSON_AddItemToObject(obj, "truncated", estimate(r->truncated));
  cJSON *radial = cJSON_AddObjectToObject(obj, "radial");
  cJSON_AddItemToObject(radial, "r_lo", numbers(r->r_lo, r->rbins));
  cJSON_AddItemToObject(radial, "r_hi", numbers(r->r_hi, r->rbins));
  add_estimates(radial, r->radial, r->rbins);
  cJSON *dirs = cJSON_AddArrayToObject(obj, "directions");
  for (int k = 0; k < r->n_theta_o; ++k) {
    cJSON *d = cJSON_CreateObject();
    cJSON_AddNumberToObject(d, "theta_o", r->theta_o[k] * 180.0 / 3.14159265358979323846);
    cJSON_AddItemToObject(d, "x_lo", numbers(r->x_lo, r->xbins));
    cJSON_AddItemToObject(d, "x_hi", numbers(r->x_hi, r->xbins));
    add_estimates(d, r->directions + (size_t)k * (size_t)r->xbins, r->xbins);
    cJSON_AddItemToArray(dirs, d);
  }
}

/* 1 when `j` holds a NaN or infinite number; `key` receives its path
 * ("radial.value[3]"). cJSON would print such a number as null. */
static int find_nonfinite(const cJSON *j, char *key, size_t size) {
  if (cJSON_IsNumber(j)) {
    return !isfinite(j->valuedouble);
  }
  size_t len = strlen(key);
  int i = 0;
  for (const cJSON *c = j->child; c; c = c->next, ++i) {
    if (cJSON_IsArray(j)) {
      snprintf(key + len, size - len, "[%d]", i);
    } else {
      snprintf(key + len, size - len, "%s%s", len ? "." : "", c->string ? c->string : "");
    }
    if (find_nonfinite(c, key, size)) {
      return 1;
    }
  }
  key[len] = '\0';
  return 0;
}

int ss_json_check_finite(const cJSON *json, const char *cmd) {
  char key[256] = "";
  if (find_nonfinite(json, key, sizeof key)) {
    fprintf(stderr,
            "subsurf %s: the result holds NaN or Inf at \"%s\" for these inputs; "
            "nothing written\n",
            cmd, key);
    return -1;
  }
  return 0;
}

int ss_result_check_finite(const ss_halfspace_result *r, const char *cmd) {
  cJSON *j = cJSON_CreateObject();
  if (!j) {
    return 0;
  }
  ss_result_add_json(j, r);
  int rc = ss_json_check_finite(j, cmd);
  cJSON_Delete(j);
  return rc;
}

/* `json` with "subsurf_version" as its first key when it is an object (a
 * copy: the caller's tree is left as it is), else `json` itself. */
static char *print_with_version(const cJSON *json) {
  if (!cJSON_IsObject(json)) {
    return cJSON_Print(json);
  }
  cJSON *out = cJSON_CreateObject();
  int ok = out && cJSON_AddStringToObject(out, "subsurf_version", ss_version());
  for (const cJSON *c = json->child; ok && c; c = c->next) {
    if (!strcmp(c->string, "subsurf_version")) {
      continue;
    }
    cJSON *copy = cJSON_Duplicate(c, 1);
    ok = copy && cJSON_AddItemToObject(out, c->string, copy);
    if (!ok) {
      cJSON_Delete(copy);
    }
  }
  char *text = ok ? cJSON_Print(out) : NULL;
  cJSON_Delete(out);
  return text;
}

int ss_json_write_file(const cJSON *json, const char *path, const char *cmd) {
  if (ss_json_check_finite(json, cmd) != 0) {
    return -1;
  }
  char *text = print_with_version(json);
  if (!text) {
    fprintf(stderr, "subsurf %s: out of memory while formatting JSON\n", cmd);
    return -1;
  }
  if (!strcmp(path, "-")) {
    fputs(text, stdout);
    fputc('\n', stdout);
    free(text);
    return fflush(stdout) == 0 ? 0 : -1;
  }
  ss_atomic_file f;
  ss_error err;
  size_t len = strlen(text);
  text[len] = '\n'; /* the terminating NUL becomes the file's last newline */
  ss_status st = ss_atomic_file_open(&f, path, SS_FILE_JSON, &err);
  if (st == SS_OK && (st = ss_atomic_file_write(&f, text, len + 1, &err)) != SS_OK) {
    ss_atomic_file_abort(&f);
  } else if (st == SS_OK) {
    st = ss_atomic_file_commit(&f, &err);
  }
  free(text);
  if (st != SS_OK) {
    fprintf(stderr, "subsurf %s: %s\n", cmd, err.message);
    return -1;
  }
  return 0;
}
