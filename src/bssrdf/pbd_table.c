/* The per-material PBD table (pbd_table.h). */
#include "bssrdf/pbd_table.h"

#include "subsurf/sampling.h"
#include "subsurf/table_index.h"

#include <math.h>

enum { NT = SS_PBD_TABLE_THETA, NP = SS_PBD_TABLE_PHI, NR = SS_PBD_TABLE_R };

static const double theta_step = 0.5 * SS_PI / (NT - 1), phi_step = SS_PI / (NP - 1);

/* log of a non-negative value; exp() of the floor is 0 */
static double safe_log(double v) { return v > 0.0 && isfinite(v) ? log(v) : -745.0; }

void ss_pbd_table_build(ss_pbd_table *t, const ss_pbd *p, double r_lo, double r_hi) {
  double log_q = log(r_hi / r_lo) / (NR - 1);
  t->inv_log_q = 1.0 / log_q;
  for (int k = 0; k < NR; ++k) {
    t->r[k] = r_lo * exp(k * log_q);
    t->ln_ss[k] = safe_log(ss_pbd_ss(p, t->r[k]));
  }
  for (int i = 0; i < NT; ++i) {
    ss_pbd_beam beam = ss_pbd_beam_make(p, i * theta_step);
    for (int j = 0; j < NP; ++j) {
      for (int k = 0; k < NR; ++k) {
        t->ln_ms[i][j][k] = safe_log(ss_pbd_ms(p, &beam, t->r[k], j * phi_step));
      }
    }
  }
}

/* Cell index and fraction of x on a uniform grid of n nodes, step h. */
static int cell(double x, double h, int n, double *f) {
  double u = fmax(0.0, x / h);
  int i = ss_table_cell(u, n - 1);
  if (i < 0) {
    *f = 1.0;
    return n - 2;
  }
  *f = u - i;
  return i;
}

double ss_pbd_table_eval(const ss_pbd_table *t, const ss_pbd *p, double theta, double r,
                         double phi) {
  if (!(r >= t->r[0]) || !(r <= t->r[NR - 1])) {
    ss_pbd_beam beam = ss_pbd_beam_make(p, theta);
    return ss_pbd_ms(p, &beam, r, phi) + ss_pbd_ss(p, r);
  }
  int k = ss_table_cell_clamped(log(r / t->r[0]) * t->inv_log_q, NR - 1);
  double fr = (r - t->r[k]) / (t->r[k + 1] - t->r[k]), ft, fp;
  int i = cell(theta, theta_step, NT, &ft), j = cell(phi, phi_step, NP, &fp);
  double w[2][2] = {{(1.0 - ft) * (1.0 - fp), (1.0 - ft) * fp}, {ft * (1.0 - fp), ft * fp}};
  double ln_ms = 0.0;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      const double *v = &t->ln_ms[i + a][j + b][k];
      ln_ms += w[a][b] * ((1.0 - fr) * v[0] + fr * v[1]);
    }
  }
  double ln_ss = (1.0 - fr) * t->ln_ss[k] + fr * t->ln_ss[k + 1];
  return exp(ln_ms) + exp(ln_ss);
}
