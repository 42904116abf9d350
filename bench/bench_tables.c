/* Speed of photon beam diffusion and its tables: evaluation ns/call and
 * samples/s of direct PBD, the pbrt-style radial table and Ferrier's table
 * (both azimuthal fits), and the table build times.
 * Usage: bench_tables [threads for the builds, default all]. Targets:
 * table-gwc eval <= 100 ns, sample <= 300 ns, build <= 30 s. */
#include "bench_clock.h"
#include "subsurf/bssrdf.h"
#include "subsurf/pbd.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/table_gwc.h"
#include "subsurf/table_radial.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define QUERIES 4096

extern const ss_bssrdf_ops ss_bssrdf_model_pbd;

typedef struct {
  double rho, theta, r, phi, u1, u2;
} query;

static query queries[QUERIES];
static volatile double sink;

static void make_queries(void) {
  ss_rng rng;
  ss_rng_seed(&rng, 1, 0);
  for (int i = 0; i < QUERIES; ++i) {
    query *q = &queries[i];
    q->rho = 0.3 + 0.69 * ss_rng_uniform(&rng);
    q->theta = 1.55 * ss_rng_uniform(&rng);
    q->r = 0.01 * exp(7.0 * ss_rng_uniform(&rng)); /* 0.01 .. 11 mean free paths */
    q->phi = SS_PI * ss_rng_uniform(&rng);
    q->u1 = ss_rng_uniform(&rng);
    q->u2 = ss_rng_uniform(&rng);
  }
}

/* Runs `body` over the queries in CHUNKS chunks of ~0.1 s each and prints
 * the medians of the chunks' ns per call in thread CPU time (what the
 * calls cost, insensitive to other processes taking the core) and in wall
 * time. */
#define CHUNKS 5
#define TIME_LOOP(label, ...)                                                                      \
  do {                                                                                             \
    double acc = 0.0, cpu_[CHUNKS], wall_[CHUNKS];                                                 \
    for (int c_ = 0; c_ < CHUNKS; ++c_) {                                                          \
      double w0_ = omp_get_wtime(), c0_ = thread_seconds(), w1_;                                   \
      long calls = 0;                                                                              \
      do {                                                                                         \
        for (int i_ = 0; i_ < QUERIES; ++i_) {                                                     \
          const query *q = &queries[i_];                                                           \
          __VA_ARGS__;                                                                             \
        }                                                                                          \
        calls += QUERIES;                                                                          \
        w1_ = omp_get_wtime();                                                                     \
      } while (w1_ - w0_ < 0.1);                                                                   \
      cpu_[c_] = (thread_seconds() - c0_) / (double)calls * 1e9;                                   \
      wall_[c_] = (w1_ - w0_) / (double)calls * 1e9;                                               \
    }                                                                                              \
    sink = acc;                                                                                    \
    qsort(cpu_, CHUNKS, sizeof cpu_[0], compare_doubles);                                          \
    qsort(wall_, CHUNKS, sizeof wall_[0], compare_doubles);                                        \
    printf("%-34s %10.1f ns/call %10.1f ns/call wall %12.3g calls/s\n", label, cpu_[CHUNKS / 2],   \
           wall_[CHUNKS / 2], 1e9 / cpu_[CHUNKS / 2]);                                             \
  } while (0)

