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
  ss_bssrdf_destroy(model);
  ss_bssrdf_destroy(brdf);
  return 0;
}
