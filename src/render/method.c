/* Comparison methods: parsing and applying (method.h). */
#include "subsurf/method.h"

#include "subsurf/integrator.h"
#include "subsurf/subsurface.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

/* Sets option "NAME=VALUE" (`opt`, modified) of the model. */
static ss_status parse_option(ss_method *m, const ss_bssrdf_ops *ops, char *opt, ss_error *err) {
  char *eq = strchr(opt, '=');
  if (!eq || eq == opt || !eq[1]) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "method '%s': expected an option NAME=VALUE after ':', got '%s'", m->text,
                        opt);
  }
  *eq = '\0';
  ss_error e;
  if (ss_bssrdf_params_set_option(&m->options, ops, opt, eq + 1, &e) != SS_OK) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "method '%s': %s", m->text, e.message);
  }
  return SS_OK;
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
  if (!ops) {
    if (!ss_integrator_find(buf)) {
      return unknown(text, buf, err);
    }
    if (rest) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "method '%s': integrator %s takes no options here", text, buf);
    }
    snprintf(m->integrator, sizeof m->integrator, "%s", buf);
    return SS_OK;
  }
  snprintf(m->integrator, sizeof m->integrator, "bssrdf");
  snprintf(m->model, sizeof m->model, "%s", buf);
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
  snprintf(scene->integrator.name, sizeof scene->integrator.name, "%s", m->integrator);
  if (!m->model[0]) {
    return SS_OK;
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
  return SS_OK;
}

void ss_method_file_name(const ss_method *m, char *buf, size_t size) {
  snprintf(buf, size, "%s", m->text);
  for (char *c = buf; *c; ++c) {
    if (!isalnum((unsigned char)*c) && *c != '.' && *c != '_' && *c != '-') {
      *c = '_';
    }
  }
}
