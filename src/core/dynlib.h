/* Shared objects opened at run time (dlopen) instead of linked: the system
 * libraries found at configure time whose loading would cost every process
 * (gmsh, CHOLMOD: src/fem/gmsh_api.h, cholmod_api.h) and subsurf's own
 * plugins (io/plugin.h). One place says why such an object cannot be used:
 * it does not load (and what to install), or it lacks a symbol. */
#ifndef SUBSURF_CORE_DYNLIB_H
#define SUBSURF_CORE_DYNLIB_H

#include "subsurf/status.h"

#include <stddef.h>

/* A symbol the object must define and where its address goes; for a
 * function pointer f, (void **)&f (POSIX's way to store dlsym's object
 * pointer into a function pointer). */
typedef struct {
  const char *name;
  void **address;
} ss_dynlib_symbol;

/* Opens the shared object `path` (dlopen, RTLD_NOW | RTLD_LOCAL, kept open
 * for the process's life) and stores the address of each of the n symbols.
 * SS_OK, or SS_ERR_UNSUPPORTED with every address NULL and err set to
 *   "cannot load WHAT (PATH): WHY; REMEDY" when it does not load, or
 *   "PATH has no SYMBOL (EXPECTED expected)" when a symbol is missing,
 * e.g. what "CHOLMOD", remedy "install libsuitesparse-dev
 * (scripts/install-deps.sh)", expected "CHOLMOD 3". */
ss_status ss_dynlib_open(const char *path, const char *what, const char *remedy,
                         const char *expected, const ss_dynlib_symbol *symbols, size_t n,
                         ss_error *err);

#endif
