/* Table files: round trips, and foreign, truncated, corrupt, wrong-kind,
 * newer-version and mismatched-material files refused with clear errors. */
#include "subsurf/table_file.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char path[128];

static void make_path(const char *tag) {
  snprintf(path, sizeof path, "/tmp/subsurf_test_%s_%ld.tbl", tag, (long)getpid());
}

static ss_table_radial *radial_table(void) {
  ss_table_radial *t;
  ss_error err;
  cr_assert_eq(ss_table_radial_build(1.33, 0.25, &t, &err), SS_OK, "%s", err.message);
  return t;
}

/* A gwc table with arbitrary finite data: files do not care about physics. */
static ss_table_gwc *gwc_table(int fit) {
  ss_table_gwc *t;
  ss_error err;
  cr_assert_eq(ss_table_gwc_alloc(1.4, -0.3, fit, &t, &err), SS_OK);
  size_t ne = t->n_rho * t->n_theta * t->n_r, ns = t->n_rho * t->n_theta * t->n_rs * t->n_shape;
  for (size_t i = 0; i < ne; ++i) {
    t->energy[i] = (float)((i % 97) * 0.01);
  }
  for (size_t i = 0; i < ns; ++i) {
    t->shape[i] = (float)((i % 13) * 0.03);
  }
  ss_table_gwc_finish(t);
  return t;
}

static long file_size(void) {
  FILE *f = fopen(path, "rb");
  cr_assert(f);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fclose(f);
  return n;
}

static void poke(long offset, unsigned char xor_mask) {
  FILE *f = fopen(path, "r+b");
  cr_assert(f);
  fseek(f, offset, SEEK_SET);
  int c = fgetc(f);
  fseek(f, offset, SEEK_SET);
  fputc((unsigned char)c ^ xor_mask, f);
  fclose(f);
}

Test(table_file, radial_round_trip_is_exact) {
  make_path("radial");
  ss_table_radial *t = radial_table(), *u;
  ss_error err;
  cr_assert_eq(ss_table_radial_save(t, path, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_table_radial_load(path, &u, &err), SS_OK, "%s", err.message);
  cr_assert_eq(u->eta, 1.33);
  cr_assert_eq(u->g, 0.25);
  cr_assert_eq(memcmp(t->profile, u->profile, t->n_rho * t->n_r * sizeof(float)), 0);
  cr_assert_eq(memcmp(t->cdf, u->cdf, t->n_rho * t->n_r * sizeof(float)), 0);
  ss_table_radial_destroy(t);
  ss_table_radial_destroy(u);
  remove(path);
}

Test(table_file, gwc_round_trip_is_exact_for_both_fits) {
  make_path("gwc");
  for (int fit = 0; fit < 2; ++fit) {
    ss_table_gwc *t = gwc_table(fit), *u;
    ss_error err;
    cr_assert_eq(ss_table_gwc_save(t, path, &err), SS_OK, "%s", err.message);
    cr_assert_eq(ss_table_gwc_load(path, &u, &err), SS_OK, "%s", err.message);
    cr_assert_eq(u->fit, fit);
    cr_assert_eq(u->eta, 1.4);
    cr_assert_eq(u->g, -0.3);
    size_t ns = t->n_rho * t->n_theta * t->n_rs * t->n_shape;
    cr_assert_eq(memcmp(t->shape, u->shape, ns * sizeof(float)), 0);
    cr_assert_eq(memcmp(t->cdf, u->cdf, t->n_rho * t->n_theta * t->n_r * sizeof(float)), 0);
    ss_table_file_info info;
    cr_assert_eq(ss_table_file_info_read(path, &info, &err), SS_OK);
    cr_assert_eq(info.kind, SS_TABLE_KIND_GWC);
    cr_assert_eq(info.n_theta, 10);
    ss_table_gwc_destroy(t);
    ss_table_gwc_destroy(u);
  }
  remove(path);
}

static void expect_refusal(const char *needle) {
  ss_table_radial *u = NULL;
  ss_error err;
  ss_status st = ss_table_radial_load(path, &u, &err);
  cr_assert_neq(st, SS_OK, "expected '%s'", needle);
  cr_assert_null(u);
  cr_assert(strstr(err.message, needle) != NULL, "'%s' lacks '%s'", err.message, needle);
  cr_assert(strstr(err.message, path) != NULL, "'%s' does not name the file", err.message);
}

Test(table_file, corrupt_truncated_and_foreign_files_are_refused) {
  make_path("bad");
  ss_table_radial *t = radial_table();
  ss_error err;
  cr_assert_eq(ss_table_radial_save(t, path, &err), SS_OK);
  long size = file_size();
  /* One flipped bit in the data. */
  poke(SS_TABLE_FILE_HEADER + 4000, 0x10);
  expect_refusal("CRC-32 mismatch");
  /* Truncated. */
  cr_assert_eq(ss_table_radial_save(t, path, &err), SS_OK);
  cr_assert_eq(truncate(path, size - 100), 0);
  expect_refusal("truncated");
  cr_assert_eq(truncate(path, 20), 0);
  expect_refusal("truncated header");
  /* Padded. */
  cr_assert_eq(ss_table_radial_save(t, path, &err), SS_OK);
  cr_assert_eq(truncate(path, size + 4), 0);
  expect_refusal("truncated or padded");
  /* Foreign. */
  FILE *f = fopen(path, "wb");
  fputs("P6\n640 480\n255\n", f);
  fclose(f);
  expect_refusal("not a subsurf BSSRDF table");
  /* Empty. */
  f = fopen(path, "wb");
  fclose(f);
  expect_refusal("not a subsurf BSSRDF table");
  /* A newer format version. */
  cr_assert_eq(ss_table_radial_save(t, path, &err), SS_OK);
  poke(8, 0x02);
  expect_refusal("format version 3");
  /* Missing. */
  remove(path);
  expect_refusal("cannot open");
  ss_table_radial_destroy(t);
}

Test(table_file, wrong_kind_and_mismatched_material_are_refused) {
  make_path("kind");
  ss_table_gwc *t = gwc_table(SS_TABLE_GWC_TWO_LOBE);
  ss_error err;
  cr_assert_eq(ss_table_gwc_save(t, path, &err), SS_OK);
  expect_refusal("holds a gwc table");
  ss_table_gwc_destroy(t);
  cr_assert_eq(ss_table_file_check_material(path, 1.4, -0.3, 1.4, -0.3, &err), SS_OK);
  cr_assert_neq(ss_table_file_check_material(path, 1.4, -0.3, 1.33, -0.3, &err), SS_OK);
  cr_assert(strstr(err.message, "built for eta 1.4, g -0.3") != NULL, "%s", err.message);
  cr_assert_neq(ss_table_file_check_material(path, 1.4, -0.3, 1.4, 0.0, &err), SS_OK);
  remove(path);
}

Test(table_file, failed_write_leaves_no_file) {
  ss_table_radial *t = radial_table();
  ss_error err;
  cr_assert_neq(ss_table_radial_save(t, "/nonexistent-dir/x.tbl", &err), SS_OK);
  cr_assert(strstr(err.message, "/nonexistent-dir/x.tbl") != NULL, "%s", err.message);
  cr_assert_neq(access("/nonexistent-dir/x.tbl", F_OK), 0);
  ss_table_radial_destroy(t);
}
