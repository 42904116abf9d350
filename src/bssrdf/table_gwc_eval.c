/* Evaluating and sampling Ferrier's table (seed 004 sec. 4.1-4.2 and 7.1):
 * Catmull-Rom interpolation in (rho, theta, r), the analytic azimuthal
 * models of gwc.h, and the samplers whose densities are exactly those of the
 * interpolated table. */
#include "subsurf/catmull_rom.h"
#include "subsurf/gwc.h"
#include "subsurf/sampling.h"
#include "subsurf/table_gwc.h"

#include <math.h>

/* Spline weights of the (rho, theta) rows: a mixture of table rows. */
/* Theta weights on the grid extended by the mirror node at 100 deg, with
 * the ghost's weight folded onto the 80 deg node it mirrors. */
static int theta_weights(const ss_table_gwc *t, double theta, long *off, double w[4]) {
  if (!(theta <= t->theta[t->n_theta - 1]) ||
      !ss_cr_weights(t->n_theta + 1, t->theta, theta, off, w)) {
    return 0;
  }
  int ghost = (int)((long)t->n_theta - *off), mirror = ghost - 2;
  if (ghost >= 0 && ghost < 4) {
    w[mirror] += w[ghost];
    w[ghost] = 0.0;
  }
  return 1;
}

/* Albedo weights; a slice (one row) has weight 1 whatever rho. */
static int rho_weights(const ss_table_gwc *t, double rho, long *off, double w[4]) {
  if (t->n_rho == 1) {
    *off = 0;
    w[0] = 1.0;
    w[1] = w[2] = w[3] = 0.0;
    return 1;
  }
  return ss_cr_weights(t->n_rho, t->rho, rho, off, w);
}

static int row_mix(const ss_table_gwc *t, double rho, double theta, ss_cr_mix *m) {
  long oa, ob;
  double wa[4], wb[4];
  if (!rho_weights(t, rho, &oa, wa) || !theta_weights(t, theta, &ob, wb)) {
    return 0;
  }
  m->count = 0;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      double w = wa[a] * wb[b];
      if (w != 0.0) {
        m->row[m->count] = (size_t)(oa + a) * t->n_theta + (size_t)(ob + b);
        m->w[m->count] = w;
        m->count++;
      }
    }
  }
  return 1;
}

/* Spline value of the mixed rows of `data` (rows of n nodes of `stride`
 * floats, component `comp`) at x on `nodes`. */
static double mix_spline(const ss_cr_mix *m, const float *data, size_t n, const double *nodes,
                         size_t stride, size_t comp, double x) {
  long off;
  double w[4];
  if (!ss_cr_weights(n, nodes, x, &off, w)) {
    return 0.0;
  }
  double v = 0.0;
  for (int k = 0; k < 4; ++k) {
    if (w[k] == 0.0) {
      continue;
    }
    size_t node = (size_t)(off + k);
    for (int j = 0; j < m->count; ++j) {
      v += w[k] * m->w[j] * data[(m->row[j] * n + node) * stride + comp];
    }
  }
  return v;
}

/* The azimuthal model at radius r of the mixed rows: the normalised density
 * of phi and the radial energy E(r). */
typedef struct {
  double e;     /* E(r) >= 0 */
  int two_lobe; /* which member is valid */
  ss_gwc gwc;
  ss_wc2 wc2;
} cell;

