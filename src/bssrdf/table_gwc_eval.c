/* Evaluating and sampling Ferrier's table (Ferrier2016 sec. 4.1-4.2 and 7.1):
 * Catmull-Rom interpolation in (rho, theta, r) on the prepared grids of
 * catmull_rom.h (spline weights as cubics per interval, interval lookup
 * without search on the theta and radius grids), the analytic azimuthal
 * models of gwc.h, and the samplers whose densities are exactly those of the
 * interpolated table. */
#include "subsurf/catmull_rom.h"
#include "subsurf/gwc.h"
#include "subsurf/sampling.h"
#include "subsurf/table_gwc.h"
#include "subsurf/table_index.h"

#include <math.h>

/* A linear mixture of table rows: up to 4 albedo x 4 incidence rows of
 * [rho][theta] tables, or 4 albedo rows of [rho] tables; the rows of one
 * table are n values long. */
typedef struct {
  int count;
  size_t row[16];
  double w[16];
} rows;

static double mix_at(const rows *m, const float *data, size_t n, size_t k) {
  double v = 0.0;
  for (int j = 0; j < m->count; ++j) {
    v += m->w[j] * data[m->row[j] * n + k];
  }
  return v;
}

/* Albedo weights; a slice (one row) has weight 1 whatever rho. */
static int rho_weights(const ss_table_gwc *t, double rho, size_t *base, double w[4], int *taps) {
  if (t->n_rho == 1) {
    *base = 0;
    w[0] = 1.0;
    *taps = 1;
    return 1;
  }
  *taps = 4;
  return ss_cr_grid_weights(&t->rho_grid, rho, base, w);
}

/* The (rho, theta) rows at a query. The theta grid folds the mirror node's
 * weight onto 80 deg (table_gwc.h). */
static int rows_at(const ss_table_gwc *t, double rho, double theta, rows *m) {
  size_t ab, tb;
  double wa[4], wt[4];
  int na;
  if (!rho_weights(t, rho, &ab, wa, &na) || !ss_cr_grid_weights(&t->theta_grid, theta, &tb, wt)) {
    return 0;
  }
  m->count = 0;
  for (int a = 0; a < na; ++a) {
    for (int b = 0; b < 4; ++b) {
      m->row[m->count] = (ab + (size_t)a) * t->n_theta + tb + (size_t)b;
      m->w[m->count] = wa[a] * wt[b];
      m->count++;
    }
  }
  return 1;
}

/* The albedo rows alone. */
static int rho_rows(const ss_table_gwc *t, double rho, rows *m) {
  size_t ab;
  double wa[4];
  if (!rho_weights(t, rho, &ab, wa, &m->count)) {
    return 0;
  }
  for (int a = 0; a < m->count; ++a) {
    m->row[a] = ab + (size_t)a;
    m->w[a] = wa[a];
  }
  return 1;
}

/* Spline value at x of the mixed rows (n values each) on grid g. */
static double mix_spline(const ss_cr_grid *g, const rows *m, const float *data, size_t n,
                         double x) {
  size_t base;
  double w[4];
  if (!ss_cr_grid_weights(g, x, &base, w)) {
    return 0.0;
  }
  double v = 0.0;
  for (int j = 0; j < m->count; ++j) {
    const float *d = data + m->row[j] * n + base;
    v += m->w[j] * (w[0] * d[0] + w[1] * d[1] + w[2] * d[2] + w[3] * d[3]);
  }
  return v;
}

/* sum_j w[j] row[j][k] over `count` rows, in two chains of additions. */
static inline double mix_rows(const double *w, const float *const *row, int count, size_t k) {
  double v0 = 0.0, v1 = 0.0;
  int j = 0;
  for (; j + 1 < count; j += 2) {
    v0 += w[j] * row[j][k];
    v1 += w[j + 1] * row[j + 1][k];
  }
  if (j < count) {
    v0 += w[j] * row[j][k];
  }
  return v0 + v1;
}

/* Samples x on grid g with density proportional to the spline of the mixed
 * rows of f, from the mixed rows of its cumulative integral F (rows of n
 * values, built by ss_cr_integrate, with guide tables or NULL): the
 * interval from F, then the root
 * of the cubic's integral by safeguarded fourth-order steps (PBR 3rd ed.,
 * sec. 8.8.2 does Newton-bisection).
 * u in [0, 1); NaN when the total is not positive. `count` = m->count, a
 * constant at each call so that the row loops unroll. */