int main(int argc, char **argv) {
  int threads = argc > 1 ? atoi(argv[1]) : 0;
  if (threads > 0) {
    omp_set_num_threads(threads);
  }
  make_queries();
  ss_error err;
  printf("builds with %d thread(s); per-call figures: medians of %d chunks, thread CPU time "
         "then wall time\n",
         omp_get_max_threads(), CHUNKS);

  double t0 = omp_get_wtime();
  ss_table_radial *radial;
  if (ss_table_radial_build(1.33, 0.0, &radial, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  double t_radial = omp_get_wtime() - t0;
  t0 = omp_get_wtime();
  ss_table_gwc *anchors, *two;
  if (ss_table_gwc_build(1.33, 0.0, SS_TABLE_GWC_ANCHORS, &anchors, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  double t_anchors = omp_get_wtime() - t0;
  t0 = omp_get_wtime();
  if (ss_table_gwc_build(1.33, 0.0, SS_TABLE_GWC_TWO_LOBE, &two, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  double t_two = omp_get_wtime() - t0;
  printf("%-34s %10.2f s\n", "build table-radial (100 x 64)", t_radial);
  printf("%-34s %10.2f s (%zu bytes)\n", "build table-gwc anchors (100x10x64)", t_anchors,
         ss_table_gwc_bytes(anchors));
  printf("%-34s %10.2f s (%zu bytes)\n", "build table-gwc two-lobe (100x10x64)", t_two,
         ss_table_gwc_bytes(two));

  ss_pbd pbd;
  ss_pbd_init(&pbd, 0.9, 0.1, 0.0, 1.33, 32, &err);
  ss_pbd_beam beam = ss_pbd_beam_make(&pbd, 1.0);
  TIME_LOOP("pbd ms eval (32 nodes, 60 deg)", acc += ss_pbd_ms(&pbd, &beam, q->r, q->phi));
  TIME_LOOP("pbd ss eval (32 nodes)", acc += ss_pbd_ss(&pbd, q->r));
  ss_bssrdf_params params;
  ss_bssrdf_params_default(&params);
  params.eta = 1.33;
  ss_bssrdf *model;
  if (ss_bssrdf_create_ops(&ss_bssrdf_model_pbd, &params, &model, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  ss_bssrdf_sample_ctx ctx = {{0, 0, 0}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 0, 0}};
  TIME_LOOP("pbd sample_entry (+pdf)", {
    ss_bssrdf_entry e;
    ss_bssrdf_sample_entry(model, &ctx, 0, q->u1, q->u2, &e);
    acc += e.r + e.pdf;
  });
  ss_bssrdf_destroy(model);

  TIME_LOOP("table-radial eval", acc += ss_table_radial_sp(radial, q->rho, q->r));
  TIME_LOOP("table-radial sample r", acc += ss_table_radial_sample(radial, q->rho, q->u1));
  TIME_LOOP("table-radial pdf", acc += ss_table_radial_pdf_area(radial, q->rho, q->r));

  const ss_table_gwc *tabs[2] = {anchors, two};
  const char *names[2] = {"anchors", "two-lobe"};
  for (int k = 0; k < 2; ++k) {
    const ss_table_gwc *t = tabs[k];
    char label[64];
    snprintf(label, sizeof label, "table-gwc %s eval", names[k]);
    TIME_LOOP(label, acc += ss_table_gwc_eval(t, q->rho, q->theta, q->r, q->phi));
    snprintf(label, sizeof label, "table-gwc %s sample (r, phi)", names[k]);
    TIME_LOOP(label, {
      double r, phi;
      ss_table_gwc_sample(t, q->rho, q->theta, q->u1, q->u2, &r, &phi);
      acc += r + phi;
    });
    snprintf(label, sizeof label, "table-gwc %s sample path", names[k]);
    TIME_LOOP(label, {
      double u[4] = {q->u1, q->u2, q->u1 * 0.5, q->u2}, th, r, phi, phi2;
      ss_table_gwc_sample_path(t, q->rho, u, &th, &r, &phi, &phi2);
      acc += r + phi;
    });
    snprintf(label, sizeof label, "table-gwc %s sample radial", names[k]);
    TIME_LOOP(label, acc += ss_table_gwc_sample_radial(t, q->rho, q->u1));
  }
  /* What a material uses: the table at its albedo (table-gwc model). */
  ss_table_gwc *slice;
  if (ss_table_gwc_slice(two, 0.9, &slice, &err) != SS_OK) {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  TIME_LOOP("table-gwc two-lobe slice eval",
            acc += ss_table_gwc_eval(slice, 0.9, q->theta, q->r, q->phi));
  TIME_LOOP("table-gwc two-lobe slice sample", {
    double r, phi;
    ss_table_gwc_sample(slice, 0.9, q->theta, q->u1, q->u2, &r, &phi);
    acc += r + phi;
  });
  TIME_LOOP("table-gwc two-lobe slice radial",
            acc += ss_table_gwc_sample_radial(slice, 0.9, q->u1));
  ss_table_gwc_destroy(slice);
  ss_table_radial_destroy(radial);
  ss_table_gwc_destroy(anchors);
  ss_table_gwc_destroy(two);
  return 0;
}
