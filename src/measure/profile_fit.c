/* Fitting a medium to a radial exitance profile (profile_fit.h). */
#include "subsurf/profile_fit.h"

#include "subsurf/bssrdf.h"
#include "subsurf/rng.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#define N_PARAMS 3 /* ln sigma_a, ln sigma_s', ln scale */
#define MAX_PASSES 4

static const char *const model_names[] = {"exact", "dipole", "better-dipole", "pbd"};

int ss_fit_model_from_name(const char *name) {
  for (int m = 0; m < (int)(sizeof model_names / sizeof model_names[0]); ++m) {
    if (!strcmp(name, model_names[m])) {
      return m;
    }
  }
  return -1;
}

const char *ss_fit_model_name(ss_fit_model m) { return model_names[m]; }

void ss_fit_params_default(ss_fit_params *p) {
  memset(p, 0, sizeof *p);
  p->model = SS_FIT_EXACT;
  p->eta = 1.3;
  p->rmin = -1.0;
  p->rmin_mfp = 1.0;
  p->max_iter = 200;
}

/* GSL's default handler aborts the process; the fit checks every status
 * instead. Switched off once, for the whole process. */
static pthread_once_t gsl_once = PTHREAD_ONCE_INIT;
static void gsl_handler_off(void) { gsl_set_error_handler_off(); }

/* ---- the models' profiles */

/* 4-point Gauss-Legendre nodes and weights on [-1, 1]. */
#define QUAD 4
static const double gl_x[QUAD] = {-0.86113631159405258, -0.33998104358485626, 0.33998104358485626,
                                  0.86113631159405258};
static const double gl_w[QUAD] = {0.34785484513745386, 0.65214515486254614, 0.65214515486254614,
                                  0.34785484513745386};

typedef struct {
  const ss_fit_params *p;
  const ss_profile_table *table;
  size_t np; /* parameters fitted: 3, or 2 with the scale fixed at 1 */
  size_t n;  /* points in the fit */
  /* the points (error NULL: fitted in the logarithm; r_lo NULL: point values) */
  const double *r, *r_lo, *r_hi, *value, *error;
  const double *weight;          /* bootstrap multiplicities (NULL: 1 each) */
  double *radii, *rho, *model_q; /* scratch [n * QUAD] */
  double *model;                 /* scratch [n] */
  ss_error *err;
  int failed;
} fit_ctx;

/* The model's exitance per unit incident power at n radii. */
static ss_status profile_at(const ss_fit_params *p, const ss_profile_table *table, double sigma_a,
                            double sigma_s_prime, const double *r, size_t n, double *rho,
                            double *out, ss_error *err) {
  double sigma_t_prime = sigma_a + sigma_s_prime;
  if (p->model == SS_FIT_EXACT) {
    /* M(r) = sigma_t'^2 M_table(alpha', sigma_t' r) (profile_table.h). */
    for (size_t i = 0; i < n; ++i) {
      rho[i] = sigma_t_prime * r[i];
    }
    ss_profile_table_eval(table, sigma_s_prime / sigma_t_prime, rho, n, out);
    for (size_t i = 0; i < n; ++i) {
      out[i] *= sigma_t_prime * sigma_t_prime;
    }
    return SS_OK;
  }
  static const char *const bssrdf_names[] = {NULL, "dipole", "better-dipole", "pbd"};
  ss_bssrdf_params bp;
  ss_bssrdf_params_default(&bp);
  ss_bssrdf_params_set_gray(&bp, sigma_s_prime / (1.0 - p->g), sigma_a, p->g);
  bp.eta = p->eta;
  bp.single_use = 1;
  ss_bssrdf *b;
  ss_status st = ss_bssrdf_create(bssrdf_names[p->model], &bp, &b, err);
  if (st != SS_OK) {
    return st;
  }
  for (size_t i = 0; i < n; ++i) {
    double m[SS_BSSRDF_CHANNELS];
    ss_bssrdf_exitance(b, 1.0, r[i], 0.0, m);
    out[i] = m[0];
  }
  ss_bssrdf_destroy(b);
  return SS_OK;
}

