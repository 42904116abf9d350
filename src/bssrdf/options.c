/* Model options by name (bssrdf.h) through the shared contract
 * (option.h): declarations in each model's ops, values on the params. */
#include "subsurf/bssrdf.h"

#include <string.h>

size_t ss_bssrdf_option_count(const ss_bssrdf_ops *ops) { return ss_option_count(ops->options); }

const ss_option *ss_bssrdf_option_find(const ss_bssrdf_ops *ops, const char *name) {
  return ss_option_find(ops->options, name);
}

void ss_bssrdf_option_names(const ss_bssrdf_ops *ops, char *buf, size_t size) {
  ss_option_names(ops->options, buf, size);
}

void ss_bssrdf_option_describe(const ss_option *o, char *buf, size_t size) {
  ss_option_describe(o, buf, size);
}

ss_status ss_bssrdf_params_set_option(ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                      const char *name, const char *value, ss_error *err) {
  return ss_option_set(p->options, &p->n_options, SS_BSSRDF_MAX_OPTIONS, ops->name, ops->options,
                       name, value, err);
}

ss_status ss_bssrdf_params_set_option_number(ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                             const char *name, double value, ss_error *err) {
  return ss_option_set_number(p->options, &p->n_options, SS_BSSRDF_MAX_OPTIONS, ops->name,
                              ops->options, name, value, err);
}

void ss_bssrdf_params_clear_options(ss_bssrdf_params *p) {
  p->n_options = 0;
  memset(p->options, 0, sizeof p->options);
}

ss_status ss_bssrdf_params_check_options(const ss_bssrdf_params *p, const ss_bssrdf_ops *ops,
                                         ss_error *err) {
  return ss_option_check(p->options, p->n_options, ops->name, ops->options, err);
}

double ss_bssrdf_params_double(const ss_bssrdf_params *p, const ss_option *opt) {
  return ss_option_get_number(p->options, p->n_options, opt);
}

int ss_bssrdf_params_int(const ss_bssrdf_params *p, const ss_option *opt) {
  return (int)ss_option_get_number(p->options, p->n_options, opt);
}

int ss_bssrdf_params_bool(const ss_bssrdf_params *p, const ss_option *opt) {
  return ss_option_get_number(p->options, p->n_options, opt) != 0.0;
}

int ss_bssrdf_params_choice(const ss_bssrdf_params *p, const ss_option *opt) {
  return (int)ss_option_get_number(p->options, p->n_options, opt);
}

const char *ss_bssrdf_params_string(const ss_bssrdf_params *p, const ss_option *opt) {
  return ss_option_get_text(p->options, p->n_options, opt);
}
