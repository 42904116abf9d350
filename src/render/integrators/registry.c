/* The table of integrators. */
#include "subsurf/integrator.h"

#include <stdio.h>
#include <string.h>

extern const ss_integrator_ops ss_integrator_bssrdf;
extern const ss_integrator_ops ss_integrator_fem;
extern const ss_integrator_ops ss_integrator_hierarchical;
extern const ss_integrator_ops ss_integrator_hybrid;
extern const ss_integrator_ops ss_integrator_path;
extern const ss_integrator_ops ss_integrator_volpath;

static const ss_integrator_ops *const table[] = {
    &ss_integrator_path,         &ss_integrator_volpath, &ss_integrator_bssrdf,
    &ss_integrator_hierarchical, &ss_integrator_hybrid,  &ss_integrator_fem,
};

size_t ss_integrator_count(void) { return sizeof table / sizeof table[0]; }

const ss_integrator_ops *ss_integrator_at(size_t i) {
  return i < ss_integrator_count() ? table[i] : NULL;
}

const ss_integrator_ops *ss_integrator_find(const char *name) {
  for (size_t i = 0; i < ss_integrator_count(); ++i) {
    if (!strcmp(table[i]->name, name)) {
      return table[i];
    }
  }
  return NULL;
}

void ss_integrator_names(char *buf, size_t size) {
  size_t used = 0;
  if (size > 0) {
    buf[0] = '\0';
  }
  for (size_t i = 0; i < ss_integrator_count() && used < size; ++i) {
    int n = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", table[i]->name);
    if (n < 0) {
      return;
    }
    used += (size_t)n;
  }
}

int ss_integrator_accepts_option(const ss_integrator_ops *ops, const char *option) {
  if (!strcmp(option, "max_depth") || !strcmp(option, "rr_depth")) {
    return 1;
  }
  for (const char *const *o = ops->options; o && *o; ++o) {
    if (!strcmp(*o, option)) {
      return 1;
    }
  }
  return 0;
}

ss_status ss_integrator_check(const ss_scene *scene, ss_error *err) {
  const ss_integrator_ops *ops = ss_integrator_find(scene->integrator.name);
  if (!ops) {
    char names[256];
    ss_integrator_names(names, sizeof names);
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "unknown integrator '%s' (known: %s)",
                        scene->integrator.name, names);
  }
  return ops->check ? ops->check(scene, err) : SS_OK;
}