/* c->model[i]: the model at point i, or its average over the annulus
 * (Gauss-Legendre in ln r with the area element 2 pi r^2 d ln r; in r for
 * an annulus from the centre). */
static ss_status model_profile(fit_ctx *c, double sigma_a, double sigma_s_prime) {
  if (!c->r_lo) {
    return profile_at(c->p, c->table, sigma_a, sigma_s_prime, c->r, c->n, c->rho, c->model, c->err);
  }
  for (size_t i = 0; i < c->n; ++i) {
    double a = c->r_lo[i], b = c->r_hi[i];
    for (int q = 0; q < QUAD; ++q) {
      c->radii[i * QUAD + q] =
          a > 0.0 ? sqrt(a * b) * pow(b / a, 0.5 * gl_x[q]) : 0.5 * b * (1.0 + gl_x[q]);
    }
  }
  ss_status st = profile_at(c->p, c->table, sigma_a, sigma_s_prime, c->radii, c->n * QUAD, c->rho,
                            c->model_q, c->err);
  for (size_t i = 0; st == SS_OK && i < c->n; ++i) {
    double a = c->r_lo[i], b = c->r_hi[i], sum = 0.0;
    for (int q = 0; q < QUAD; ++q) {
      double rq = c->radii[i * QUAD + q];
      sum += gl_w[q] * c->model_q[i * QUAD + q] *
             (a > 0.0 ? rq * rq * 0.5 * log(b / a) : rq * 0.5 * b);
    }
    c->model[i] = 2.0 * sum / (b * b - a * a);
  }
  return st;
}

static double point_weight(const fit_ctx *c, size_t i) { return c->weight ? c->weight[i] : 1.0; }

/* Point i's residual for a scale: weighted by its standard error, or in the
 * logarithm without one. */
static double residual(const fit_ctx *c, size_t i, double scale) {
  double m = scale * c->model[i];
  double res = c->error ? (c->value[i] - m) / c->error[i] : log(c->value[i] / m);
  return sqrt(point_weight(c, i)) * res;
}

static int residuals(const gsl_vector *x, void *data, gsl_vector *f) {
  fit_ctx *c = data;
  double sigma_a = exp(gsl_vector_get(x, 0)), sigma_s_prime = exp(gsl_vector_get(x, 1));
  double scale = c->np == N_PARAMS ? exp(gsl_vector_get(x, 2)) : 1.0;
  if (!isfinite(sigma_a) || !isfinite(sigma_s_prime) || !isfinite(scale) || !(sigma_a > 0.0) ||
      !(sigma_s_prime > 0.0)) {
    return GSL_EDOM;
  }
  if (model_profile(c, sigma_a, sigma_s_prime) != SS_OK) {
    c->failed = 1;
    return GSL_EFAILED;
  }
  for (size_t i = 0; i < c->n; ++i) {
    double res = residual(c, i, scale);
    if (!isfinite(res)) {
      return GSL_EDOM;
    }
    gsl_vector_set(f, i, res);
  }
  return GSL_SUCCESS;
}

/* The sum of squared residuals with the scale at its optimum (linear least
 * squares, or the mean log ratio without standard errors), for the initial
 * search; *scale receives it. */
static double chi2_best_scale(fit_ctx *c, double sigma_a, double sigma_s_prime, double *scale) {
  if (model_profile(c, sigma_a, sigma_s_prime) != SS_OK) {
    c->failed = 1;
    return INFINITY;
  }
  double s = 1.0;
  if (!c->p->absolute) {
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < c->n; ++i) {
      double w = point_weight(c, i);
      if (c->error) {
        double e2 = c->error[i] * c->error[i];
        num += w * c->value[i] * c->model[i] / e2;
        den += w * c->model[i] * c->model[i] / e2;
      } else {
        num += w * log(c->value[i] / c->model[i]);
        den += w;
      }
    }
    s = c->error ? (den > 0.0 ? num / den : 0.0) : exp(num / den);
  }
  *scale = s;
  double chi2 = 0.0;
  for (size_t i = 0; i < c->n; ++i) {
    double res = residual(c, i, s);
    chi2 += res * res;
  }
  return s > 0.0 && isfinite(chi2) ? chi2 : INFINITY;
}

