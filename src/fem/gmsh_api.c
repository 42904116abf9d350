/* Loading gmsh's C API at run time (see gmsh_api.h). */
#include "fem/gmsh_api.h"

#include "core/dynlib.h"

#ifndef SUBSURF_GMSH_LIBRARY
#error "SUBSURF_GMSH_LIBRARY (the path of libgmsh, set by CMake) is required"
#endif

ss_status ss_gmsh_api_get(const ss_gmsh_api **api, ss_error *err) {
  static ss_gmsh_api table;
  static int loaded;
  if (!loaded) {
#define SS_GMSH_SYMBOL(f) {#f, (void **)&table.f},
    const ss_dynlib_symbol symbols[] = {SS_GMSH_FUNCTIONS(SS_GMSH_SYMBOL)};
#undef SS_GMSH_SYMBOL
    ss_status st = ss_dynlib_open(SUBSURF_GMSH_LIBRARY, "gmsh",
                                  "install libgmsh-dev (scripts/install-deps.sh)", "gmsh 4.8",
                                  symbols, sizeof symbols / sizeof *symbols, err);
    if (st != SS_OK) {
      ss_error_prefix(err, "fem mesh: ");
      return st;
    }
    loaded = 1;
  }
  *api = &table;
  return SS_OK;
}
