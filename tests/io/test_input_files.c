/* Inputs that are not regular files (a directory, a FIFO, a device) are
 * refused by every reader with one message naming the file and what it is,
 * before anything is read; sizes announced by a header or implied by the file
 * are checked before anything is allocated from them. */
#include "subsurf/mesh.h"
#include "subsurf/mesh_io.h"
#include "subsurf/table_file.h"

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
  expect(read_scene_file, path, SS_ERR_PARSE, "too large for a scene file");
}