/* A grid over the reduced albedo and the transport mean free path (from
 * the radii the data span), the scale solved for at each node. */
static void initial_guess(fit_ctx *c, double x0[N_PARAMS]) {
  const ss_fit_params *p = c->p;
  if (p->sigma_a0 > 0.0 && p->sigma_s_prime0 > 0.0) {
    double s;
    double chi2 = chi2_best_scale(c, p->sigma_a0, p->sigma_s_prime0, &s);
    x0[0] = log(p->sigma_a0);
    x0[1] = log(p->sigma_s_prime0);
    x0[2] = isfinite(chi2) ? log(s) : 0.0;
    return;
  }
  double best = INFINITY;
  x0[0] = x0[1] = x0[2] = 0.0;
  double r_lo = c->r[0], r_hi = c->r[c->n - 1];
  for (int iu = 0; iu < 16; ++iu) {
    double u = 0.02 + 0.96 * iu / 15.0, ap = 1.0 - u * u;
    for (int it = 0; it < 24; ++it) {
      /* mean free paths from r_lo / 3 to 3 r_hi */
      double mfp = r_lo / 3.0 * pow(9.0 * r_hi / r_lo, it / 23.0);
      double sigma_t_prime = 1.0 / mfp, s;
      double chi2 = chi2_best_scale(c, (1.0 - ap) * sigma_t_prime, ap * sigma_t_prime, &s);
      if (chi2 < best) {
        best = chi2;
        x0[0] = log((1.0 - ap) * sigma_t_prime);
        x0[1] = log(ap * sigma_t_prime);
        x0[2] = log(s);
      }
    }
  }
}

typedef struct {
  double x[N_PARAMS], stderr_[N_PARAMS], chi2;
  int iterations, converged;
} solution;

static ss_status solve(fit_ctx *c, const double x0[N_PARAMS], solution *out, ss_error *err) {
  size_t np = c->np;
  if (c->n <= np) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "%zu points in the fitted range: fewer than the %zu parameters + 1", c->n,
                        np);
  }
  /* With the scale fixed, GSL fits the first two parameters only. */
  gsl_multifit_nlinear_fdf fdf;
  memset(&fdf, 0, sizeof fdf);
  fdf.f = residuals;
  fdf.n = c->n;
  fdf.p = np;
  fdf.params = c;
  gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
  gsl_multifit_nlinear_workspace *w =
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, c->n, np);
  gsl_matrix *covar = gsl_matrix_alloc(np, np);
  if (!w || !covar) {
    gsl_multifit_nlinear_free(w);
    gsl_matrix_free(covar);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fit: out of memory");
  }
  double xv[N_PARAMS] = {x0[0], x0[1], c->p->absolute ? 0.0 : x0[2]};
  gsl_vector_view xview = gsl_vector_view_array(xv, np);
  int info = 0, status = gsl_multifit_nlinear_init(&xview.vector, &fdf, w);
  if (status == GSL_SUCCESS) {
    status = gsl_multifit_nlinear_driver((size_t)c->p->max_iter, 1e-10, 1e-12, 1e-12, NULL, NULL,
                                         &info, w);
  }
  ss_status st = SS_OK;
  if (c->failed) {
    st = SS_ERR_NO_MEMORY;
  } else if (status != GSL_SUCCESS && status != GSL_EMAXITER) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "the fit failed: %s", gsl_strerror(status));
  } else {
    const gsl_vector *x = gsl_multifit_nlinear_position(w);
    const gsl_vector *f = gsl_multifit_nlinear_residual(w);
    double chi2;
    gsl_blas_ddot(f, f, &chi2);
    gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, covar);
    double dof = (double)(c->n - np);
    double factor = c->error ? 1.0 : chi2 / dof;
    for (size_t k = 0; k < N_PARAMS; ++k) {
      out->x[k] = k < np ? gsl_vector_get(x, k) : 0.0;
      double v = k < np ? gsl_matrix_get(covar, k, k) * factor : 0.0;
      out->stderr_[k] = v >= 0.0 ? sqrt(v) : 0.0;
    }
    out->chi2 = chi2;
    out->iterations = (int)gsl_multifit_nlinear_niter(w);
    out->converged = status == GSL_SUCCESS;
  }
  gsl_multifit_nlinear_free(w);
  gsl_matrix_free(covar);
  return st;
}

