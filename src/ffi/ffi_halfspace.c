/* The flat interface's half-space reference (ffi.h over halfspace.h). */
#include "subsurf/ffi.h"

#include "ffi/ffi_medium.h"

#include "subsurf/halfspace.h"

#include <stdio.h>

int ss_ffi_halfspace(const double sigma_s[3], const double sigma_a[3], const double g[3],
                     int channel, double eta, double theta_i, double thickness, uint64_t paths,
                     uint64_t seed, int threads, double rmin, double rmax, int rbins,
                     double out_totals[8], double *r_lo, double *r_hi, double *radial,
                     double *radial_error, char *err, size_t err_size) {
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium = ss_ffi_medium(sigma_s, sigma_a, g);
  p.channel = channel;
  p.eta = eta;
  p.theta_i = theta_i;
  p.thickness = thickness;
  p.paths = paths;
  p.seed = seed;
  p.threads = threads;
  p.rmin = rmin;
  p.rmax = rmax;
  p.rbins = rbins;
  p.n_theta_o = 0;
  ss_error e;
  ss_halfspace_result *r = NULL;
  ss_status st = ss_halfspace_validate(&p, &e);
  if (st == SS_OK) {
    st = ss_halfspace_run(&p, &r, &e);
  }
  if (st != SS_OK) {
    if (err && err_size > 0) {
      snprintf(err, err_size, "halfspace: %s", e.message);
    }
    return (int)st;
  }
  const ss_estimate totals[4] = {r->reflectance, r->transmittance, r->specular, r->absorbed};
  for (int i = 0; i < 4; i++) {
    out_totals[2 * i] = totals[i].value;
    out_totals[2 * i + 1] = totals[i].error;
  }
  for (int i = 0; i < r->rbins; i++) {
    if (r_lo) {
      r_lo[i] = r->r_lo[i];
    }
    if (r_hi) {
      r_hi[i] = r->r_hi[i];
    }
    if (radial) {
      radial[i] = r->radial[i].value;
    }
    if (radial_error) {
      radial_error[i] = r->radial[i].error;
    }
  }
  ss_halfspace_result_destroy(r);
  return 0;
}