static double clamp(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

/* Spline weights of x on n nodes as four weights on nodes *base..*base+3,
 * all inside the table (the zero weights of missing neighbours shifted). */
static int weights4(size_t n, const double *nodes, double x, size_t *base, double w[4]) {
  long off;
  if (!ss_cr_weights(n, nodes, x, &off, w)) {
    return 0;
  }
  if (off < 0) {
    w[0] = w[1];
    w[1] = w[2];
    w[2] = w[3];
    w[3] = 0.0;
    off = 0;
  } else if ((size_t)off + 3 >= n) {
    w[3] = w[2];
    w[2] = w[1];
    w[1] = w[0];
    w[0] = 0.0;
    off = (long)n - 4;
  }
  *base = (size_t)off;
  return 1;
}

/* E and the shape parameters at r: one pass over the 4 x 4 rows, four
 * consecutive radii each (the tables are contiguous along r). */
static void cell_at(const ss_table_gwc *t, const ss_cr_mix *m, double r, cell *c) {
  size_t rb = 0, sb = 0, ns = t->n_shape;
  double rw[4] = {0, 0, 0, 0}, sw[4];
  double e = 0.0, p[3] = {0.0, 0.0, 0.0};
  int inside = weights4(t->n_r, t->radius, r, &rb, rw);
  double rs = clamp(r, t->radius_shape[0], t->radius_shape[t->n_rs - 1]);
  weights4(t->n_rs, t->radius_shape, rs, &sb, sw);
  for (int j = 0; j < m->count; ++j) {
    const float *ev = t->energy + m->row[j] * t->n_r + rb;
    const float *sv = t->shape + (m->row[j] * t->n_rs + sb) * ns;
    double wj = m->w[j];
    if (inside) {
      e += wj * (rw[0] * ev[0] + rw[1] * ev[1] + rw[2] * ev[2] + rw[3] * ev[3]);
    }
    if (ns == 3) {
      p[0] += wj * (sw[0] * sv[0] + sw[1] * sv[3] + sw[2] * sv[6] + sw[3] * sv[9]);
      p[1] += wj * (sw[0] * sv[1] + sw[1] * sv[4] + sw[2] * sv[7] + sw[3] * sv[10]);
      p[2] += wj * (sw[0] * sv[2] + sw[1] * sv[5] + sw[2] * sv[8] + sw[3] * sv[11]);
    } else {
      p[0] += wj * (sw[0] * sv[0] + sw[1] * sv[2] + sw[2] * sv[4] + sw[3] * sv[6]);
      p[1] += wj * (sw[0] * sv[1] + sw[1] * sv[3] + sw[2] * sv[5] + sw[3] * sv[7]);
    }
  }
  c->e = fmax(0.0, e);
  c->two_lobe = t->fit == SS_TABLE_GWC_TWO_LOBE;
  if (c->two_lobe) {
    ss_wc2_from_harmonics(p, &c->wc2);
    return;
  }
  /* Ferrier 2016 algorithm 1: alpha = (E/r - beta)/(2 pi), with beta stored
   * as the fraction beta r / E, kept in [0, 1] so that alpha >= 0. */
  double total = r > 0.0 ? c->e / r : 0.0;
  c->gwc.beta = clamp(p[0], 0.0, 1.0) * total;
  c->gwc.c = clamp(p[1], 0.0, SS_GWC_C_MAX);
  c->gwc.alpha = (total - c->gwc.beta) / (2.0 * SS_PI);
  if (!(total > 0.0)) {
    c->gwc.alpha = 1.0 / (2.0 * SS_PI);
    c->gwc.beta = 0.0;
  }
}

/* Normalised azimuthal density from cos(phi) (both models are even). */
static double cell_pdf_cos(const cell *c, double cos_phi) {
  if (c->two_lobe) {
    return c->wc2.lambda * ss_wc_pdf_cos(cos_phi, c->wc2.c1) +
           (1.0 - c->wc2.lambda) * ss_wc_pdf_cos(cos_phi, c->wc2.c2);
  }
  return (c->gwc.alpha + c->gwc.beta * ss_wc_pdf_cos(cos_phi, c->gwc.c)) /
         (2.0 * SS_PI * c->gwc.alpha + c->gwc.beta);
}

static double cell_sample_phi(const cell *c, double u) {
  return c->two_lobe ? ss_wc2_sample(&c->wc2, u) : ss_gwc_sample(&c->gwc, u);
}

double ss_table_gwc_eval(const ss_table_gwc *t, double rho, double theta, double r, double phi) {
  ss_cr_mix m;
  if (!(r > 0.0) || !row_mix(t, rho, theta, &m)) {
    return 0.0;
  }
  cell c;
  cell_at(t, &m, r, &c);
  /* S = (E / r) g(phi) with g the normalised azimuthal density. */
  return c.e / r * cell_pdf_cos(&c, cos(phi));
}

double ss_table_gwc_albedo(const ss_table_gwc *t, double rho, double theta) {
  ss_cr_mix m;
  if (!row_mix(t, rho, theta, &m)) {
    return 0.0;
  }
  return ss_cr_mix_at(&m, t->cdf, t->n_r, 1, t->n_r - 1);
}

int ss_table_gwc_sample(const ss_table_gwc *t, double rho, double theta, double u1, double u2,
                        double *r, double *phi) {
  ss_cr_mix m;
  if (!row_mix(t, rho, theta, &m)) {
    return 0;
  }
  /* Algorithm 2: r from the cumulative radial energy, then phi from the
   * azimuthal model interpolated at r. */
  double rr = ss_cr_sample_mix(t->n_r, t->radius, &m, t->energy, 1, t->cdf, u1, NULL, NULL);
  if (!(rr > 0.0)) {
    return 0;
  }
  cell c;
  cell_at(t, &m, rr, &c);
  *r = rr;
  *phi = cell_sample_phi(&c, u2);
  return 1;
}

double ss_table_gwc_pdf(const ss_table_gwc *t, double rho, double theta, double r, double phi) {
  double total = ss_table_gwc_albedo(t, rho, theta);
  return total > 0.0 ? ss_table_gwc_eval(t, rho, theta, r, phi) / total : 0.0;
}

/* The albedo axis alone, as a mixture of [rho] rows of the theta tables. */
static int rho_mix(const ss_table_gwc *t, double rho, ss_cr_mix *m) {
  long oa;
  double wa[4];
  if (!rho_weights(t, rho, &oa, wa)) {
    return 0;
  }
  m->count = 0;
  for (int a = 0; a < 4; ++a) {
    if (wa[a] != 0.0) {
      m->row[m->count] = (size_t)(oa + a);
      m->w[m->count] = wa[a];
      m->count++;
    }
  }
  return 1;
}

double ss_table_gwc_pdf_theta(const ss_table_gwc *t, double rho, double theta) {
  ss_cr_mix m;
  if (!(theta >= 0.0 && theta <= t->theta[t->n_theta - 1]) || !rho_mix(t, rho, &m)) {
    return 0.0;
  }
  size_t nt = t->n_theta + 1;
  double total = ss_cr_mix_at(&m, t->albedo_cdf, nt, 1, t->n_theta - 1);
  double v = mix_spline(&m, t->albedo, nt, t->theta, 1, 0, theta);
  return total > 0.0 ? fmax(0.0, v) / total : 0.0;
}

int ss_table_gwc_sample_path(const ss_table_gwc *t, double rho, const double u[4], double *theta,
                             double *r, double *phi, double *phi_entry) {
  ss_cr_mix m;
  if (!rho_mix(t, rho, &m)) {
    return 0;
  }
  /* Sec. 7.1: theta_i from the effective albedo, (r, phi) by algorithm 2,
   * then the entry point's azimuth about the exit point uniformly. The
   * spline runs on to the mirror node: rescale u to stop at 90 deg. */
  size_t nt = t->n_theta + 1;
  double f90 = ss_cr_mix_at(&m, t->albedo_cdf, nt, 1, t->n_theta - 1);
  double f100 = ss_cr_mix_at(&m, t->albedo_cdf, nt, 1, t->n_theta);
  if (!(f90 > 0.0 && f100 > 0.0)) {
    return 0;
  }
  double th = ss_cr_sample_mix(nt, t->theta, &m, t->albedo, 1, t->albedo_cdf, u[0] * f90 / f100,
                               NULL, NULL);
  th = fmin(th, t->theta[t->n_theta - 1]);
  if (!isfinite(th) || !ss_table_gwc_sample(t, rho, th, u[1], u[2], r, phi)) {
    return 0;
  }
  *theta = th;
  *phi_entry = 2.0 * SS_PI * u[3];
  return 1;
}

/* The radius marginal of the path sampler: rows (rho_a, theta_j) mixed with
 * the rho spline weights times the theta basis integrals. */
static int radial_mix(const ss_table_gwc *t, double rho, ss_cr_mix *m) {
  ss_cr_mix ma;
  if (!rho_mix(t, rho, &ma)) {
    return 0;
  }
  m->count = 0;
  for (int a = 0; a < ma.count; ++a) {
    for (size_t j = 0; j < t->n_theta; ++j) {
      m->row[m->count] = ma.row[a] * t->n_theta + j;
      m->w[m->count] = ma.w[a] * t->theta_weight[j];
      m->count++;
    }
  }
  return 1;
}

double ss_table_gwc_sample_radial(const ss_table_gwc *t, double rho, double u) {
  ss_cr_mix m;
  if (!radial_mix(t, rho, &m)) {
    return -1.0;
  }
  double r = ss_cr_sample_mix(t->n_r, t->radius, &m, t->energy, 1, t->cdf, u, NULL, NULL);
  return isfinite(r) ? r : -1.0;
}

double ss_table_gwc_pdf_radial(const ss_table_gwc *t, double rho, double r) {
  ss_cr_mix m;
  if (!(r > 0.0) || !radial_mix(t, rho, &m)) {
    return 0.0;
  }
  double total = ss_cr_mix_at(&m, t->cdf, t->n_r, 1, t->n_r - 1);
  double e = mix_spline(&m, t->energy, t->n_r, t->radius, 1, 0, r);
  return total > 0.0 ? fmax(0.0, e) / (total * 2.0 * SS_PI * r) : 0.0;
}