/* ---- checks and the driver */

static ss_status check(const ss_fit_params *p, const ss_fit_data *d, ss_error *err) {
  if ((int)p->model < 0 || p->model > SS_FIT_PBD) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "model: expected one of %s",
                        SS_FIT_MODEL_NAMES);
  }
  if (!(p->eta >= 1.0 && p->eta <= 10.0) || !(p->g > -1.0 && p->g < 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "eta %g, g %g: expected eta in [1, 10] and |g| < 1", p->eta, p->g);
  }
  if (p->model == SS_FIT_EXACT && p->table &&
      (fabs(ss_profile_table_eta(p->table) - p->eta) > 1e-9 ||
       fabs(ss_profile_table_g(p->table) - p->g) > 1e-9)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "the profile table is for eta %g, g %g, the sample has eta %g, g %g",
                        ss_profile_table_eta(p->table), ss_profile_table_g(p->table), p->eta, p->g);
  }
  if (!(p->max_iter >= 1) || p->bootstrap < 0 || !isfinite(p->rmin) || !isfinite(p->rmax) ||
      !(p->rmin_mfp >= 0.0 && p->rmin_mfp < 1e3)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fit options: expected max_iter >= 1, bootstrap >= 0, finite rmin and "
                        "rmax, 0 <= rmin_mfp < 1000");
  }
  if (d->n < 1) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "the profile has no points");
  }
  if (!d->r_lo != !d->r_hi) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "annuli: expected both r_lo and r_hi or neither");
  }
  for (size_t i = 0; i < d->n; ++i) {
    if (!isfinite(d->r[i]) || !(d->r[i] > 0.0) || (i && !(d->r[i] > d->r[i - 1]))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "point %zu: radius %g (expected finite, > 0 and increasing)", i + 1,
                          d->r[i]);
    }
    if (!isfinite(d->value[i]) || d->value[i] < 0.0 || (!d->error && !(d->value[i] > 0.0))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "point %zu: exitance %g (expected finite and %s)", i + 1, d->value[i],
                          d->error ? ">= 0" : "> 0 without standard errors");
    }
    if (d->r_lo && (!(d->r_lo[i] >= 0.0) || !(d->r_hi[i] < INFINITY) ||
                    !(d->r_lo[i] <= d->r[i] && d->r[i] <= d->r_hi[i] && d->r_lo[i] < d->r_hi[i]))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "point %zu: annulus [%g, %g] (expected 0 <= r_lo < r_hi, finite, "
                          "holding r = %g)",
                          i + 1, d->r_lo[i], d->r_hi[i], d->r[i]);
    }
    if (d->error && (!isfinite(d->error[i]) || !(d->error[i] > 0.0))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "point %zu: standard error %g (expected finite and > 0)", i + 1,
                          d->error[i]);
    }
  }
  return SS_OK;
}

/* The scratch arrays of a fit of up to n points. */
typedef struct {
  double *r, *r_lo, *r_hi, *value, *error;
} point_arrays;

static double *alloc_scratch(fit_ctx *c, size_t n, point_arrays *pts) {
  double *buf = malloc((6 * n + 3 * QUAD * n) * sizeof *buf);
  if (buf) {
    double *at = buf;
    pts->r = at, at += n;
    pts->r_lo = at, at += n;
    pts->r_hi = at, at += n;
    pts->value = at, at += n;
    pts->error = at, at += n;
    c->model = at, at += n;
    c->radii = at, at += QUAD * n;
    c->rho = at, at += QUAD * n;
    c->model_q = at;
  }
  return buf;
}

