/* The forward scattering dipole: G_f (eq. 9) ns/call with and without the
 * coefficients, G^b_f (eq. 14), G^pb_f (eq. 17-18), the model's S (the
 * adaptive integral over s) and the effective BRDF's samples/s. One channel
 * per call; ps log-uniform over [1e-3, 1e3], points within a few reduced
 * mean free paths. Thread CPU time, median of 5 chunks. */
#include "bssrdf/fwddip_propagator.h"
#include "subsurf/bssrdf.h"
#include "subsurf/fwddip.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define N 8192
#define CHUNKS 5

static volatile double sink;

static double cpu_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
}

static int compare(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

typedef struct {
  ss_fwddip_medium m;
  double s[N];
  ss_vec3 x[N], w[N], wp[N];
  ss_fwddip_coeffs k[N];
  const ss_bssrdf *model, *brdf;
  ss_bssrdf_query q[N];
} bench;

typedef double (*kernel)(bench *b, int i);

static double k_gf(bench *b, int i) {
  return ss_fwddip_gf(&b->m, b->s[i], b->x[i], b->w[i], ss_vec3_make(0, 0, 0), b->wp[i]);
}
static double k_coeffs(bench *b, int i) {
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(b->m.p * b->s[i], &k);
  return k.log_norm;
}
static double k_log_gf(bench *b, int i) {
  return ss_fwddip_log_gf(&b->m, &b->k[i], b->s[i], b->x[i], b->w[i], ss_vec3_make(0, 0, 0),
                          b->wp[i]);
}
static double k_gbf(bench *b, int i) {
  ss_vec3 n = ss_vec3_make(0, 0, 1), w_i = b->wp[i];
  w_i.z = -fabs(w_i.z);
  ss_vec3 x = b->x[i];
  x.z = 0.0;
  return ss_fwddip_gbf(&b->m, &b->k[i], b->s[i], x, b->w[i], ss_vec3_make(0, 0, 0), n, w_i, 0.3);
}
static double k_gpbf(bench *b, int i) {
  ss_vec3 w_i = b->wp[i];
  w_i.z = -fabs(w_i.z);
  return ss_fwddip_gpbf(&b->m, &b->k[i], b->s[i], b->w[i], w_i, ss_vec3_make(0, 0, 1), 0.3);
}
static double k_eval(bench *b, int i) {
  double s[3];
  ss_bssrdf_eval(b->model, &b->q[i % 256], s);
  return s[0];
}
static double k_brdf_sample(bench *b, int i) {
  ss_vec3 w_o;
  double pdf;
  ss_fwddip_brdf_sample(b->brdf, b->q[i].w_i, b->s[i] - (int)b->s[i], b->x[i].x - (int)b->x[i].x,
                        &w_o, &pdf);
  return pdf;
}

/* One sample of E = int dA(x_i) int ds int dw' G^b_f(s, x_o, w_o, x_i, w') |w'.n|
 * over downward w' (eq. 16 with L_e = 1 on the plane z = 0), x_o = 0:
 * either with the model's samplers (entry point, then s, then w') or
 * brute force (x_i uniform in a disk of radius R, s uniform on [0, S], w'
 * uniform over the lower hemisphere). */
typedef struct {
  const ss_bssrdf *model;
  ss_fwddip_medium m;
  ss_vec3 w_o;
  double z_v, R, S;
} estimator;

static double sample_ours(const estimator *e, ss_rng *rng) {
  ss_bssrdf_sample_ctx ctx;
  ctx.x = ss_vec3_make(0, 0, 0);
  ctx.frame = ss_frame_from_normal(ss_vec3_make(0, 0, 1));
  ctx.w = e->w_o;
  ss_bssrdf_entry en;
  if (!ss_bssrdf_sample_entry(e->model, &ctx, 0, ss_rng_uniform(rng), ss_rng_uniform(rng), &en)) {
    return 0.0;
  }
  ss_vec3 x_i = ss_vec3_make(en.r * cos(en.phi), en.r * sin(en.phi), 0.0), w;
  double s, ps, pw;
  if (!ss_fwddip_sample_length(e->model, 0, en.r, ss_rng_uniform(rng), ss_rng_uniform(rng), &s,
                               &ps) ||
      !ss_fwddip_sample_direction(e->model, 0, s, ss_vec3_make(0, 0, 0), e->w_o, x_i,
                                  ss_rng_uniform(rng), ss_rng_uniform(rng), &w, &pw) ||
      w.z >= 0.0) {
    return 0.0;
  }
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(e->m.p * s, &k);
  double g = ss_fwddip_gbf(&e->m, &k, s, ss_vec3_make(0, 0, 0), e->w_o, x_i, ss_vec3_make(0, 0, 1),
                           w, e->z_v);
  return g * -w.z / (en.pdf * ps * pw);
}

static double sample_uniform(const estimator *e, ss_rng *rng) {
  double r = e->R * sqrt(ss_rng_uniform(rng)), phi = 2.0 * SS_PI * ss_rng_uniform(rng);
  double s = e->S * ss_rng_uniform(rng);
  ss_vec3 w = ss_sample_uniform_hemisphere(ss_rng_uniform(rng), ss_rng_uniform(rng));
  w.z = -w.z;
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(e->m.p * s, &k);
  double g = ss_fwddip_gbf(&e->m, &k, s, ss_vec3_make(0, 0, 0), e->w_o,
                           ss_vec3_make(r * cos(phi), r * sin(phi), 0.0), ss_vec3_make(0, 0, 1), w,
                           e->z_v);
  return g * -w.z * (SS_PI * e->R * e->R) * e->S * (2.0 * SS_PI);
}

static void efficiency(const ss_bssrdf *model, double theta_o) {
  estimator e = {model,
                 ss_fwddip_medium_make(0.1, 0.01),
                 ss_vec3_make(sin(theta_o), 0.0, cos(theta_o)),
                 0.0,
                 200.0,
                 2e4};
  /* z_v = 2 d_e of eq. 13 for sigma_s' = 0.1, sigma_a = 0.01 (A = 1). */
  double D = 1.0 / (3.0 * 0.11);
  e.z_v = 2.0 * 2.131 * D / sqrt(0.1 / 0.11);
  double (*f[2])(const estimator *, ss_rng *) = {sample_ours, sample_uniform};
  double mean[2], var[2], ns[2];
  const int n[2] = {200000, 2000000};
  for (int j = 0; j < 2; ++j) {
    ss_rng rng;
    ss_rng_seed(&rng, 3, (uint64_t)j);
    double sum = 0.0, sum2 = 0.0, t0 = cpu_ns();
    for (int i = 0; i < n[j]; ++i) {
      double v = f[j](&e, &rng);
      sum += v;
      sum2 += v * v;
    }
    ns[j] = (cpu_ns() - t0) / n[j];
    mean[j] = sum / n[j];
    var[j] = sum2 / n[j] - mean[j] * mean[j];
  }
  printf("eq. 16 estimator, exit toward %2.0f deg: ours %.5g +- %.2g (%.0f ns, %.3g samples/s, "
         "variance/sample %.3g); uniform %.5g +- %.2g (%.0f ns, variance/sample %.3g); "
         "efficiency gain %.3g\n",
         theta_o * 180.0 / SS_PI, mean[0], sqrt(var[0] / n[0]), ns[0], 1e9 / ns[0], var[0], mean[1],
         sqrt(var[1] / n[1]), ns[1], var[1], var[1] * ns[1] / (var[0] * ns[0]));
}

/* Median over chunks of ns per call for calls 0..n-1. */
static double time_kernel(bench *b, kernel f, int n) {
  double t[CHUNKS];
  for (int c = 0; c < CHUNKS; ++c) {
    double acc = 0.0, t0 = cpu_ns();
    for (int i = 0; i < n; ++i) {
      acc += f(b, i);
    }
    t[c] = (cpu_ns() - t0) / n;
    sink = acc;
  }
  qsort(t, CHUNKS, sizeof t[0], compare);
  return t[CHUNKS / 2];
}

static ss_bssrdf *make(const char *name) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, 1.0, 0.01, 0.9);
  p.eta = 1.0;
  ss_bssrdf *m = NULL;
  ss_error err;
  if (ss_bssrdf_create(name, &p, &m, &err) != SS_OK) {
    fprintf(stderr, "bench_fwddip: %s\n", err.message);
    exit(1);
  }
  return m;
}

