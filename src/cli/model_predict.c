#include "cli/model_predict.h"

#include "cli/args.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include "subsurf/fresnel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int ss_model_create(const char *cmd, const char *name, const ss_model_options *mo,
                    const ss_halfspace_params *p, ss_bssrdf **out) {
  const ss_bssrdf_ops *ops = ss_bssrdf_model_find(name);
  if (!ops) {
    char names[512];
    ss_bssrdf_model_names(names, sizeof names);
    fprintf(stderr, "subsurf %s: --model: unknown model '%s'; known models: %s\n", cmd, name,
            names);
    return -1;
  }
  ss_bssrdf_params bp;
  ss_bssrdf_params_default(&bp);
  /* one channel in all three: the model's quadrature scales follow its medium */
  int c = p->channel;
  bp.medium = ss_medium_optics_gray(p->medium.sigma_s.c[c], p->medium.sigma_a.c[c],
                                    p->medium.g.c[c], p->medium.phase);
  bp.medium.flakes = p->medium.flakes; /* refused by the models that do not take them */
  bp.eta = p->eta;
  ss_error err;
  if (isfinite(p->thickness)) {
    if (!ss_bssrdf_option_find(ops, "thickness")) {
      fprintf(stderr, "subsurf %s: --thickness: model '%s' has no thickness option (%s)\n", cmd,
              name,
              ops->flags & SS_BSSRDF_SLAB ? "its options set the geometry"
                                          : "it describes a half-space; multipole is a slab");
      return -1;
    }
    if (ss_bssrdf_params_set_option_number(&bp, ops, "thickness", p->thickness, &err) != SS_OK) {
      fprintf(stderr, "subsurf %s: --thickness: %s\n", cmd, err.message);
      return -1;
    }
  }
  if (ss_model_options_apply(mo, cmd, ops, &bp) != 0) {
    return -1;
  }
  if (ss_bssrdf_create_ops(ops, &bp, out, &err) != SS_OK) {
    fprintf(stderr, "subsurf %s: %s\n", cmd, err.message);
    return -1;
  }
  return 0;
}

static ss_estimate exact(double v) {
  ss_estimate e = {v, 0.0};
  return e;
}

int ss_model_predict(const char *cmd, const ss_bssrdf *b, const ss_halfspace_params *p, int channel,
                     ss_halfspace_result **out) {
  ss_halfspace_result *r = NULL;
  ss_error err;
  if (ss_halfspace_result_create(p, &r, &err) != SS_OK) {
    fprintf(stderr, "subsurf %s: %s\n", cmd, err.message);
    return -1;
  }
  double cos_i = cos(p->theta_i), v[SS_BSSRDF_CHANNELS];
  ss_bssrdf_total_reflectance(b, cos_i, v);
  r->reflectance = exact(v[channel]);
  ss_bssrdf_total_transmittance(b, cos_i, v);
  r->transmittance = exact(v[channel]);
  r->specular = exact(ss_fresnel_dielectric(cos_i, ss_bssrdf_entry_eta(b)));
  r->absorbed = exact(1.0 - r->specular.value - r->reflectance.value - r->transmittance.value);
  r->truncated = exact(0.0);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < p->rbins; ++i) {
    if (ss_cli_interrupted()) {
      continue; /* the caller reports the interrupt */
    }
    double m[SS_BSSRDF_CHANNELS];
    ss_bssrdf_radial_average(b, cos_i, r->r_lo[i], r->r_hi[i], m);
    r->radial[i] = exact(m[channel]);
  }
  int cells = p->n_theta_o * p->xbins;
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < cells; ++k) {
    if (ss_cli_interrupted()) {
      continue;
    }
    int d = k / p->xbins, i = k % p->xbins;
    ss_vec3 w_o = ss_vec3_make(sin(p->theta_o[d]), 0.0, cos(p->theta_o[d]));
    double m[SS_BSSRDF_CHANNELS];
    ss_bssrdf_direction_average(b, cos_i, w_o, r->x_lo[i], r->x_hi[i], m);
    r->directions[k] = exact(m[channel]);
  }
  if (ss_result_check_finite(r, cmd) != 0) {
    ss_halfspace_result_destroy(r);
    return -1;
  }
  *out = r;
  return 0;
}

int ss_parse_radius_list(const char *cmd, const char *name, const char *text, double **out,
                         int *n) {
  int cap = 1;
  for (const char *c = text; *c; ++c) {
    cap += *c == ',';
  }
  double *v = malloc((size_t)cap * sizeof *v);
  if (!v) {
    fprintf(stderr, "subsurf %s: out of memory\n", cmd);
    return -1;
  }
  *n = ss_cli_number_list(text, 0.0, SS_HALFSPACE_MAX_LENGTH, v, cap);
  if (*n < 0) {
    fprintf(
        stderr,
        "subsurf %s: --%s: expected comma-separated radii in [0, %g] (e.g. 0.1,0.5,1), got '%s'\n",
        cmd, name, SS_HALFSPACE_MAX_LENGTH, text);
    free(v);
    return -1;
  }
  *out = v;
  return 0;
}
