/* Spectral MIS: the hero channel's choice and the channel ratios
 * (spectral_mis.h). */
#include "render/integrators/spectral_mis.h"

#include "subsurf/volume.h"

#include <math.h>

void ss_spectral_renormalise(ss_rgb *beta, ss_spectral *sp) {
  double k = ss_rgb_average(sp->r_u);
  if (k > 0.0 && isfinite(k)) {
    *beta = ss_rgb_scale(*beta, 1.0 / k);
    sp->r_u = ss_rgb_scale(sp->r_u, 1.0 / k);
    sp->r_l = ss_rgb_scale(sp->r_l, 1.0 / k);
  }
}

/* The probabilities of the hero channels in medium `med`: in proportion to
 * each channel's diffusion length 1/sigma_tr, sigma_tr = sqrt(3 sigma_a
 * sigma_t') (the effective transport coefficient of Jensen2001's
 * dipole), mixed with 10 % of the uniform choice (defensive sampling: no
 * channel's technique drops below 1/30). Light travels furthest in the
 * channel with the longest diffusion length, whose long walks vary most
 * (the red of skin, 0.73 against 0.27 and 0.14 for green and
 * blue). A medium without absorption in a channel, or none, chooses
 * uniformly. */
static void hero_pmf(const ss_medium *med, double pmf[3]) {
  double len[3], total = 0.0;
  for (int c = 0; c < 3 && med; ++c) {
    const ss_medium_optics *o = &med->optics;
    double st_prime = o->sigma_s.c[c] * (1.0 - o->g.c[c]) + o->sigma_a.c[c];
    len[c] = 1.0 / sqrt(3.0 * o->sigma_a.c[c] * st_prime);
    total += len[c];
  }
  for (int c = 0; c < 3; ++c) {
    pmf[c] = med && isfinite(total) && total > 0.0 ? 0.9 * len[c] / total + 0.1 / 3.0 : 1.0 / 3.0;
  }
}

/* The hero is chosen when the path first needs it (its first free flight,
 * with the pmf of the medium it runs through, or a shadow ray's tracking,
 * uniformly) from the number drawn at the path's start. Until then every
 * channel's density is the same, so choosing then equals choosing at the
 * start with a pmf that depends on the path so far (unbiased for any pmf
 * without a zero): r_u and r_l take the factor 3 pmf_i, so that the
 * one-sample balance heuristic divides by sum_i pmf_i p_i (the header's
 * estimate). Equal probabilities keep the uniform choice (int)(3 u) and
 * the ratios unchanged. */
void ss_spectral_choose_hero(ss_spectral *sp, const ss_medium *med) {
  if (sp->hero >= 0) {
    return;
  }
  double pmf[3];
  hero_pmf(med, pmf);
  if (pmf[0] == pmf[1] && pmf[1] == pmf[2]) {
    sp->hero = ss_volume_uniform_hero(sp->hero_u);
    return;
  }
  ss_rgb k = ss_rgb_make(3.0 * pmf[0], 3.0 * pmf[1], 3.0 * pmf[2]);
  sp->r_u = ss_rgb_mul(sp->r_u, k);
  sp->r_l = ss_rgb_mul(sp->r_l, k);
  sp->hero = sp->hero_u < pmf[0] ? 0 : sp->hero_u < pmf[0] + pmf[1] ? 1 : 2;
}

int ss_spectral_hero(const ss_spectral *sp) {
  return sp->hero >= 0 ? sp->hero : ss_volume_uniform_hero(sp->hero_u);
}

ss_rgb ss_spectral_emitted(ss_rgb beta, const ss_spectral *sp, ss_rgb le, double p_light, int mis) {
  if (!mis) {
    return ss_rgb_scale(ss_rgb_mul(beta, le), 1.0 / ss_rgb_average(sp->r_u));
  }
  ss_rgb denom = ss_rgb_madd(sp->r_u, sp->r_l, p_light);
  return ss_rgb_scale(ss_rgb_mul(beta, le), 1.0 / ss_rgb_average(denom));
}
