/* A medium's optical coefficients (medium_optics.h). */
#include "subsurf/medium_optics.h"

#include <math.h>

ss_medium_optics ss_medium_optics_gray(double sigma_s, double sigma_a, double g,
                                       ss_phase_type phase) {
  ss_medium_optics m;
  m.sigma_s = ss_rgb_gray(sigma_s);
  m.sigma_a = ss_rgb_gray(sigma_a);
  m.g = ss_rgb_gray(g);
  m.phase = phase;
  m.flakes = (ss_medium_flakes){0};
  return m;
}

ss_medium_optics ss_medium_optics_from_preset(const ss_medium_preset *preset, double scale,
                                              double g, ss_phase_type phase) {
  ss_medium_optics m = ss_medium_optics_gray(0.0, 0.0, g, phase);
  for (int c = 0; c < 3; ++c) {
    /* sigma_s' = (1 - g) sigma_s (the similarity relation). */
    m.sigma_s.c[c] = preset->sigma_s_prime[c] * scale / (1.0 - g);
    m.sigma_a.c[c] = preset->sigma_a[c] * scale;
  }
  return m;
}

static int nonneg(double v) { return isfinite(v) && v >= 0.0; }

ss_status ss_medium_optics_check(const ss_medium_optics *m, ss_error *err) {
  static const char ch[] = "RGB";
  for (int c = 0; c < 3; ++c) {
    double s = m->sigma_s.c[c], a = m->sigma_a.c[c], g = m->g.c[c];
    if (!nonneg(s)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "sigma_s[%c] must be finite and >= 0, got %g", ch[c], s);
    }
    if (!nonneg(a)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "sigma_a[%c] must be finite and >= 0, got %g", ch[c], a);
    }
    if (!(s + a > 0.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "sigma_s + sigma_a of channel %c must be > 0", ch[c]);
    }
    if (!isfinite(g) || fabs(g) >= 1.0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "g[%c] must lie in (-1, 1), got %g", ch[c],
                          g);
    }
    if (!((1.0 - g) * s + a > 0.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "the reduced extinction of channel %c is zero", ch[c]);
    }
    ss_phase phase;
    ss_status st = ss_phase_init(&phase, m->phase, g, err);
    if (st != SS_OK) {
      return st;
    }
  }
  return ss_medium_flakes_check(&m->flakes, err);
}
