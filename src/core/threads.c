#include "subsurf/threads.h"

#include <omp.h>

ss_status ss_threads_check(int threads, ss_error *err) {
  if (threads < 0 || threads > SS_THREADS_MAX) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "threads must be in [0, %d] (got %d)",
                        SS_THREADS_MAX, threads);
  }
  return SS_OK;
}

int ss_threads_team(int threads) {
  int n = threads > 0 ? threads : omp_get_max_threads();
  return n < SS_THREADS_MAX ? n : SS_THREADS_MAX;
}
