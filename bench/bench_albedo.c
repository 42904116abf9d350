/* The albedo + mfp conversion: the shipped table's size and parse
 * time, ns per lookup (forward albedo, exact inversion, and the conversion
 * by each method), in thread CPU time (medians of 5 chunks), and how far each
 * model's own inversion is from the exact one: the albedo that the exact
 * transport (volpath) renders for the medium each method gives, against the
 * albedo asked for (the table of docs/albedo.md).
 * Usage: bench_albedo [path of data/halfspace_albedo.txt]. */
#include "bench_clock.h"
#include "subsurf/albedo_inversion.h"
#include "subsurf/albedo_table.h"
#include "subsurf/rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define QUERIES 4096
#define CHUNKS 5

static double albedo_q[QUERIES], g_q[QUERIES], eta_q[QUERIES];
static volatile double sink;

typedef double (*lookup_fn)(const ss_albedo_table *t, int i);

static double forward(const ss_albedo_table *t, int i) {
  return ss_albedo_table_albedo(t, albedo_q[i], g_q[i], eta_q[i], NULL);
}
static double inverse(const ss_albedo_table *t, int i) {
  return ss_albedo_table_invert(t, albedo_q[i] * 0.9, g_q[i], eta_q[i]);
}
static ss_albedo_inversion method_q;
static double convert(const ss_albedo_table *t, int i) {
  double s, a;
  ss_albedo_to_coefficients(method_q, albedo_q[i] * 0.9, 1.0, g_q[i], eta_q[i], &s, &a, NULL);
  return s;
}

/* Median ns per call over CHUNKS chunks of n calls. */
static double time_ns(const ss_albedo_table *t, lookup_fn f, int n) {
  double ns[CHUNKS];
  for (int c = 0; c < CHUNKS; ++c) {
    double t0 = thread_seconds(), acc = 0.0;
    for (int k = 0; k < n; ++k) {
      acc += f(t, k % QUERIES);
    }
    sink = acc;
    ns[c] = 1e9 * (thread_seconds() - t0) / n;
  }
  qsort(ns, CHUNKS, sizeof ns[0], compare_doubles);
  return ns[CHUNKS / 2];
}

static void accuracy_table(void) {
  const double etas[] = {1.0, 1.33, 1.5}, gs[] = {0.0, 0.8};
  const double albedos[] = {0.05, 0.2, 0.4, 0.6, 0.8, 0.9, 0.95};
  printf("\n| eta | g | albedo | exact alpha' | dipole: alpha' -> renders | pbd: alpha' -> renders "
         "| burley: alpha' -> renders |\n|---|---|---|---|---|---|---|\n");
  for (int e = 0; e < 3; ++e) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 7; ++i) {
        double A = albedos[i], g = gs[j], eta = etas[e];
        if (!(A < ss_albedo_max(eta))) {
          continue;
        }
        double ar[4];
        printf("| %.2f | %.1f | %.2f |", eta, g, A);
        for (int m = 0; m < 4; ++m) {
          ss_error err;
          if (ss_albedo_invert((ss_albedo_inversion)m, A, g, eta, &ar[m], &err) != SS_OK) {
            printf(" %s |", err.message);
            continue;
          }
          if (m == 0) {
            printf(" %.5f |", ar[m]);
            continue;
          }
          double alpha = ar[m] / (1.0 - g + g * ar[m]), rendered;
          ss_albedo_exact(alpha, g, eta, &rendered, NULL);
          printf(" %.5f -> %.3f (%+.0f%%) |", ar[m], rendered, 100.0 * (rendered / A - 1.0));
        }
        printf("\n");
      }
    }
  }
}

int main(int argc, char **argv) {
  const char *path = argc > 1 ? argv[1] : "data/halfspace_albedo.txt";
  ss_albedo_table *t = NULL;
  ss_error err;
  double parse[CHUNKS];
  for (int c = 0; c < CHUNKS; ++c) {
    double t0 = thread_seconds();
    if (ss_albedo_table_load(path, &t, &err) != SS_OK) {
      fprintf(stderr, "bench_albedo: %s\n", err.message);
      return 1;
    }
    parse[c] = thread_seconds() - t0;
    if (c < CHUNKS - 1) {
      ss_albedo_table_destroy(t);
    }
  }
  qsort(parse, CHUNKS, sizeof parse[0], compare_doubles);
  FILE *f = fopen(path, "rb");
  fseek(f, 0, SEEK_END);
  long bytes = ftell(f);
  fclose(f);
  double eta_lo, eta_hi, g_lo, g_hi;
  ss_albedo_table_range(t, &eta_lo, &eta_hi, &g_lo, &g_hi);
  printf("table %s: %ld bytes, eta [%g, %g], g [%g, %g]; load + parse + checks %.1f us (median "
         "of %d, CPU)\n",
         path, bytes, eta_lo, eta_hi, g_lo, g_hi, 1e6 * parse[CHUNKS / 2], CHUNKS);
  ss_rng rng;
  ss_rng_seed(&rng, 3, 0);
  for (int i = 0; i < QUERIES; ++i) {
    albedo_q[i] = ss_rng_uniform(&rng);
    g_q[i] = g_lo + (g_hi - g_lo) * ss_rng_uniform(&rng);
    eta_q[i] = eta_lo + (eta_hi - eta_lo) * ss_rng_uniform(&rng);
  }
  printf("forward albedo(alpha', g, eta): %.0f ns/call\n", time_ns(t, forward, 200000));
  printf("exact inversion albedo -> alpha': %.0f ns/call\n", time_ns(t, inverse, 200000));
  const int calls[4] = {200000, 20000, 10, 200000};
  for (int m = 0; m < 4; ++m) {
    method_q = (ss_albedo_inversion)m;
    printf("ss_albedo_to_coefficients, %s: %.0f ns/call\n", ss_albedo_inversion_name(method_q),
           time_ns(t, convert, calls[m]));
  }
  accuracy_table();
  ss_albedo_table_destroy(t);
  return 0;
}
