/* Running `mpirun` (Open MPI, localhost, --oversubscribe: more ranks than
 * cores) for the CLI tests of the commands that split their work over MPI
 * ranks, and comparing their files byte for byte. */
#ifndef SUBSURF_TESTS_CLI_MPIRUN_H
#define SUBSURF_TESTS_CLI_MPIRUN_H

#include "cli/cli_run.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Runs `mpirun ARGS` in dir: exit code and stderr in r, stdout in
 * dir/out.txt. In the sanitizer build LeakSanitizer is off for the ranks:
 * Open MPI's plugins, unloaded at MPI_Finalize, keep allocations it cannot
 * attribute (the commands' own leaks are checked by the tests without
 * mpirun). */
static inline void mpirun(const char *dir, cli_result *r, const char *args) {
  char cmd[4096];
  snprintf(cmd, sizeof cmd,
           "cd %s && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
           "ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" "
           "OMPI_MCA_rmaps_base_oversubscribe=1 mpirun --oversubscribe %s >out.txt 2>err.txt",
           dir, args);
  int st = system(cmd);
  r->status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  char path[256];
  snprintf(path, sizeof path, "%s/err.txt", dir);
  cli_slurp(path, r->err, sizeof r->err);
}

/* The bytes of dir/name (malloc'd in *data), or -1 when it cannot be read. */
static inline long mpirun_file_bytes(const char *dir, const char *name, char **data) {
  char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "rb");
  if (!f) {
    return -1;
  }
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  rewind(f);
  *data = malloc((size_t)n + 1);
  cr_assert(fread(*data, 1, (size_t)n, f) == (size_t)n);
  (*data)[n] = '\0';
  fclose(f);
  return n;
}

static inline void expect_same_file(const char *dir, const char *a, const char *b) {
  char *x = NULL, *y = NULL;
  long nx = mpirun_file_bytes(dir, a, &x), ny = mpirun_file_bytes(dir, b, &y);
  cr_expect(nx > 0 && nx == ny, "%s (%ld bytes) and %s (%ld bytes)", a, nx, b, ny);
  if (nx > 0 && nx == ny) {
    cr_expect(!memcmp(x, y, (size_t)nx), "%s and %s differ", a, b);
  }
  free(x);
  free(y);
}

#endif