int main(void) {
  static bench b;
  b.m = ss_fwddip_medium_make(0.1, 0.01); /* sigma_s = 1, g = 0.9 */
  ss_rng rng;
  ss_rng_seed(&rng, 1, 8);
  for (int i = 0; i < N; ++i) {
    double ps = 1e-3 * pow(1e6, ss_rng_uniform(&rng));
    b.s[i] = ps / b.m.p;
    ss_fwddip_coeffs_make(ps, &b.k[i]);
    b.w[i] = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    b.wp[i] = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    double r = fmin(b.s[i], 30.0) * ss_rng_uniform(&rng);
    b.x[i] = ss_vec3_scale(ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng)), r);
    double rr = 20.0 * ss_rng_uniform(&rng), phi = 2.0 * SS_PI * ss_rng_uniform(&rng);
    b.q[i] = ss_bssrdf_halfspace_query(
        cos(1.4 * ss_rng_uniform(&rng)), rr * cos(phi), rr * sin(phi),
        ss_sample_cosine_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng)));
  }
  ss_bssrdf *model = make("fwddip"), *brdf = make("fwddip-brdf");
  b.model = model;
  b.brdf = brdf;
  printf("sigma_s 1, sigma_a 0.01, g 0.9, eta 1; ps log-uniform in [1e-3, 1e3]; one channel\n");
  printf("%-44s %12s\n", "kernel", "ns/call");
  printf("%-44s %12.1f\n", "G_f (eq. 9) with its coefficients", time_kernel(&b, k_gf, N));
  printf("%-44s %12.1f\n", "  coefficients A..F, Z, log N e^{-C} only",
         time_kernel(&b, k_coeffs, N));
  printf("%-44s %12.1f\n", "  log G_f, coefficients given", time_kernel(&b, k_log_gf, N));
  printf("%-44s %12.1f\n", "G^b_f (eq. 14), coefficients given", time_kernel(&b, k_gbf, N));
  printf("%-44s %12.1f\n", "G^pb_f (eq. 18), coefficients given", time_kernel(&b, k_gpbf, N));
  printf("%-44s %12.1f\n", "fwddip eval (int G^b_f ds, 3 equal channels)",
         time_kernel(&b, k_eval, 256));
  printf("%-44s %12.1f\n", "fwddip-brdf sample_brdf", time_kernel(&b, k_brdf_sample, N));
  efficiency(model, 0.0);
  efficiency(model, 80.0 * SS_PI / 180.0);
  ss_bssrdf_destroy(model);
  ss_bssrdf_destroy(brdf);
  return 0;
}
