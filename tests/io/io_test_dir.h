/* Directory helpers of the I/O tests. */
#ifndef SUBSURF_TESTS_IO_TEST_DIR_H
#define SUBSURF_TESTS_IO_TEST_DIR_H

#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A fresh directory /tmp/<prefix>-XXXXXX, its name in dir[size]. */
static inline void io_test_make_dir(char *dir, size_t size, const char *prefix) {
  snprintf(dir, size, "/tmp/%s-XXXXXX", prefix);
  cr_assert_not_null(mkdtemp(dir));
}

/* Removes the directory and everything in it. */
static inline void io_test_remove_dir(const char *dir) {
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_assert_eq(system(cmd), 0);
}

/* Copies the file `from` to `to` (replacing it). */
static inline void io_test_copy_file(const char *from, const char *to) {
  FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
  cr_assert(a && b, "cannot copy %s to %s", from, to);
  int c;
  while ((c = fgetc(a)) != EOF) {
    fputc(c, b);
  }
  fclose(a);
  fclose(b);
}

/* The bytes of the file `path` (malloc'd, *size of them), or NULL when it
 * cannot be opened. */
static inline unsigned char *io_test_read_file(const char *path, size_t *size) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    return NULL;
  }
  fseek(f, 0, SEEK_END);
  *size = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *data = malloc(*size + 1);
  cr_assert_not_null(data);
  cr_assert_eq(fread(data, 1, *size, f), *size, "cannot read %s", path);
  fclose(f);
  return data;
}

/* Entries of `path` other than "." and "..", hidden files included (a
 * leftover temporary file counts). */
static inline int io_test_count_entries(const char *path) {
  DIR *d = opendir(path);
  cr_assert_not_null(d);
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
  }
  closedir(d);
  return n;
}

#endif
