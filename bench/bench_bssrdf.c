/* eval ns/call and entry samples/s of every registered BSSRDF model (helper
 * tables have their own rows in bench_tables.c). Gray medium, albedo 0.95,
 * sigma_t = 1, eta 1.33, random flat configurations within 4 mean free
 * paths. Models without pointwise values (BRDF, single scattering) are timed
 * through their brdf hook. */
#include "subsurf/bssrdf.h"
#include "subsurf/progress.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <stdio.h>
#include <string.h>

#define N_QUERIES 4096

static volatile double sink;

/* One row: create, eval and entry-sampling times of `ops` with `p`. */
static void bench_model(const ss_bssrdf_ops *ops, const ss_bssrdf_params *p, const char *label,
                        const ss_bssrdf_query *q, ss_rng *rng) {
  ss_error err;
  ss_bssrdf *b = NULL;
  double t0 = ss_seconds();
  if (ss_bssrdf_create_ops(ops, p, &b, &err) != SS_OK) {
    printf("%-16s skipped: %s\n", label, err.message);
    return;
  }
  double create_ms = 1e3 * (ss_seconds() - t0);
  int pointwise = !(ops->flags & (SS_BSSRDF_BRDF | SS_BSSRDF_SINGULAR));
  long calls = 0;
  double s[3], acc = 0.0;
  t0 = ss_seconds();
  do {
    for (int i = 0; i < N_QUERIES; ++i) {
      if (pointwise) {
        ss_bssrdf_eval(b, &q[i], s);
      } else {
        ss_bssrdf_brdf(b, q[i].w_i, q[i].w_o, s);
      }
      acc += s[0];
    }
    calls += N_QUERIES;
  } while (ss_seconds() - t0 < 0.3);
  double eval_ns = 1e9 * (ss_seconds() - t0) / (double)calls;
  double samples_per_s = 0.0;
  if (ops->sample_entry) {
    ss_bssrdf_sample_ctx ctx;
    ctx.x = ss_vec3_make(0, 0, 0);
    ctx.frame = ss_frame_from_normal(ss_vec3_make(0, 0, 1));
    ctx.w = ss_vec3_make(0, 0, 1);
    long n = 0;
    ss_bssrdf_entry e;
    t0 = ss_seconds();
    do {
      for (int i = 0; i < N_QUERIES; ++i) {
        if (ss_bssrdf_sample_entry(b, &ctx, i % 3, ss_rng_uniform(rng), ss_rng_uniform(rng), &e)) {
          acc += e.r;
        }
      }
      n += N_QUERIES;
    } while (ss_seconds() - t0 < 0.3);
    samples_per_s = (double)n / (ss_seconds() - t0);
  }
  sink = acc;
  printf("%-16s %12.2f %14.1f %12.3g%s\n", label, create_ms, eval_ns, samples_per_s,
         pointwise ? "" : "  (eval = brdf hook)");
  ss_bssrdf_destroy(b);
}

int main(void) {
  printf("%-16s %12s %14s %12s\n", "model", "create ms", "eval ns/call", "samples/s");
  ss_rng rng;
  ss_rng_seed(&rng, 1, 2);
  static ss_bssrdf_query q[N_QUERIES];
  for (int i = 0; i < N_QUERIES; ++i) {
    q[i].x_i = ss_vec3_make(0, 0, 0);
    q[i].n_i = q[i].n_o = ss_vec3_make(0, 0, 1);
    double r = 4.0 * ss_rng_uniform(&rng), phi = 2.0 * SS_PI * ss_rng_uniform(&rng);
    q[i].x_o = ss_vec3_make(r * cos(phi), r * sin(phi), 0.0);
    q[i].w_i = ss_sample_cosine_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    q[i].w_o = ss_sample_cosine_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
  }
  for (size_t m = 0; m < ss_bssrdf_model_count(); ++m) {
    const ss_bssrdf_ops *ops = ss_bssrdf_model_at(m);
    ss_bssrdf_params p;
    ss_bssrdf_params_default(&p);
    ss_bssrdf_params_set_gray(&p, 0.95, 0.05, 0.0);
    p.eta = 1.33;
    ss_error err;
    if (ss_bssrdf_option_find(ops, "thickness")) {
      ss_bssrdf_params_set_option(&p, ops, "thickness", "3", &err);
    }
    bench_model(ops, &p, ops->name, q, &rng);
  }
  /* aniso-dipole with fibre-like flakes (p = 20) along x, in the surface
   * plane, beside the uniform flakes of the loop above. */
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, 0.95, 0.05, 0.0);
  p.eta = 1.33;
  const ss_bssrdf_ops *aniso = ss_bssrdf_model_find("aniso-dipole");
  const char *keys[] = {"flake_distribution", "flake_exponent", "flake_axis"};
  const char *values[] = {"fiber", "20", "1,0,0"};
  ss_error err;
  for (int k = 0; k < 3; ++k) {
    ss_bssrdf_params_set_option(&p, aniso, keys[k], values[k], &err);
  }
  bench_model(aniso, &p, "aniso (fiber)", q, &rng);
  return 0;
}