/* The points within [lo, hi] into the context. */
static void select_range(fit_ctx *c, const ss_fit_data *d, double lo, double hi,
                         const point_arrays *pts) {
  c->n = 0;
  for (size_t i = 0; i < d->n; ++i) {
    if (d->r[i] >= lo && d->r[i] <= hi) {
      pts->r[c->n] = d->r[i];
      pts->value[c->n] = d->value[i];
      if (d->error) {
        pts->error[c->n] = d->error[i];
      }
      if (d->r_lo) {
        pts->r_lo[c->n] = d->r_lo[i];
        pts->r_hi[c->n] = d->r_hi[i];
      }
      c->n++;
    }
  }
  c->r = pts->r;
  c->value = pts->value;
  c->error = d->error ? pts->error : NULL;
  c->r_lo = d->r_lo ? pts->r_lo : NULL;
  c->r_hi = d->r_lo ? pts->r_hi : NULL;
}

/* Resamples of the points with replacement, as multiplicities of their
 * residuals, each refitted from the best fit. */
static void bootstrap(fit_ctx *c, const solution *best, ss_fit_result *out) {
  size_t n = c->n;
  double *count = malloc(n * sizeof *count);
  double sum[2] = {0.0, 0.0}, sum2[2] = {0.0, 0.0};
  int done = 0;
  out->sigma_a_boot_stderr = out->sigma_s_prime_boot_stderr = NAN;
  if (!count) {
    return;
  }
  c->weight = count;
  for (int b = 0; b < c->p->bootstrap; ++b) {
    ss_rng rng;
    ss_rng_seed_item(&rng, c->p->seed, (uint64_t)b);
    memset(count, 0, n * sizeof *count);
    for (size_t i = 0; i < n; ++i) {
      size_t k = (size_t)(ss_rng_uniform(&rng) * (double)n);
      count[k < n ? k : n - 1] += 1.0;
    }
    solution s;
    ss_error local;
    if (solve(c, best->x, &s, &local) == SS_OK) {
      for (int k = 0; k < 2; ++k) {
        double v = exp(s.x[k]);
        sum[k] += v;
        sum2[k] += v * v;
      }
      ++done;
    }
  }
  c->weight = NULL;
  free(count);
  if (done >= 2) {
    double var[2];
    for (int k = 0; k < 2; ++k) {
      double mean = sum[k] / done;
      var[k] = fmax(sum2[k] / done - mean * mean, 0.0) * done / (done - 1.0);
    }
    out->sigma_a_boot_stderr = sqrt(var[0]);
    out->sigma_s_prime_boot_stderr = sqrt(var[1]);
  }
}

