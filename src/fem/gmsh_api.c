/* Loading gmsh's C API at run time (see gmsh_api.h). */
#include "fem/gmsh_api.h"

#include <dlfcn.h>

#ifndef SUBSURF_GMSH_LIBRARY
#error "SUBSURF_GMSH_LIBRARY (the path of libgmsh, set by CMake) is required"
#endif

ss_status ss_gmsh_api_get(const ss_gmsh_api **api, ss_error *err) {
  static ss_gmsh_api table;
  static int loaded;
  if (!loaded) {
    void *lib = dlopen(SUBSURF_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      const char *why = dlerror();
      return ss_error_set(err, SS_ERR_UNSUPPORTED,
                          "fem mesh: cannot load gmsh (%s): %s; install libgmsh-dev "
                          "(scripts/install-deps.sh)",
                          SUBSURF_GMSH_LIBRARY, why ? why : "unknown error");
    }
    /* POSIX's way to store dlsym's object pointer into a function pointer */
#define SS_GMSH_LOAD(f)                                                                            \
  *(void **)(&table.f) = dlsym(lib, #f);                                                           \
  if (!table.f) {                                                                                  \
    dlclose(lib);                                                                                  \
    return ss_error_set(err, SS_ERR_UNSUPPORTED, "fem mesh: %s has no %s (gmsh 4.8 expected)",     \
                        SUBSURF_GMSH_LIBRARY, #f);                                                 \
  }
    SS_GMSH_FUNCTIONS(SS_GMSH_LOAD)
#undef SS_GMSH_LOAD
    loaded = 1;
  }
  *api = &table;
  return SS_OK;
}