static inline double sample_spline(const ss_cr_grid *g, size_t n, const rows *m, int count,
                                   const float *f, const float *F, const uint8_t *guides, double u,
                                   size_t *interval) {
  const float *fr[16], *Fr[16];
  for (int j = 0; j < count; ++j) {
    fr[j] = f + m->row[j] * n;
    Fr[j] = F + m->row[j] * n;
  }
  double total = mix_rows(m->w, Fr, count, n - 1);
  if (!(total > 0.0)) {
    return NAN;
  }
  /* The interval i <= n - 2 with F(i) <= target < F(i + 1). */
  double target = u * total, fi;
  size_t i = 0, last = n - 2;
  if (guides) {
    /* From the guide of the row with the largest weight (the nearest
     * node), walk to the mixture's interval: usually no step, and two
     * independent loads. */
    int best = 0;
    for (int j = 1; j < count; ++j) {
      best = m->w[j] > m->w[best] ? j : best;
    }
    i = guides[m->row[best] * SS_TABLE_GWC_GUIDE +
               ss_table_cell_clamped(u * SS_TABLE_GWC_GUIDE, SS_TABLE_GWC_GUIDE)];
    fi = mix_rows(m->w, Fr, count, i);
    double fn = mix_rows(m->w, Fr, count, i + 1);
    for (;;) {
      if (fi > target && i > 0) {
        --i;
        fn = fi;
        fi = mix_rows(m->w, Fr, count, i);
      } else if (fn <= target && i < last) {
        ++i;
        fi = fn;
        fn = mix_rows(m->w, Fr, count, i + 1);
      } else {
        break;
      }
    }
  } else {
    /* Counted in two rounds of independent probes (the starts of blocks of
     * 8 nodes, then the nodes of one block): for a monotone F bisection's
     * answer, without its chain of dependent loads. */
    for (size_t k = 8; k <= last; k += 8) {
      i += mix_rows(m->w, Fr, count, k) <= target ? 8 : 0;
    }
    size_t block = i;
    for (size_t k = block + 1; k < block + 8 && k <= last; ++k) {
      i += mix_rows(m->w, Fr, count, k) <= target;
    }
    fi = mix_rows(m->w, Fr, count, i);
  }
  const ss_cr_piece *p = g->piece + i;
  *interval = i;
  double v[4], a[4];
  for (int k = 0; k < 4; ++k) {
    v[k] = mix_rows(m->w, fr, count, p->base + (size_t)k);
  }
  double rest = (target - fi) * p->inv_width;
  for (int q = 0; q < 4; ++q) {
    a[q] = (p->m[q][0] * v[0] + p->m[q][1] * v[1]) + (p->m[q][2] * v[2] + p->m[q][3] * v[3]);
  }
  /* Start from the inverse of the linear interpolant's integral (in the
   * form without cancellation); then steps that invert the Taylor series of
   * the integral, a quartic, to fourth order (its derivatives f, f', f'',
   * f''' as h = err/f, A = f'/(2f), B = f''/(6f), C = f'''/(24f)),
   * kept inside a bisection bracket. The error left is ~ 10 K^4 h^5,
   * K = 1 + |A| + sqrt|B| + sqrt|C| (cf. gwc.c): below the tolerance the
   * iteration stops without another evaluation. */
  double f0 = a[0], f1 = a[0] + a[1] + a[2] + a[3];
  double t = 2.0 * rest / (f0 + sqrt(fmax(0.0, f0 * f0 + 2.0 * rest * (f1 - f0))));
  double b0 = a[0], b1 = 0.5 * a[1], b2 = a[2] * (1.0 / 3.0), b3 = 0.25 * a[3];
  double lo = 0.0, hi = 1.0;
  double tol = 1e-12 * fabs(b0 + b1 + b2 + b3);
  for (int iter = 0; iter < 100; ++iter) {
    if (!(t >= lo && t <= hi)) {
      t = 0.5 * (lo + hi);
    }
    double t2 = t * t;
    double err = t * ((b0 + t * b1) + t2 * (b2 + t * b3)) - rest;
    if (fabs(err) <= tol || hi - lo < 1e-13) {
      break;
    }
    if (err < 0.0) {
      lo = t;
    } else {
      hi = t;
    }
    double fv = (a[0] + t * a[1]) + t2 * (a[2] + t * a[3]);
    double inv = 1.0 / fv, h = err * inv;
    double ca = 0.5 * (a[1] + t * (2.0 * a[2] + 3.0 * t * a[3])) * inv;
    double cb = (a[2] + 3.0 * t * a[3]) * inv * (1.0 / 3.0), cc = 0.25 * a[3] * inv;
    t -= h * (1.0 + h * (ca + h * ((2.0 * ca * ca - cb) + h * (5.0 * ca * (ca * ca - cb) + cc))));
    double k = 1.0 + fabs(ca) + sqrt(fabs(cb)) + sqrt(fabs(cc)), k2 = k * k, h2 = h * h;
    if (t >= lo && t <= hi && 10.0 * k2 * k2 * h2 * h2 * fabs(h * fv) <= tol) {
      break;
    }
  }
  return g->nodes[i] + t * (g->nodes[i + 1] - g->nodes[i]);
}

