/* Loading CHOLMOD at run time (see cholmod_api.h). */
#include "fem/cholmod_api.h"

#include "core/dynlib.h"

#include <limits.h>
#include <pthread.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

/* The definitions below, and so the declarations of cholmod.h (whose system
 * headers are included above, with their default visibility), are hidden. */
#pragma GCC visibility push(hidden)
#include <cholmod.h>

#ifndef SUBSURF_CHOLMOD_LIBRARY
#error "SUBSURF_CHOLMOD_LIBRARY (the path of libcholmod, set by CMake) is required"
#endif

#define SS_CHOLMOD_POINTER(ret, name, params, args) static ret(*loaded_##name) params;
SS_CHOLMOD_FUNCTIONS(SS_CHOLMOD_POINTER)
#undef SS_CHOLMOD_POINTER

#define SS_CHOLMOD_CALL(ret, name, params, args)                                                   \
  ret name params { return loaded_##name args; }
SS_CHOLMOD_FUNCTIONS(SS_CHOLMOD_CALL)
#undef SS_CHOLMOD_CALL
#pragma GCC visibility pop

static ss_status open_cholmod(ss_error *err) {
#define SS_CHOLMOD_SYMBOL(ret, name, params, args) {#name, (void **)&loaded_##name},
  const ss_dynlib_symbol symbols[] = {SS_CHOLMOD_FUNCTIONS(SS_CHOLMOD_SYMBOL)};
#undef SS_CHOLMOD_SYMBOL
  ss_status st = ss_dynlib_open(SUBSURF_CHOLMOD_LIBRARY, "CHOLMOD",
                                "install libsuitesparse-dev (scripts/install-deps.sh)", "CHOLMOD 3",
                                symbols, sizeof symbols / sizeof *symbols, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "fem: ");
  }
  return st;
}

ss_status ss_cholmod_load(ss_error *err) {
  static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
  static int loaded;
  ss_status st = SS_OK;
  pthread_mutex_lock(&lock);
  if (!loaded && (st = open_cholmod(err)) == SS_OK) {
    loaded = 1;
  }
  pthread_mutex_unlock(&lock);
  return st;
}
