/* The BRDF approximation of the dipole BSSRDF (Jensen2001
 * sec. 2.4): under uniform illumination the BSSRDF integrates over the
 * surface to f_r = f_r^(1) + Ft(w_i) Ft(w_o) R_d / pi, with R_d the dipole's
 * closed-form total and f_r^(1) the single-scattering BRDF of single.c.
 *
 * Options: those of `dipole` and `single` (sigma_s, sigma_a, g, eta).
 * Light leaves where it entered: eval returns 0 (flag SS_BSSRDF_BRDF), the
 * brdf hook carries the model, there is no entry point to sample, and the
 * profile reports the two components it integrates (ms: the dipole's R_d(r),
 * ss: the single-scattering exitance). */
#include "bssrdf/bssrdf_util.h"

#include <stdlib.h>

extern const ss_bssrdf_ops ss_bssrdf_model_dipole;
extern const ss_bssrdf_ops ss_bssrdf_model_single;

typedef struct {
  void *dipole, *single;
} dipole_brdf;

static void dipole_brdf_destroy(void *state) {
  dipole_brdf *d = state;
  if (d) {
    if (d->dipole) {
      ss_bssrdf_model_dipole.destroy(d->dipole);
    }
    if (d->single) {
      ss_bssrdf_model_single.destroy(d->single);
    }
    free(d);
  }
}

static ss_status dipole_brdf_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  dipole_brdf *d = calloc(1, sizeof *d);
  if (!d) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "dipole-brdf: out of memory");
  }
  ss_bssrdf_params q = *p;
  ss_bssrdf_params_clear_options(&q); /* the closed form integrates the unclamped profile */
  ss_status st = ss_bssrdf_model_dipole.create(&q, &d->dipole, err);
  if (st == SS_OK) {
    st = ss_bssrdf_model_single.create(&q, &d->single, err);
  }
  if (st != SS_OK) {
    dipole_brdf_destroy(d);
    return st;
  }
  *state = d;
  return SS_OK;
}

/* Jensen et al. 2001, sec. 2.4: f_r = f_r^(1) + F R_d / pi, the dipole's BRDF
 * with its closed-form total (min_distance is off). */
static void dipole_brdf_brdf(const void *state, ss_vec3 w_i, ss_vec3 w_o,
                             double out[SS_BSSRDF_CHANNELS]) {
  const dipole_brdf *d = state;
  double ms[SS_BSSRDF_CHANNELS];
  ss_bssrdf_model_single.brdf(d->single, w_i, w_o, out);
  ss_bssrdf_model_dipole.brdf(d->dipole, w_i, w_o, ms);
  ss_channels_add(out, ms);
}

static void dipole_brdf_total(const void *state, double cos_i, double out[SS_BSSRDF_CHANNELS]) {
  const dipole_brdf *d = state;
  double ms[SS_BSSRDF_CHANNELS];
  ss_bssrdf_model_single.total_reflectance(d->single, cos_i, out);
  ss_bssrdf_model_dipole.total_reflectance(d->dipole, cos_i, ms);
  ss_channels_add(out, ms);
}

static void dipole_brdf_rd(const void *state, double out[SS_BSSRDF_CHANNELS]) {
  const dipole_brdf *d = state;
  double ms[SS_BSSRDF_CHANNELS];
  ss_bssrdf_model_single.rd(d->single, out);
  ss_bssrdf_model_dipole.rd(d->dipole, ms);
  ss_channels_add(out, ms);
}

static void dipole_brdf_profile(const void *state, int channel, double r,
                                ss_bssrdf_profile_value *out) {
  const dipole_brdf *d = state;
  ss_bssrdf_profile_value ms = {0}, ss = {0};
  ss_bssrdf_model_dipole.profile(d->dipole, channel, r, &ms);
  ss_bssrdf_model_single.profile(d->single, channel, r, &ss);
  out->ms = ms.value;
  out->ss = ss.value;
  out->value = ms.value + ss.value;
}

static double dipole_brdf_max_radius(const void *state, int channel) {
  const dipole_brdf *d = state;
  return ss_bssrdf_model_dipole.max_radius(d->dipole, channel);
}

const ss_bssrdf_ops ss_bssrdf_model_dipole_brdf = {
    .name = "dipole-brdf",
    .summary = "BRDF approximation f_r^(1) + F Rd / pi (Jensen et al. 2001 sec. 2.4)",
    .flags = SS_BSSRDF_BRDF | SS_BSSRDF_ANGULAR,
    .create = dipole_brdf_create,
    .destroy = dipole_brdf_destroy,
    .max_radius = dipole_brdf_max_radius,
    .total_reflectance = dipole_brdf_total,
    .rd = dipole_brdf_rd,
    .profile = dipole_brdf_profile,
    .brdf = dipole_brdf_brdf,
};
