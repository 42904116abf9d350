/* Grid files (grid_io.h): the raw format and OpenVDB load the same grid
 * identically; damaged raw files (truncated, too long, negative density,
 * zero axis, bad magic) and an OpenVDB file without a float grid are refused
 * with one message naming the file.
 *
 * tests/io/data/vec3_only.vdb holds a single Vec3SGrid "axis" and no float
 * grid; it was written by a six-line OpenVDB program (openvdb::Vec3SGrid::
 * create, setValue at (0, 0, 0), io::File::write). */
#include <criterion/criterion.h>

#include "subsurf/grid.h"
#include "subsurf/grid_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[256];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "/tmp/subsurf-grid-io-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void) {
  char cmd[512];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_assert_eq(system(cmd), 0);
}

TestSuite(grid_io, .init = make_dir, .fini = remove_dir);

static const char *path_of(const char *name) {
  static char p[2][512];
  static int k;
  k ^= 1;
  snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
  return p[k];
}

/* A small yarn: cubic voxels (as OpenVDB needs), densities in [0, 1], axes. */
static ss_grid *yarn(void) {
  ss_yarn_params p = {10, 0.5, 3, 0.3, 0.8};
  ss_grid *g;
  ss_error err;
  cr_assert_eq(ss_grid_yarn(&p, &g, &err), SS_OK, "%s", err.message);
  cr_assert_gt(g->max_density, 0.5);
  return g;
}

static void expect_same_grid(const ss_grid *a, const ss_grid *b) {
  for (int k = 0; k < 3; ++k) {
    cr_assert_eq(a->n[k], b->n[k]);
    double la = ss_vec3_component(a->lo, k), lb = ss_vec3_component(b->lo, k);
    double ha = ss_vec3_component(a->hi, k), hb = ss_vec3_component(b->hi, k);
    cr_assert(fabs(la - lb) <= 1e-12 && fabs(ha - hb) <= 1e-12, "bounds differ along %d", k);
  }
  int64_t n = ss_grid_voxels(a);
  cr_assert_eq(memcmp(a->density, b->density, (size_t)n * sizeof *a->density), 0);
  cr_assert_eq(!a->axis, !b->axis);
  if (a->axis) {
    cr_assert_eq(memcmp(a->axis, b->axis, (size_t)n * 2 * sizeof *a->axis), 0);
  }
  cr_assert_eq(a->max_density, b->max_density);
}

Test(grid_io, raw_and_openvdb_files_of_one_grid_load_identically) {
  ss_grid *g = yarn();
  ss_error err;
  cr_assert_eq(ss_grid_write_raw(path_of("y.ssgrid"), g, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_grid_write_vdb(path_of("y.vdb"), g, &err), SS_OK, "%s", err.message);
  ss_grid *raw, *vdb;
  cr_assert_eq(ss_grid_read(path_of("y.ssgrid"), &raw, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_grid_read(path_of("y.vdb"), &vdb, &err), SS_OK, "%s", err.message);
  expect_same_grid(raw, vdb);
  /* and both are the grid written (axes to their 16-bit precision) */
  cr_assert_eq(memcmp(raw->density, g->density, (size_t)ss_grid_voxels(g) * 4), 0);
  for (int64_t v = 0; v < ss_grid_voxels(g); ++v) {
    double c = ss_vec3_dot(ss_grid_axis_of(g, v), ss_grid_axis_of(raw, v));
    cr_assert_gt(c, 1.0 - 1e-8);
  }
  ss_grid_destroy(g);
  ss_grid_destroy(raw);
  ss_grid_destroy(vdb);
}

/* Writes g as raw, then replaces the file by its first `keep` bytes plus
 * `extra` zero bytes; returns the read's status and message. */
static ss_status read_damaged(const ss_grid *g, long keep, int extra, ss_error *err) {
  const char *p = path_of("d.ssgrid");
  cr_assert_eq(ss_grid_write_raw(p, g, err), SS_OK);
  FILE *f = fopen(p, "rb");
  cr_assert_not_null(f);
  unsigned char *buf = calloc(1 << 20, 1);
  size_t n = fread(buf, 1, 1 << 20, f);
  fclose(f);
  size_t len = keep < 0 ? n : (size_t)keep;
  f = fopen(p, "wb");
  cr_assert_eq(fwrite(buf, 1, len + (size_t)extra, f), len + (size_t)extra);
  fclose(f);
  free(buf);
  ss_grid *out = NULL;
  ss_status st = ss_grid_read(p, &out, err);
  cr_assert_null(out);
  return st;
}

static ss_grid *tiny(float density) {
  const int n[3] = {2, 2, 2};
  ss_grid *g;
  ss_error err;
  cr_assert_eq(ss_grid_create(n, ss_vec3_make(0, 0, 0), ss_vec3_make(1, 1, 1), 1, &g, &err), SS_OK);
  for (int v = 0; v < 8; ++v) {
    g->density[v] = density;
  }
  return g;
}

Test(grid_io, a_truncated_or_padded_raw_file_names_the_file) {
  ss_grid *g = tiny(1.0f);
  ss_error err;
  long full = SS_GRID_RAW_HEADER + 8 * 16;
  cr_assert_eq(read_damaged(g, full - 1, 0, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "d.ssgrid") && strstr(err.message, "truncated or inconsistent"),
            "%s", err.message);
  cr_assert_eq(read_damaged(g, full, 4, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "truncated or inconsistent"), "%s", err.message);
  cr_assert_eq(read_damaged(g, 40, 0, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "not a subsurf grid file"), "%s", err.message);
  ss_grid_destroy(g);
}

Test(grid_io, negative_densities_and_zero_axes_are_refused) {
  ss_grid *g = tiny(-0.5f);
  ss_error err;
  cr_assert_eq(read_damaged(g, -1, 0, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "d.ssgrid") && strstr(err.message, "finite and >= 0"), "%s",
            err.message);
  ss_grid_destroy(g);
  /* a zero axis where the density is positive: patch voxel 0's axis */
  g = tiny(1.0f);
  const char *p = path_of("z.ssgrid");
  cr_assert_eq(ss_grid_write_raw(p, g, &err), SS_OK);
  FILE *f = fopen(p, "r+b");
  static const unsigned char zero[12] = {0};
  cr_assert_eq(fseek(f, SS_GRID_RAW_HEADER + 4, SEEK_SET), 0);
  cr_assert_eq(fwrite(zero, 1, sizeof zero, f), sizeof zero);
  fclose(f);
  ss_grid *out;
  cr_assert_eq(ss_grid_read(p, &out, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "non-zero"), "%s", err.message);
  ss_grid_destroy(g);
}

Test(grid_io, an_openvdb_file_without_a_float_grid_is_refused) {
  char p[1024];
  snprintf(p, sizeof p, "%s/tests/io/data/vec3_only.vdb", getenv("SUBSURF_SOURCE_DIR"));
  ss_grid *out;
  ss_error err;
  cr_assert_eq(ss_grid_read(p, &out, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "vec3_only.vdb") && strstr(err.message, "no float grid"), "%s",
            err.message);
  /* a file with the VDB magic and nothing after it */
  const char *q = path_of("cut.vdb");
  FILE *f = fopen(q, "wb");
  static const unsigned char magic[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
  fwrite(magic, 1, sizeof magic, f);
  fclose(f);
  cr_assert_eq(ss_grid_read(q, &out, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "cut.vdb"), "%s", err.message);
}
