/* The shipped half-space albedo table (albedo_table.h): it loads with every
 * check, its interpolant is strictly monotone in the reduced albedo at any
 * (eta, g) of its range, the inversion is its exact inverse, its ends are
 * exact, and damaged files are refused with a message naming the file (and
 * line) and the problem. */
#include <criterion/criterion.h>

#include "subsurf/albedo_table.h"
#include "subsurf/rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

static const ss_albedo_table *builtin(void) {
  const ss_albedo_table *t;
  ss_error err;
  cr_assert_eq(ss_albedo_table_builtin(&t, &err), SS_OK, "%s", err.message);
  return t;
}

static char *read_text(const char *path, size_t *size) {
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f, "%s", path);
  fseek(f, 0, SEEK_END);
  *size = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  char *t = malloc(*size + 64);
  cr_assert_eq(fread(t, 1, *size, f), *size);
  fclose(f);
  t[*size] = '\0';
  return t;
}

static const char *data_path(void) {
  static char path[4096];
  const char *src = getenv("SUBSURF_SOURCE_DIR");
  cr_assert_not_null(src);
  snprintf(path, sizeof path, "%s/data/halfspace_albedo.txt", src);
  return path;
}

Test(albedo_table, shipped_file_loads_and_equals_the_built_in_table) {
  ss_albedo_table *t = NULL;
  ss_error err;
  cr_assert_eq(ss_albedo_table_load(data_path(), &t, &err), SS_OK, "%s", err.message);
  const ss_albedo_table *b = builtin();
  for (double a = 0.0; a <= 1.0; a += 0.01) {
    cr_expect_eq(ss_albedo_table_albedo(t, a, 0.5, 1.25, NULL),
                 ss_albedo_table_albedo(b, a, 0.5, 1.25, NULL));
  }
  ss_albedo_table_destroy(t);
}

Test(albedo_table, albedo_increases_strictly_with_the_reduced_albedo) {
  const ss_albedo_table *t = builtin();
  double eta_lo, eta_hi, g_lo, g_hi;
  ss_albedo_table_range(t, &eta_lo, &eta_hi, &g_lo, &g_hi);
  ss_rng rng;
  ss_rng_seed(&rng, 17, 1);
  for (int k = 0; k < 40; ++k) {
    double eta = eta_lo + (eta_hi - eta_lo) * ss_rng_uniform(&rng);
    double g = g_lo + (g_hi - g_lo) * ss_rng_uniform(&rng);
    double prev = -1.0;
    for (int i = 0; i <= 4000; ++i) {
      double u = 1.0 - i / 4000.0; /* u = sqrt(1 - alpha') from 1 to 0 */
      double a = ss_albedo_table_albedo(t, 1.0 - u * u, g, eta, NULL);
      cr_assert(a > prev || (i == 0 && a == 0.0), "eta %g g %g u %g: %.9f after %.9f", eta, g, u, a,
                prev);
      prev = a;
    }
    cr_expect(fabs(prev - ss_albedo_max(eta)) < 1e-12, "no absorption: %.12f", prev);
  }
}

Test(albedo_table, inversion_round_trips) {
  const ss_albedo_table *t = builtin();
  const double etas[] = {1.0, 1.05, 1.33, 1.6};
  const double gs[] = {0.0, 0.45, 0.85, 0.9};
  for (int e = 0; e < 4; ++e) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 1; i < 200; ++i) {
        double A = ss_albedo_max(etas[e]) * i / 200.0;
        double ar = ss_albedo_table_invert(t, A, gs[j], etas[e]);
        double back = ss_albedo_table_albedo(t, ar, gs[j], etas[e], NULL);
        cr_expect(fabs(back - A) < 1e-12, "eta %g g %g: %.15f -> alpha' %.15f -> %.15f", etas[e],
                  gs[j], A, ar, back);
      }
      cr_expect_eq(ss_albedo_table_invert(t, ss_albedo_max(etas[e]), gs[j], etas[e]), 1.0);
      cr_expect_eq(ss_albedo_table_invert(t, 0.0, gs[j], etas[e]), 0.0);
    }
  }
}

Test(albedo_table, range_check_names_the_value) {
  const ss_albedo_table *t = builtin();
  ss_error err;
  cr_expect_eq(ss_albedo_table_check(t, 0.3, 2.0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "eta 2 is outside"), "%s", err.message);
  cr_expect_eq(ss_albedo_table_check(t, -0.2, 1.3, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "g -0.2 is outside"), "%s", err.message);
  cr_expect_eq(ss_albedo_table_check(t, 0.3, 1.3, &err), SS_OK);
}

/* Rewrites the CRC line of a modified text so that the body checks run. */
static size_t with_crc(char *text) {
  char *crc = strstr(text, "crc32 ");
  size_t body = (size_t)(crc - text);
  uint32_t c = (uint32_t)crc32(crc32(0L, Z_NULL, 0), (const Bytef *)text, (uInt)body);
  return body + (size_t)sprintf(crc, "crc32 %08x\n", (unsigned)c);
}

static void expect_refused(const char *text, size_t size, const char *what) {
  ss_albedo_table *t = NULL;
  ss_error err;
  cr_expect_eq(ss_albedo_table_parse(text, size, "x.txt", &t, &err), SS_ERR_PARSE, "%s", what);
  cr_expect_null(t);
  cr_expect(strstr(err.message, "x.txt") && strstr(err.message, what), "%s: got '%s'", what,
            err.message);
}

Test(albedo_table, damaged_files_are_refused) {
  size_t size;
  char *orig = read_text(data_path(), &size);
  char *t = malloc(size + 64);
  /* truncated */
  expect_refused(orig, size / 2, "truncated");
  /* one digit changed: checksum */
  memcpy(t, orig, size + 1);
  char *v = strstr(t, "curve ") + 20;
  *v = *v == '5' ? '6' : '5';
  expect_refused(t, size, "checksum mismatch");
  /* wrong version, with a valid checksum */
  memcpy(t, orig, size + 1);
  memcpy(strstr(t, "subsurf-albedo-table 1"), "subsurf-albedo-table 7", 22);
  expect_refused(t, with_crc(t), "version 7 is not supported");
  /* a curve that rises (first value after the exact end set to 1) */
  memcpy(t, orig, size + 1);
  char *curve = strstr(t, "\ncurve 1.0 0.0 ");
  cr_assert_not_null(curve);
  char *second = strchr(strchr(curve + 15, ' ') + 1, ' ');
  memcpy(second - 8, "1.000000", 8);
  expect_refused(t, with_crc(t), "decrease strictly");
  /* a NUL byte */
  memcpy(t, orig, size + 1);
  t[10] = '\0';
  expect_refused(t, size, "NUL");
  free(t);
  free(orig);
}
