/* Directory helpers of the I/O tests. */
#ifndef SUBSURF_TESTS_IO_TEST_DIR_H
#define SUBSURF_TESTS_IO_TEST_DIR_H

#include <criterion/criterion.h>
#include <dirent.h>
#include <string.h>

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
