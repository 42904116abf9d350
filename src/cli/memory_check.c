#include "cli/memory_check.h"

#include <math.h>
#include <stdio.h>
#include <unistd.h>

/* Bytes of physical memory (INFINITY when unknown). */
static double physical_memory(void) {
  long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  return pages > 0 && size > 0 ? (double)pages * (double)size : INFINITY;
}

int ss_cli_check_memory(const char *cmd, double need, const char *what, const char *hint) {
  double have = physical_memory();
  if (need <= have) {
    return 0;
  }
  fprintf(stderr, "subsurf %s: %s need %.1f GB, more than this machine's %.1f GB of memory (%s)\n",
          cmd, what, need / 1e9, have / 1e9, hint);
  return -1;
}
