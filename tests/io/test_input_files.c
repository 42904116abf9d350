/* Inputs that are not regular files (a directory, a FIFO, a device) are
 * refused by every reader with one message naming the file and what it is,
 * before anything is read; sizes announced by a header or implied by the file
 * are checked before anything is allocated from them; a file read whole is
 * read to its end, whatever size it reports, and refused past its kind's
 * cap. */
#include "subsurf/albedo_table.h"
#include "subsurf/fem_cache.h"
#include "subsurf/grid_io.h"
#include "subsurf/mesh.h"
#include "subsurf/mesh_io.h"
#include "subsurf/table_file.h"
#include "subsurf/texture_io.h"

#include "io/read_scene_file.h"

#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[64];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "/tmp/subsurf-input-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void) {
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_assert_eq(system(cmd), 0);
}

TestSuite(input_files, .init = make_dir, .fini = remove_dir);

static ss_status read_tables(const char *path, ss_error *err) {
  ss_table_radial *t = NULL;
  ss_status st = ss_table_radial_load(path, &t, err);
  cr_assert_neq(st, SS_OK);
  ss_table_gwc *g = NULL;
  cr_assert_eq(ss_table_gwc_load(path, &g, err), st, "both loaders agree");
  ss_table_file_info info;
  cr_assert_eq(ss_table_file_info_read(path, &info, err), st, "and the header reader");
  return st;
}

static void expect(ss_status (*read)(const char *, ss_error *), const char *path, ss_status status,
                   const char *what) {
  ss_error err;
  ss_error_clear(&err);
  ss_status st = read(path, &err);
  cr_assert_eq(st, status, "%s: %s (%s)", path, ss_status_name(st), err.message);
  cr_assert(strstr(err.message, path) != NULL, "message lacks the path: %s", err.message);
  cr_assert(strstr(err.message, what) != NULL, "message lacks '%s': %s", what, err.message);
}

Test(input_files, scene_and_table_readers_refuse_directories_fifos_and_devices) {
  char path[128];
  snprintf(path, sizeof path, "%s/scene.json", dir);
  cr_assert_eq(mkdir(path, 0755), 0);
  expect(read_scene_file, path, SS_ERR_IO, "is a directory (expected a regular file)");
  snprintf(path, sizeof path, "%s/x.table", dir);
  cr_assert_eq(mkdir(path, 0755), 0);
  expect(read_tables, path, SS_ERR_IO, "is a directory (expected a regular file)");
  snprintf(path, sizeof path, "%s/fifo", dir);
  cr_assert_eq(mkfifo(path, 0644), 0);
  expect(read_scene_file, path, SS_ERR_IO, "is a FIFO");
  expect(read_tables, path, SS_ERR_IO, "is a FIFO");
  expect(read_scene_file, "/dev/zero", SS_ERR_IO, "is a character device");
  expect(read_tables, "/dev/null", SS_ERR_IO, "is a character device");
}

static void put_u64(unsigned char *p, uint64_t v) {
  for (int i = 0; i < 8; ++i) {
    p[i] = (unsigned char)(v >> (8 * i));
  }
}

/* A table header that announces 2^32 values (16 GiB) in a 68-byte file is
 * refused from the header, before the file is read. */
Test(input_files, table_header_counts_are_checked_against_the_file_size) {
  unsigned char head[SS_TABLE_FILE_HEADER + 4] = {'S', 'S', 'B', 'S', 'S', 'R', 'D', 'F', 1};
  const uint64_t counts[3] = {(uint64_t)1 << 32, ((uint64_t)1 << 32) + 1, UINT64_MAX};
  for (int i = 0; i < 3; ++i) {
    put_u64(head + 56, counts[i]);
    char path[128];
    snprintf(path, sizeof path, "%s/huge%d.table", dir, i);
    FILE *f = fopen(path, "wb");
    cr_assert_eq(fwrite(head, 1, sizeof head, f), sizeof head);
    fclose(f);
    expect(read_tables, path, SS_ERR_PARSE, "truncated or padded");
  }
}

Test(input_files, scene_files_larger_than_64_mib_are_refused_unread) {
  char path[128];
  snprintf(path, sizeof path, "%s/big.json", dir);
  FILE *f = fopen(path, "wb");
  cr_assert_not_null(f);
  fclose(f);
  cr_assert_eq(truncate(path, ((off_t)64 << 20) + 1), 0, "a sparse file");
  expect(read_scene_file, path, SS_ERR_PARSE, "more than 64 MiB, the limit for a scene file");
}

