#include "bssrdf/multipole.h"

#include "bssrdf/bssrdf_util.h"

#include <math.h>

void ss_multipole_setup(ss_multipole *m, ss_bssrdf_coeffs k, double d, double A_top,
                        double A_bottom, int max_pairs) {
  m->alpha_prime = k.alpha_prime;
  m->sigma_tr = k.sigma_tr;
  m->d = d;
  m->l = 1.0 / k.sigma_t_prime;
  /* Donner & Jensen 2005, eq. 11: z_b = 2 A D per face. */
  m->z_bt = 2.0 * A_top * k.D;
  double z_bb = 2.0 * A_bottom * k.D;
  if (!isfinite(d)) {
    m->n = 0;
    m->period = INFINITY;
    return;
  }
  m->period = 2.0 * (d + m->z_bt + z_bb);
  /* Pair i sits about i * period away: e^{-sigma_tr i period} < 1e-8. */
  double n = m->sigma_tr > 0.0 ? ceil(18.42 / (m->sigma_tr * m->period)) : max_pairs;
  m->n = (int)fmin(fmax(n, 1.0), (double)max_pairs);
}

/* Donner & Jensen 2005, eq. 10: z_r,i = i period + l, z_v,i = i period - l - 2 z_b. */
static double z_real(const ss_multipole *m, int i) { return (i ? i * m->period : 0.0) + m->l; }
static double z_virtual(const ss_multipole *m, int i) {
  return (i ? i * m->period : 0.0) - m->l - 2.0 * m->z_bt;
}

typedef double (*source_term)(double z, double x, double sigma_tr);

/* alpha'/(4 pi) sum_i [term(z_r,i) - term(z_v,i)] over the pairs, the depths
 * measured from the top face or, for transmittance, from the bottom (d - z). */
static inline double pair_sum(const ss_multipole *m, source_term term, double x, int from_bottom) {
  double sum = 0.0;
  for (int i = -m->n; i <= m->n; ++i) {
    double zr = z_real(m, i), zv = z_virtual(m, i);
    if (from_bottom) {
      zr = m->d - zr;
      zv = m->d - zv;
    }
    sum += term(zr, x, m->sigma_tr) - term(zv, x, m->sigma_tr);
  }
  return m->alpha_prime / (4.0 * SS_PI) * sum;
}

/* Donner & Jensen 2005, eq. 12. */
double ss_multipole_reflectance(const ss_multipole *m, double r) {
  return pair_sum(m, ss_dipole_source, r * r, 0);
}

/* Donner & Jensen 2005, eq. 13 (distances measured from the bottom face). */
double ss_multipole_transmittance(const ss_multipole *m, double r) {
  return isfinite(m->d) ? pair_sum(m, ss_dipole_source, r * r, 1) : 0.0;
}

/* 2 pi int_0^rho r z (1 + s d) e^{-s d} / d^3 dr = 2 pi z (e^{-s|z|}/|z| - e^{-s D}/D),
 * D = sqrt(rho^2 + z^2), since d/dd (-e^{-s d}/d) = (1 + s d) e^{-s d}/d^2.
 * At z = 0 the profile is a Dirac peak at r = 0 and the integral jumps by
 * 4 pi. Only the real source can lie on a face (the bottom one, at d = 1/sigma_t'),
 * from inside the slab, so z = 0 takes the limit z -> 0+: half of the source's
 * flux crosses that face. Virtual and image sources lie strictly outside. */
static double source_disk(double z, double rho, double s) {
  if (z == 0.0) {
    return rho > 0.0 ? 2.0 * SS_PI : 0.0;
  }
  double az = fabs(z);
  double outer = isfinite(rho) ? exp(-s * sqrt(rho * rho + z * z)) / sqrt(rho * rho + z * z) : 0.0;
  return 2.0 * SS_PI * z * (exp(-s * az) / az - outer);
}

double ss_multipole_reflectance_disk(const ss_multipole *m, double rho) {
  return pair_sum(m, source_disk, rho, 0);
}

double ss_multipole_transmittance_disk(const ss_multipole *m, double rho) {
  return isfinite(m->d) ? pair_sum(m, source_disk, rho, 1) : 0.0;
}