static double clamp(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

/* cos x for |x| <= pi without libm's range reduction: on v = min(|x|,
 * pi - |x|) <= pi/2, cos v = 1 - 2 sin^2(v/2) with sin h = h P(h^2), terms
 * up to h^15 (next h^17/17! < 5e-17 for h <= pi/4), and cos x = -cos v past
 * pi/2; absolute error < 1e-15, branch-free, twice as fast as cos(). */
static double cos_pi(double x) {
  if (!(fabs(x) <= SS_PI)) {
    return cos(x);
  }
  const double pi_lo = 1.2246467991473532e-16; /* pi - SS_PI */
  double a = fabs(x), b = (SS_PI - a) + pi_lo;
  int flip = a > b;
  double v = flip ? b : a;
  double h = 0.5 * v, w = h * h, w2 = w * w, w4 = w2 * w2;
  double p01 = 1.0 - w * (1.0 / 6.0), p23 = 1.0 / 120.0 - w * (1.0 / 5040.0);
  double p45 = 1.0 / 362880.0 - w * (1.0 / 39916800.0);
  double p67 = 1.0 / 6227020800.0 - w * (1.0 / 1307674368000.0);
  double s = h * ((p01 + w2 * p23) + w4 * (p45 + w2 * p67));
  double c = 1.0 - 2.0 * s * s;
  return flip ? -c : c;
}

/* The shape parameters at r, in radius interval ri, of the mixed rows:
 * (H1, H2, H3) for the two-lobe fit, (beta r / E, c) for the anchors.
 * `count` is a constant at each call (4 rows for a slice, 16 for the full
 * table), so the loops unroll; rows are mixed first (their loads need only
 * the interval), then the radius taps. */
static inline void shape_at(const ss_table_gwc *t, const rows *m, int count, size_t ri, double r,
                            double p[3]) {
  const ss_cr_piece *ps = t->rs_grid.piece + t->shape_interval[ri];
  size_t sb = ps->base;
  double sw[4];
  ss_cr_piece_weights(ps, clamp(r, t->radius_shape[0], t->radius_shape[t->n_rs - 1]), sw);
  /* Two chains of additions over the rows (count is even). */
  if (t->n_shape == 3) {
    double acc[12] = {0.0}, odd[12] = {0.0};
    for (int j = 0; j < count; j += 2) {
      const float *sv = t->shape + (m->row[j] * t->n_rs + sb) * 3;
      const float *so = t->shape + (m->row[j + 1] * t->n_rs + sb) * 3;
      for (int e = 0; e < 12; ++e) {
        acc[e] += m->w[j] * sv[e];
        odd[e] += m->w[j + 1] * so[e];
      }
    }
    for (int e = 0; e < 12; ++e) {
      acc[e] += odd[e];
    }
    for (int q = 0; q < 3; ++q) {
      p[q] = (sw[0] * acc[q] + sw[1] * acc[3 + q]) + (sw[2] * acc[6 + q] + sw[3] * acc[9 + q]);
    }
  } else {
    double acc[8] = {0.0}, odd[8] = {0.0};
    for (int j = 0; j < count; j += 2) {
      const float *sv = t->shape + (m->row[j] * t->n_rs + sb) * 2;
      const float *so = t->shape + (m->row[j + 1] * t->n_rs + sb) * 2;
      for (int e = 0; e < 8; ++e) {
        acc[e] += m->w[j] * sv[e];
        odd[e] += m->w[j + 1] * so[e];
      }
    }
    for (int e = 0; e < 8; ++e) {
      acc[e] += odd[e];
    }
    for (int q = 0; q < 2; ++q) {
      p[q] = (sw[0] * acc[q] + sw[1] * acc[2 + q]) + (sw[2] * acc[4 + q] + sw[3] * acc[6 + q]);
    }
    p[2] = 0.0;
  }
}

/* Both azimuthal models as lambda pdf_WC(c1) + (1 - lambda) pdf_WC(c2). The
 * paper's GWC is lambda = beta / (2 pi alpha + beta), c2 = 0 (Ferrier2016
 * algorithm 1: alpha = (E/r - beta)/(2 pi), with beta stored as the fraction
 * beta r / E, kept in [0, 1] so that alpha >= 0). */
static void azimuth_from_shape(const ss_table_gwc *t, const double p[3], ss_wc2 *az) {
  if (t->fit == SS_TABLE_GWC_TWO_LOBE) {
    ss_wc2_from_harmonics(p, az);
    return;
  }
  az->lambda = clamp(p[0], 0.0, 1.0);
  az->c1 = clamp(p[1], 0.0, SS_GWC_C_MAX);
  az->c2 = 0.0;
}

/* S_ms = (E / r) g(phi), g the normalised azimuthal density. */
static inline double eval_rows(const ss_table_gwc *t, const rows *m, int count, double r,
                               double cos_phi) {
  /* 1/r now, off the dependency chain that ends in the density. */
  double inv_r = 1.0 / r, rw[4], acc[4] = {0.0, 0.0, 0.0, 0.0};
  if (!(r <= t->r_grid.x_max)) {
    return 0.0;
  }
  size_t ri = ss_cr_grid_find(&t->r_grid, r), rb = t->r_grid.piece[ri].base;
  ss_cr_piece_weights(t->r_grid.piece + ri, r, rw);
  double odd[4] = {0.0, 0.0, 0.0, 0.0};
  for (int j = 0; j < count; j += 2) {
    const float *ev = t->energy + m->row[j] * t->n_r + rb;
    const float *eo = t->energy + m->row[j + 1] * t->n_r + rb;
    for (int k = 0; k < 4; ++k) {
      acc[k] += m->w[j] * ev[k];
      odd[k] += m->w[j + 1] * eo[k];
    }
  }
  double e = (rw[0] * (acc[0] + odd[0]) + rw[1] * (acc[1] + odd[1])) +
             (rw[2] * (acc[2] + odd[2]) + rw[3] * (acc[3] + odd[3]));
  if (!(e > 0.0)) {
    return 0.0;
  }
  double p[3];
  shape_at(t, m, count, ri, r, p);
  if (t->fit == SS_TABLE_GWC_TWO_LOBE) {
    return e * inv_r * ss_wc2_pdf_harmonics(p, cos_phi);
  }
  ss_wc2 az;
  azimuth_from_shape(t, p, &az);
  return e * inv_r * ss_wc2_pdf_cos(&az, cos_phi);
}

double ss_table_gwc_eval(const ss_table_gwc *t, double rho, double theta, double r, double phi) {
  rows m;
  if (!(r > 0.0) || !rows_at(t, rho, theta, &m)) {
    return 0.0;
  }
  double cos_phi = cos_pi(phi);
  return t->n_rho == 1 ? eval_rows(t, &m, 4, r, cos_phi) : eval_rows(t, &m, 16, r, cos_phi);
}

double ss_table_gwc_albedo(const ss_table_gwc *t, double rho, double theta) {
  rows m;
  if (!rows_at(t, rho, theta, &m)) {
    return 0.0;
  }
  return mix_at(&m, t->cdf, t->n_r, t->n_r - 1);
}

int ss_table_gwc_sample(const ss_table_gwc *t, double rho, double theta, double u1, double u2,
                        double *r, double *phi) {
  rows m;
  if (!rows_at(t, rho, theta, &m)) {
    return 0;
  }
  /* Algorithm 2: r from the cumulative radial energy, then phi from the
   * azimuthal model interpolated at r. */
  size_t ri = 0;
  double rr =
      t->n_rho == 1
          ? sample_spline(&t->r_grid, t->n_r, &m, 4, t->energy, t->cdf, t->cdf_guide, u1, &ri)
          : sample_spline(&t->r_grid, t->n_r, &m, 16, t->energy, t->cdf, t->cdf_guide, u1, &ri);
  if (!(rr > 0.0)) {
    return 0;
  }
  double p[3];
  if (t->n_rho == 1) {
    shape_at(t, &m, 4, ri, rr, p);
  } else {
    shape_at(t, &m, 16, ri, rr, p);
  }
  ss_wc2 az;
  azimuth_from_shape(t, p, &az);
  *r = rr;
  *phi = ss_wc2_sample(&az, u2);
  return 1;
}

double ss_table_gwc_pdf(const ss_table_gwc *t, double rho, double theta, double r, double phi) {
  double total = ss_table_gwc_albedo(t, rho, theta);
  return total > 0.0 ? ss_table_gwc_eval(t, rho, theta, r, phi) / total : 0.0;
}

double ss_table_gwc_pdf_theta(const ss_table_gwc *t, double rho, double theta) {
  rows m;
  size_t nt = t->n_theta + 1;
  if (!(theta >= 0.0 && theta <= t->theta[t->n_theta - 1]) || !rho_rows(t, rho, &m)) {
    return 0.0;
  }
  double total = mix_at(&m, t->albedo_cdf, nt, t->n_theta - 1);
  double v = mix_spline(&t->theta_grid, &m, t->albedo, nt, theta);
  return total > 0.0 ? fmax(0.0, v) / total : 0.0;
}

int ss_table_gwc_sample_path(const ss_table_gwc *t, double rho, const double u[4], double *theta,
                             double *r, double *phi, double *phi_entry) {
  rows m;
  size_t nt = t->n_theta + 1;
  if (!rho_rows(t, rho, &m)) {
    return 0;
  }
  /* Sec. 7.1: theta_i from the effective albedo, (r, phi) by algorithm 2,
   * then the entry point's azimuth about the exit point uniformly. The
   * spline runs on to the mirror node: rescale u to stop at 90 deg. */
  double f90 = mix_at(&m, t->albedo_cdf, nt, t->n_theta - 1);
  double f100 = mix_at(&m, t->albedo_cdf, nt, t->n_theta);
  if (!(f90 > 0.0 && f100 > 0.0)) {
    return 0;
  }
  size_t interval;
  double th = sample_spline(&t->theta_grid, nt, &m, m.count, t->albedo, t->albedo_cdf, NULL,
                            u[0] * f90 / f100, &interval);
  th = fmin(th, t->theta[t->n_theta - 1]);
  if (!isfinite(th) || !ss_table_gwc_sample(t, rho, th, u[1], u[2], r, phi)) {
    return 0;
  }
  *theta = th;
  *phi_entry = 2.0 * SS_PI * u[3];
  return 1;
}

/* The radius marginal of the path sampler: the albedo rows of the
 * precomputed theta integral (table_gwc.h). */
double ss_table_gwc_sample_radial(const ss_table_gwc *t, double rho, double u) {
  rows m;
  size_t interval;
  if (!rho_rows(t, rho, &m)) {
    return -1.0;
  }
  double r = t->n_rho == 1 ? sample_spline(&t->r_grid, t->n_r, &m, 1, t->radial_energy,
                                           t->radial_cdf, t->radial_guide, u, &interval)
                           : sample_spline(&t->r_grid, t->n_r, &m, 4, t->radial_energy,
                                           t->radial_cdf, t->radial_guide, u, &interval);
  return isfinite(r) ? r : -1.0;
}

double ss_table_gwc_pdf_radial(const ss_table_gwc *t, double rho, double r) {
  rows m;
  if (!(r > 0.0) || !rho_rows(t, rho, &m)) {
    return 0.0;
  }
  double total = mix_at(&m, t->radial_cdf, t->n_r, t->n_r - 1);
  double e = mix_spline(&t->r_grid, &m, t->radial_energy, t->n_r, r);
  return total > 0.0 ? fmax(0.0, e) / (total * 2.0 * SS_PI * r) : 0.0;
}