static ss_status read_mesh(const char *path, ss_error *err) {
  ss_mesh *m = NULL;
  ss_status st = ss_mesh_read(path, &m, NULL, err);
  ss_mesh_destroy(m);
  return st;
}

static ss_status read_texture(const char *path, ss_error *err) {
  ss_image *img = NULL;
  ss_status st = ss_texture_image_read(path, 1, &img, err);
  ss_image_destroy(img);
  return st;
}

static ss_status read_albedo(const char *path, ss_error *err) {
  ss_albedo_table *t = NULL;
  ss_status st = ss_albedo_table_load(path, &t, err);
  ss_albedo_table_destroy(t);
  return st;
}

static ss_status read_grid(const char *path, ss_error *err) {
  ss_grid *g = NULL;
  ss_status st = ss_grid_read(path, &g, err);
  ss_grid_destroy(g);
  return st;
}

static ss_status read_fem_cache(const char *path, ss_error *err) {
  ss_fem_cache *c = NULL;
  ss_status st = ss_fem_cache_read(path, &c, err);
  ss_fem_cache_destroy(c);
  return st;
}

static ss_status read_table(const char *path, ss_error *err) {
  ss_table_file_info info;
  return ss_table_file_info_read(path, &info, err);
}

/* Every reader of whole files refuses, unread, a (sparse) file one byte
 * larger than its kind's cap, naming the file and the cap. */
Test(input_files, every_whole_file_reader_refuses_a_file_past_its_cap) {
  static const struct {
    const char *name;
    ss_status (*read)(const char *, ss_error *);
    off_t cap;
    const char *what;
  } kinds[] = {
      {"m.ply", read_mesh, (off_t)1 << 30, "more than 1024 MiB, the limit for a mesh file"},
      {"m.obj", read_mesh, (off_t)1 << 30, "more than 1024 MiB, the limit for a mesh file"},
      {"t.png", read_texture, (off_t)512 << 20, "more than 512 MiB, the limit for a texture"},
      {"a.txt", read_albedo, (off_t)1 << 20, "more than 1 MiB, the limit for an albedo table"},
      {"x.table", read_table, (off_t)4 << 30, "more than 4096 MiB, the limit for a table file"},
      {"g.raw", read_grid, (off_t)8 << 30, "more than 8192 MiB, the limit for a density grid"},
      {"c.femcache", read_fem_cache, (off_t)4 << 30,
       "more than 4096 MiB, the limit for an fem cache"},
  };
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i) {
    char path[128];
    snprintf(path, sizeof path, "%s/%s", dir, kinds[i].name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    fclose(f);
    cr_assert_eq(truncate(path, kinds[i].cap + 1), 0, "a sparse file");
    expect(kinds[i].read, path, SS_ERR_PARSE, kinds[i].what);
    cr_assert_eq(unlink(path), 0);
  }
}

static ss_status read_pbrt(const char *path, ss_error *err) {
  ss_scene *s = NULL;
  ss_status st = ss_scene_read_pbrt(path, &s, NULL, NULL, err);
  ss_scene_destroy(s);
  return st;
}

/* /proc/self/pagemap reports 0 bytes and holds gigabytes: a reader that
 * trusts the reported size reads nothing, one that reads to the end without
 * a cap runs out of memory. Read whole, it is refused past the cap, as a
 * scene, through a pbrt Include, and as an albedo table. */
Test(input_files, files_holding_more_than_they_report_are_refused_at_the_cap) {
  const char *pagemap = "/proc/self/pagemap";
  expect(read_scene_file, pagemap, SS_ERR_PARSE, "more than 64 MiB, the limit for a scene file");
  expect(read_albedo, pagemap, SS_ERR_PARSE, "more than 1 MiB, the limit for an albedo table");
  char path[128];
  snprintf(path, sizeof path, "%s/include.pbrt", dir);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f);
  fprintf(f, "WorldBegin\nInclude \"%s\"\nWorldEnd\n", pagemap);
  fclose(f);
  ss_error err;
  ss_error_clear(&err);
  cr_assert_eq(read_pbrt(path, &err), SS_ERR_PARSE, "%s", err.message);
  cr_assert(strstr(err.message, pagemap) && strstr(err.message, "more than 64 MiB"), "%s",
            err.message);
}
