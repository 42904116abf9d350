/* Stack files of `subsurf layer --stack` (layer_stack.h). */
#include "io/layer_stack.h"

#include "io/json_path.h"
#include "io/json_strict.h"
#include "io/scene_file.h"

#include "subsurf/number.h"

#include <stdlib.h>
#include <string.h>

int ss_layer_bottom_parse(const char *text, ss_layer_bottom *bottom, double *albedo) {
  if (!strcmp(text, "same")) {
    *bottom = SS_LAYER_BOTTOM_SAME;
    return 1;
  }
  if (!strcmp(text, "index-matched")) {
    *bottom = SS_LAYER_BOTTOM_MATCHED;
    return 1;
  }
  if (strncmp(text, "diffuse:", 8) != 0) {
    return 0;
  }
  double a;
  if (!ss_number_parse(text + 8, &a) || !(a >= 0.0 && a <= 1.0)) {
    return 0;
  }
  *bottom = SS_LAYER_BOTTOM_DIFFUSE;
  *albedo = a;
  return 1;
}

const char *ss_layer_bottom_name(ss_layer_bottom bottom) {
  switch (bottom) {
  case SS_LAYER_BOTTOM_MATCHED:
    return "index-matched";
  case SS_LAYER_BOTTOM_DIFFUSE:
    return "diffuse";
  default:
    return "same";
  }
}

/* One layer: {"tau", "albedo"} or {"sigma_s", "sigma_a", "thickness"}, and
 * "phase" (iso, hg, gauss) with "g". */
static ss_status read_layer(ss_json_ctx *c, const cJSON *v, ss_layer_medium *m) {
  static const char *const keys[] = {"tau",       "albedo", "sigma_s", "sigma_a",
                                     "thickness", "phase",  "g",       NULL};
  ss_status st = ss_json_expect_object(c, v);
  if (st == SS_OK) {
    st = ss_json_check_keys(c, v, keys);
  }
  if (st != SS_OK) {
    return st;
  }
  int optical = cJSON_HasObjectItem(v, "tau") || cJSON_HasObjectItem(v, "albedo");
  int physical = cJSON_HasObjectItem(v, "sigma_s") || cJSON_HasObjectItem(v, "sigma_a") ||
                 cJSON_HasObjectItem(v, "thickness");
  if (optical == physical) {
    return ss_json_fail(c, SS_ERR_PARSE,
                        "expected either \"tau\" and \"albedo\" or \"sigma_s\", \"sigma_a\" and "
                        "\"thickness\"");
  }
  if (optical) {
    m->albedo = 1.0;
    st = ss_json_require(c, v, "tau");
    if (st == SS_OK) {
      st = ss_json_number(c, v, "tau", SS_LAYER_MIN_TAU, SS_LAYER_MAX_TAU, &m->tau);
    }
    if (st == SS_OK) {
      st = ss_json_number(c, v, "albedo", 0.0, 1.0, &m->albedo);
    }
  } else {
    double sigma_s = 0.0, sigma_a = 0.0, d = 0.0;
    st = ss_json_require(c, v, "thickness");
    if (st == SS_OK) {
      st = ss_json_number(c, v, "sigma_s", 0.0, 1e6, &sigma_s);
    }
    if (st == SS_OK) {
      st = ss_json_number(c, v, "sigma_a", 0.0, 1e6, &sigma_a);
    }
    if (st == SS_OK) {
      st = ss_json_number(c, v, "thickness", 0.0, 1e6, &d);
    }
    if (st == SS_OK && !(d > 0.0)) {
      return ss_json_fail_key(c, "thickness", "must be > 0");
    }
    double tau = (sigma_s + sigma_a) * d;
    if (st == SS_OK && !(tau >= SS_LAYER_MIN_TAU && tau <= SS_LAYER_MAX_TAU)) {
      return ss_json_fail_key(c, "thickness",
                              "the optical depth (sigma_s + sigma_a) x thickness = %g is outside "
                              "[%g, %g]",
                              tau, SS_LAYER_MIN_TAU, SS_LAYER_MAX_TAU);
    }
    m->tau = tau;
    m->albedo = st == SS_OK ? sigma_s / (sigma_s + sigma_a) : 0.0;
  }
  char name[16] = "iso";
  double g = 0.0;
  ss_phase_type type = SS_PHASE_ISOTROPIC;
  if (st == SS_OK) {
    st = ss_json_string(c, v, "phase", name, sizeof name);
  }
  if (st == SS_OK && !ss_phase_type_from_name(name, &type)) {
    return ss_json_fail_key(c, "phase", "expected iso, hg or gauss, got '%s'", name);
  }
  if (st == SS_OK) {
    st = ss_json_number(c, v, "g", -1.0, 1.0, &g);
  }
  if (st == SS_OK && ss_phase_init(&m->phase, type, g, c->err) != SS_OK) {
    return ss_json_wrap(c, SS_ERR_PARSE);
  }
  return st;
}

