#include "cli/model_options.h"

#include <string.h>

void ss_model_options_init(ss_model_options *o) { memset(o, 0, sizeof *o); }

/* "beam-samples" -> "beam_samples" (and back). */
static void convert(char *dst, size_t size, const char *src, char from, char to) {
  snprintf(dst, size, "%s", src);
  for (char *c = dst; *c; ++c) {
    *c = *c == from ? to : *c;
  }
}

/* The declaration of `name` in the first model that has it. */
static const ss_option *any_model(const char *name) {
  for (size_t i = 0; i < ss_bssrdf_model_count(); ++i) {
    const ss_option *opt = ss_bssrdf_option_find(ss_bssrdf_model_at(i), name);
    if (opt) {
      return opt;
    }
  }
  return NULL;
}

static int record(ss_model_options *o, const char *cmd, const char *snake, const char *value) {
  for (int i = 0; i < o->n; ++i) {
    if (!strcmp(o->args[i].name, snake)) {
      o->args[i].value = value;
      return 1;
    }
  }
  if (o->n == SS_MODEL_MAX_ARGS) {
    fprintf(stderr, "subsurf %s: at most %d model options\n", cmd, SS_MODEL_MAX_ARGS);
    return -1;
  }
  snprintf(o->args[o->n].name, sizeof o->args[o->n].name, "%s", snake);
  o->args[o->n++].value = value;
  return 1;
}

int ss_model_options_parse(ss_model_options *o, const char *cmd, const char *name,
                           const char *value) {
  char snake[64];
  convert(snake, sizeof snake, name, '-', '_');
  return any_model(snake) ? record(o, cmd, snake, value) : 0;
}

int ss_model_options_flag(ss_model_options *o, const char *name) {
  char snake[64];
  convert(snake, sizeof snake, name, '-', '_');
  const ss_option *opt = any_model(snake);
  return opt && opt->type == SS_OPTION_BOOL ? record(o, "", snake, "true") > 0 : 0;
}

int ss_model_options_check(const ss_model_options *o, const char *cmd,
                           const ss_bssrdf_ops *const *models, int n) {
  for (int i = 0; i < o->n; ++i) {
    int taken = 0;
    for (int k = 0; k < n && !taken; ++k) {
      taken = ss_bssrdf_option_find(models[k], o->args[i].name) != NULL;
    }
    if (taken) {
      continue;
    }
    char kebab[64];
    convert(kebab, sizeof kebab, o->args[i].name, '_', '-');
    if (n == 1) {
      char snake[512], names[512];
      ss_bssrdf_option_names(models[0], snake, sizeof snake);
      convert(names, sizeof names, snake, '_', '-');
      fprintf(stderr, "subsurf %s: --%s: model '%s' has no such option (its options: %s)\n", cmd,
              kebab, models[0]->name, names);
    } else {
      fprintf(stderr,
              "subsurf %s: --%s: none of the chosen models has this option "
              "(see --help)\n",
              cmd, kebab);
    }
    return -1;
  }
  return 0;
}

int ss_model_options_apply(const ss_model_options *o, const char *cmd, const ss_bssrdf_ops *ops,
                           ss_bssrdf_params *p) {
  for (int i = 0; i < o->n; ++i) {
    if (!ss_bssrdf_option_find(ops, o->args[i].name)) {
      continue;
    }
    ss_error err;
    if (ss_bssrdf_params_set_option(p, ops, o->args[i].name, o->args[i].value, &err) != SS_OK) {
      char kebab[64];
      convert(kebab, sizeof kebab, o->args[i].name, '_', '-');
      fprintf(stderr, "subsurf %s: --%s: %s\n", cmd, kebab, err.message);
      return -1;
    }
  }
  return 0;
}

cJSON *ss_model_options_to_json(const ss_model_options *o) {
  cJSON *j = cJSON_CreateObject();
  for (int i = 0; i < o->n; ++i) {
    cJSON_AddStringToObject(j, o->args[i].name, o->args[i].value);
  }
  return j;
}

static void option_help(FILE *out, const ss_option *opt) {
  static const char *const meta[] = {" X", " N", "", " TEXT", " NAME"};
  char flag[96], kebab[64], describe[512];
  convert(kebab, sizeof kebab, opt->name, '_', '-');
  snprintf(flag, sizeof flag, "--%s%s%s", kebab, opt->meta ? " " : "",
           opt->meta ? opt->meta : meta[opt->type]);
  ss_bssrdf_option_describe(opt, describe, sizeof describe);
  fprintf(out, "      %-22s %s\n      %-22s (%s)\n", flag, opt->help, "", describe);
}

void ss_model_list_help(FILE *out) {
  fprintf(out, "models (each followed by the options it takes; a bool option "
               "is a flag, or\n"
               "--name=true|false):\n");
  for (size_t i = 0; i < ss_bssrdf_model_count(); ++i) {
    const ss_bssrdf_ops *m = ss_bssrdf_model_at(i);
    fprintf(out, "  %-18s %s\n", m->name, m->summary);
    for (size_t k = 0; k < ss_bssrdf_option_count(m); ++k) {
      option_help(out, &m->options[k]);
    }
  }
}
