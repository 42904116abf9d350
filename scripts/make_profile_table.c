/* Builds the exact half-space profile table that `ss_profile_table_builtin`
 * ships (data/halfspace_profiles.txt, format in docs/fit.md):
 *
 *   cmake --build build --target make_profile_table
 *   build/make_profile_table OUT [PATHS [SEED [ETA [G]]]]
 *
 * OUT must not exist (the shipped file is replaced by hand, after review);
 * Ctrl-C stops the run and writes nothing. */
#include "subsurf/profile_table.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static volatile sig_atomic_t interrupted;

static void on_interrupt(int sig) {
  (void)sig;
  interrupted = 1;
}

/* One line per 5 % of the paths, on stderr. */
static void on_progress(void *ctx, uint64_t done, uint64_t total) {
  int *last = ctx, pct = (int)(100.0 * (double)done / (double)total);
  if (pct / 5 > *last / 5) {
    fprintf(stderr, "make_profile_table: %d %% of %llu paths\n", pct, (unsigned long long)total);
    *last = pct;
  }
}

static int parse_number(const char *text, const char *name, double lo, double hi, double *out) {
  char *end;
  errno = 0;
  double v = strtod(text, &end);
  if (errno || end == text || *end || !(v >= lo && v <= hi)) {
    fprintf(stderr, "make_profile_table: %s: expected a number in [%g, %g], got '%s'\n", name, lo,
            hi, text);
    return 0;
  }
  *out = v;
  return 1;
}

int main(int argc, char **argv) {
  if (argc < 2 || argc > 6) {
    fprintf(stderr, "usage: make_profile_table OUT [PATHS [SEED [ETA [G]]]]\n");
    return 2;
  }
  ss_profile_table_build_params p;
  ss_profile_table_build_params_default(&p);
  double paths = (double)p.paths, seed = (double)p.seed;
  if ((argc > 2 && !parse_number(argv[2], "PATHS", 1, 1e12, &paths)) ||
      (argc > 3 && !parse_number(argv[3], "SEED", 0, 9e15, &seed)) ||
      (argc > 4 && !parse_number(argv[4], "ETA", 1, 3, &p.eta)) ||
      (argc > 5 && !parse_number(argv[5], "G", -0.99, 0.99, &p.g))) {
    return 2;
  }
  p.paths = (uint64_t)paths;
  p.seed = (uint64_t)seed;
  int fd = open(argv[1], O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    fprintf(stderr, "make_profile_table: %s: %s\n", argv[1], strerror(errno));
    return 2;
  }
  signal(SIGINT, on_interrupt);
  signal(SIGTERM, on_interrupt);
  p.cancel = &interrupted;
  int last_pct = 0;
  p.progress = on_progress;
  p.progress_ctx = &last_pct;
  char *text = NULL;
  size_t size = 0;
  ss_error err = {0};
  ss_status st = ss_profile_table_build(&p, &text, &size, &err);
  size_t done = 0;
  while (st == SS_OK && done < size) {
    ssize_t n = write(fd, text + done, size - done);
    if (n <= 0) {
      snprintf(err.message, sizeof err.message, "%s: %s", argv[1], strerror(errno));
      st = SS_ERR_IO;
      break;
    }
    done += (size_t)n;
  }
  free(text);
  if (close(fd) != 0 && st == SS_OK) {
    snprintf(err.message, sizeof err.message, "%s: %s", argv[1], strerror(errno));
    st = SS_ERR_IO;
  }
  if (st != SS_OK) {
    unlink(argv[1]);
    fprintf(stderr, "make_profile_table: %s\n", err.message);
    return st == SS_ERR_INTERRUPTED ? 130 : 1;
  }
  printf("make_profile_table: wrote %s (%zu bytes)\n", argv[1], size);
  return 0;
}
