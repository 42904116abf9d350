/* Inputs the fuzzers (tests/fuzz) once crashed on, kept under
 * tests/fuzz/regressions/TARGET: each is now read or refused with a message
 * that names the file, and (in the sanitizer build) without a memory error or
 * a leak. */
#include "subsurf/fem_cache.h"
#include "subsurf/mesh.h"
#include "subsurf/mesh_io.h"
#include "subsurf/table_file.h"

#include "io/read_scene_file.h"

#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef ss_status (*reader)(const char *path, ss_error *err);

static ss_status read_ply(const char *path, ss_error *err) {
  ss_mesh *m = NULL;
  ss_status st = ss_mesh_read_ply(path, &m, NULL, err);
  ss_mesh_destroy(m);
  return st;
}

static ss_status read_obj(const char *path, ss_error *err) {
  ss_mesh *m = NULL;
  ss_status st = ss_mesh_read_obj(path, &m, NULL, err);
  ss_mesh_destroy(m);
  return st;
}

static ss_status read_table(const char *path, ss_error *err) {
  ss_table_radial *r = NULL;
  ss_table_gwc *g = NULL;
  ss_status st = ss_table_radial_load(path, &r, err);
  if (st == SS_OK) {
    ss_table_radial_destroy(r);
    return st;
  }
  st = ss_table_gwc_load(path, &g, err);
  if (st == SS_OK) {
    ss_table_gwc_destroy(g);
  }
  return st;
}

/* The fem cache as fuzz_fem_cache reads it: the file, then its first
 * record as a mesh. */
static ss_status read_fem_cache(const char *path, ss_error *err) {
  ss_fem_cache *c = NULL;
  ss_status st = ss_fem_cache_read(path, &c, err);
  unsigned char head[48];
  FILE *f = fopen(path, "rb");
  cr_assert(f);
  size_t n = fread(head, 1, sizeof head, f);
  fclose(f);
  uint64_t key;
  memcpy(&key, head + 40, 8);
  ss_fem_mesh *m = NULL;
  if (st == SS_OK && n == sizeof head) {
    st = ss_fem_cache_mesh(c, key, &m, err);
  }
  ss_fem_mesh_destroy(m);
  ss_fem_cache_destroy(c);
  return st;
}

/* Replays every file of the target's directory; returns how many. */
static int replay(const char *target, reader read) {
  const char *root = getenv("SUBSURF_SOURCE_DIR");
  cr_assert_not_null(root, "SUBSURF_SOURCE_DIR is not set");
  char dir[4096];
  snprintf(dir, sizeof dir, "%s/tests/fuzz/regressions/%s", root, target);
  DIR *d = opendir(dir);
  if (!d) {
    return 0;
  }
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    if (e->d_name[0] == '.') {
      continue;
    }
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    ss_error err;
    ss_error_clear(&err);
    if (read(path, &err) != SS_OK) {
      cr_expect(strstr(err.message, e->d_name) != NULL, "%s: message lacks the file: %s", e->d_name,
                err.message);
    }
    ++n;
  }
  closedir(d);
  return n;
}

Test(fuzz_regressions, ply_inputs_are_read_or_refused) {
  cr_assert_gt(replay("ply", read_ply), 0, "the PLY regressions are there");
}

Test(fuzz_regressions, obj_inputs_are_read_or_refused) { replay("obj", read_obj); }

Test(fuzz_regressions, scene_inputs_are_read_or_refused) { replay("scene", read_scene_file); }

Test(fuzz_regressions, table_inputs_are_read_or_refused) { replay("table", read_table); }

Test(fuzz_regressions, fem_cache_inputs_are_read_or_refused) {
  cr_assert_gt(replay("fem_cache", read_fem_cache), 0, "the fem cache regressions are there");
}