static ss_status read_stack(ss_json_ctx *c, const cJSON *root, ss_layer_params *p, int *eta_set,
                            int *bottom_set) {
  static const char *const keys[] = {"eta", "bottom", "layers", NULL};
  ss_status st = ss_json_expect_object(c, root);
  if (st == SS_OK) {
    st = ss_json_check_keys(c, root, keys);
  }
  if (st == SS_OK) {
    st = ss_json_require(c, root, "layers");
  }
  if (st != SS_OK) {
    return st;
  }
  *eta_set = cJSON_HasObjectItem(root, "eta");
  st = ss_json_number(c, root, "eta", 0.1, 10.0, &p->eta);
  char bottom[64] = "";
  if (st == SS_OK) {
    st = ss_json_string(c, root, "bottom", bottom, sizeof bottom);
  }
  *bottom_set = bottom[0] != '\0';
  if (st == SS_OK && *bottom_set && !ss_layer_bottom_parse(bottom, &p->bottom, &p->bottom_albedo)) {
    return ss_json_fail_key(c, "bottom",
                            "expected same, index-matched or diffuse:A with A in [0, 1], got '%s'",
                            bottom);
  }
  const cJSON *layers = cJSON_GetObjectItemCaseSensitive(root, "layers");
  int n = cJSON_IsArray(layers) ? cJSON_GetArraySize(layers) : -1;
  if (st == SS_OK && (n < 1 || n > SS_LAYER_MAX_LAYERS)) {
    return ss_json_fail_key(c, "layers", "expected an array of 1 to %d layers, got %s",
                            SS_LAYER_MAX_LAYERS,
                            n < 0    ? "no array"
                            : n == 0 ? "none"
                                     : "more");
  }
  ss_json_push_key(c, "layers");
  for (int i = 0; i < n && st == SS_OK; ++i) {
    ss_json_push_index(c, i);
    st = read_layer(c, cJSON_GetArrayItem(layers, i), &p->layers[i]);
    ss_json_pop(c);
  }
  ss_json_pop(c);
  p->n_layers = n;
  return st;
}

ss_status ss_layer_stack_read(const char *path, ss_layer_params *p, int *eta_set, int *bottom_set,
                              ss_error *err) {
  char *text, dir[SS_PATH_SIZE];
  ss_status st = ss_scene_file_read(path, "a JSON text file", &text, dir, err);
  if (st != SS_OK) {
    return st;
  }
  st = ss_json_check_strict(text, path, err);
  cJSON *root = st == SS_OK ? cJSON_Parse(text) : NULL;
  if (st == SS_OK && !root) {
    st = ss_error_set(err, SS_ERR_PARSE, "%s: invalid JSON", path);
  }
  ss_json_ctx c = {.text = text, .file = path, .err = err};
  if (st == SS_OK) {
    st = ss_json_check_unique_keys(&c, root);
  }
  if (st == SS_OK) {
    st = read_stack(&c, root, p, eta_set, bottom_set);
  }
  cJSON_Delete(root);
  free(text);
  return st;
}
