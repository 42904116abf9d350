/* Comparison methods: parsing and applying (method.h). */
#include "subsurf/method.h"

#include "subsurf/integrator.h"
#include "subsurf/number.h"
#include "subsurf/subsurface.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* "max_depth, rr_depth, ..." : the options integrator `ops` accepts. */
static void integrator_option_names(const ss_integrator_ops *ops, char *buf, size_t size) {
  int used = snprintf(buf, size, "max_depth, rr_depth");
  for (const char *const *o = ops->options; o && *o && used >= 0 && (size_t)used < size; ++o) {
    used += snprintf(buf + used, size - (size_t)used, ", %s", *o);
  }
}

/* Sets integrator option `name` to the number `value`; max_depth and rr_depth
 * are integers in [0, 1e8] as in scene files (scene-format.md). */
static ss_status set_integrator_option(ss_method *m, const char *name, const char *value,
                                       ss_error *err) {
  double v;
  int depth = !strcmp(name, "max_depth") || !strcmp(name, "rr_depth");
  if (!ss_number_parse(value, &v) || (depth && (v != floor(v) || v < 0.0 || v > 1e8))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "method '%s': integrator option %s: expected %s, got '%s'", m->text, name,
                        depth ? "an integer in [0, 100000000]" : "a number", value);
  }
  int i = 0;
  while (i < m->num_integrator_options && strcmp(m->integrator_options[i].name, name)) {
    ++i;
  }
  if (i == SS_INTEGRATOR_MAX_OPTIONS) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "method '%s': too many integrator options",
                        m->text);
  }
  snprintf(m->integrator_options[i].name, SS_NAME_SIZE, "%s", name);
  m->integrator_options[i].value = v;
  m->num_integrator_options += i == m->num_integrator_options;
  return SS_OK;
}

/* Sets option "NAME=VALUE" (`opt`, modified): the model's when `model` (NULL
 * for an integrator method) declares NAME, else the integrator's. */
static ss_status parse_option(ss_method *m, const ss_bssrdf_ops *model, char *opt, ss_error *err) {
  char *eq = strchr(opt, '=');
  if (!eq || eq == opt || !eq[1]) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "method '%s': expected an option NAME=VALUE after ':', got '%s'", m->text,
                        opt);
  }
  *eq = '\0';
  ss_error e;
  if (model && ss_bssrdf_option_find(model, opt)) {
    if (ss_bssrdf_params_set_option(&m->options, model, opt, eq + 1, &e) != SS_OK) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "method '%s': %s", m->text, e.message);
    }
    return SS_OK;
  }
  const ss_integrator_ops *in = ss_integrator_find(m->integrator);
  if (!ss_integrator_accepts_option(in, opt)) {
    char names[1024] = "";
    size_t used = 0;
    if (model) {
      snprintf(names, sizeof names, "model %s: ", model->name);
      used = strlen(names);
      ss_bssrdf_option_names(model, names + used, sizeof names - used);
      used = strlen(names);
      snprintf(names + used, sizeof names - used, "; ");
      used = strlen(names);
    }
    snprintf(names + used, sizeof names - used, "integrator %s: ", in->name);
    used = strlen(names);
    integrator_option_names(in, names + used, sizeof names - used);
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "method '%s': unknown option '%s' (%s)",
                        m->text, opt, names);
  }
  return set_integrator_option(m, opt, eq + 1, err);
}

static ss_status unknown(const char *text, const char *name, ss_error *err) {
  char integrators[256], models[1024];
  ss_integrator_names(integrators, sizeof integrators);
  ss_bssrdf_model_names(models, sizeof models);
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "method '%s': unknown name '%s' (integrators: %s; models: %s)", text, name,
                      integrators, models);
}

ss_status ss_method_parse(const char *text, ss_method *m, ss_error *err) {
  memset(m, 0, sizeof *m);
  ss_bssrdf_params_default(&m->options);
  if (strlen(text) >= sizeof m->text) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "method '%.40s...': longer than %zu bytes",
                        text, sizeof m->text - 1);
  }
  snprintf(m->text, sizeof m->text, "%s", text);
  char buf[sizeof m->text];
  snprintf(buf, sizeof buf, "%s", text);
  char *rest = strchr(buf, ':');
  if (rest) {
    *rest++ = '\0';
  }
  if (!buf[0] || strlen(buf) >= SS_NAME_SIZE) {
    return unknown(text, buf, err);
  }
  const ss_bssrdf_ops *ops = ss_bssrdf_model_find(buf);
  if (!ops && !ss_integrator_find(buf)) {
    return unknown(text, buf, err);
  }
  snprintf(m->integrator, sizeof m->integrator, "%s", ops ? "bssrdf" : buf);
  if (ops) {
    snprintf(m->model, sizeof m->model, "%s", buf);
  }
  while (rest) {
    char *next = strchr(rest, ':');
    if (next) {
      *next++ = '\0';
    }
    ss_status st = parse_option(m, ops, rest, err);
    if (st != SS_OK) {
      return st;
    }
    rest = next;
  }
  return SS_OK;
}

ss_status ss_method_apply(const ss_method *m, ss_scene *scene, ss_error *err) {
  if (strcmp(scene->integrator.name, m->integrator)) {
    scene->integrator.cache[0] = '\0'; /* the scene's cache was another integrator's */
  }
  snprintf(scene->integrator.name, sizeof scene->integrator.name, "%s", m->integrator);
  for (int i = 0; i < m->num_integrator_options; ++i) {
    const ss_integrator_option *o = &m->integrator_options[i];
    if (!strcmp(o->name, "max_depth")) {
      scene->integrator.max_depth = (int)o->value;
    } else if (!strcmp(o->name, "rr_depth")) {
      scene->integrator.rr_depth = (int)o->value;
    } else {
      ss_status st = ss_scene_set_integrator_option(scene, o->name, o->value, err);
      if (st != SS_OK) {
        return st;
      }
    }
  }
  if (!m->model[0]) {
    return ss_integrator_check(scene, err);
  }
  for (size_t i = 0; i < scene->num_materials; ++i) {
    ss_material *mat = &scene->materials[i];
    if (mat->kind != SS_MATERIAL_INTERFACE || mat->medium < 0) {
      continue;
    }
    snprintf(mat->bssrdf, sizeof mat->bssrdf, "%s", m->model);
    mat->bssrdf_options = m->options;
    mat->lod = SS_LOD_BSSRDF;
  }
  ss_subsurface *built = NULL;
  ss_status st = ss_subsurface_create(scene, &built, err);
  if (st != SS_OK) {
    return st;
  }
  ss_subsurface_destroy(scene->subsurface);
  scene->subsurface = built;
  return ss_integrator_check(scene, err);
}

void ss_method_file_name(const ss_method *m, char *buf, size_t size) {
  snprintf(buf, size, "%s", m->text);
  for (char *c = buf; *c; ++c) {
    if (!isalnum((unsigned char)*c) && *c != '.' && *c != '_' && *c != '-') {
      *c = '_';
    }
  }
}