ss_status ss_fit_run(const ss_fit_params *p, const ss_fit_data *d, ss_fit_result *out,
                     ss_error *err) {
  memset(out, 0, sizeof *out);
  ss_status st = check(p, d, err);
  if (st != SS_OK) {
    return st;
  }
  pthread_once(&gsl_once, gsl_handler_off);
  fit_ctx c = {.p = p, .table = p->table, .np = p->absolute ? 2 : N_PARAMS, .err = err};
  if (p->model == SS_FIT_EXACT && !c.table) {
    if ((st = ss_profile_table_builtin(&c.table, err)) != SS_OK) {
      return st;
    }
    if (fabs(ss_profile_table_eta(c.table) - p->eta) > 1e-9 ||
        fabs(ss_profile_table_g(c.table) - p->g) > 1e-9) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "the built-in profile table is for eta %g, g %g only (the sample has "
                          "eta %g, g %g): make a table for the sample (docs/fit.md)",
                          ss_profile_table_eta(c.table), ss_profile_table_g(c.table), p->eta, p->g);
    }
  }
  point_arrays pts;
  double *scratch = alloc_scratch(&c, d->n, &pts);
  if (!scratch) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fit: out of memory for %zu points", d->n);
  }
  double hi = p->rmax > 0.0 ? p->rmax : INFINITY, lo = p->rmin >= 0.0 ? p->rmin : 0.0;
  solution s;
  double x0[N_PARAMS];
  for (int pass = 0; pass < MAX_PASSES; ++pass) {
    select_range(&c, d, lo, hi, &pts);
    if (c.n <= (p->absolute ? 2u : 3u)) {
      st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "%zu points between r = %g and %g: fewer than the %d parameters + 1", c.n,
                        lo, hi, p->absolute ? 2 : 3);
      break;
    }
    if (pass == 0) {
      initial_guess(&c, x0);
    } else {
      memcpy(x0, s.x, sizeof x0);
    }
    if (c.failed || (st = solve(&c, x0, &s, err)) != SS_OK) {
      st = c.failed ? SS_ERR_NO_MEMORY : st;
      break;
    }
    if (p->rmin >= 0.0) {
      break;
    }
    /* the automatic rmin: rmin_mfp transport mean free paths of this fit */
    double next = p->rmin_mfp / (exp(s.x[0]) + exp(s.x[1]));
    size_t before = c.n, after = 0;
    for (size_t i = 0; i < d->n; ++i) {
      after += d->r[i] >= next && d->r[i] <= hi;
    }
    if (after == before) {
      break;
    }
    lo = next;
  }
  if (st == SS_OK) {
    double sigma_a = exp(s.x[0]), sigma_s_prime = exp(s.x[1]);
    out->sigma_a = sigma_a;
    out->sigma_s_prime = sigma_s_prime;
    out->scale = exp(s.x[2]);
    out->sigma_a_stderr = sigma_a * s.stderr_[0];
    out->sigma_s_prime_stderr = sigma_s_prime * s.stderr_[1];
    out->scale_stderr = out->scale * s.stderr_[2];
    out->alpha_prime = sigma_s_prime / (sigma_a + sigma_s_prime);
    out->mfp = 1.0 / (sigma_a + sigma_s_prime);
    out->chi2 = s.chi2;
    out->used = c.n;
    out->dof = (int)c.n - (p->absolute ? 2 : 3);
    out->rmin = c.r[0];
    out->rmax = c.r[c.n - 1];
    out->iterations = s.iterations;
    out->converged = s.converged;
    if (p->model == SS_FIT_EXACT) {
      double lo_a, hi_a;
      ss_profile_table_albedo_range(c.table, &lo_a, &hi_a);
      out->at_table_edge =
          out->alpha_prime <= lo_a * (1.0 + 1e-6) || out->alpha_prime >= hi_a * (1.0 - 1e-9);
      out->converged = out->converged && !out->at_table_edge;
    }
    out->sigma_a_boot_stderr = out->sigma_s_prime_boot_stderr = NAN;
    if (p->bootstrap > 0) {
      bootstrap(&c, &s, out);
    }
  }
  free(scratch);
  return st;
}

ss_status ss_fit_eval(const ss_fit_params *p, double sigma_a, double sigma_s_prime, double scale,
                      const double *r, const double *r_lo, const double *r_hi, size_t n,
                      double *out, ss_error *err) {
  fit_ctx c = {.p = p, .table = p->table, .n = n, .r = r, .r_lo = r_lo, .r_hi = r_hi, .err = err};
  ss_status st;
  if (p->model == SS_FIT_EXACT && !c.table &&
      (st = ss_profile_table_builtin(&c.table, err)) != SS_OK) {
    return st;
  }
  point_arrays pts;
  double *scratch = alloc_scratch(&c, n ? n : 1, &pts);
  if (!scratch) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fit: out of memory");
  }
  st = model_profile(&c, sigma_a, sigma_s_prime);
  for (size_t i = 0; st == SS_OK && i < n; ++i) {
    out[i] = scale * c.model[i];
  }
  free(scratch);
  return st;
}
