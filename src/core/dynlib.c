/* Opening a shared object and its symbols (dynlib.h). */
#include "core/dynlib.h"

#include <dlfcn.h>

static void clear(const ss_dynlib_symbol *symbols, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    *symbols[i].address = NULL;
  }
}

ss_status ss_dynlib_open(const char *path, const char *what, const char *remedy,
                         const char *expected, const ss_dynlib_symbol *symbols, size_t n,
                         ss_error *err) {
  clear(symbols, n);
  void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    const char *why = dlerror();
    return ss_error_set(err, SS_ERR_UNSUPPORTED, "cannot load %s (%s): %s; %s", what, path,
                        why ? why : "unknown error", remedy);
  }
  for (size_t i = 0; i < n; ++i) {
    *symbols[i].address = dlsym(lib, symbols[i].name);
    if (!*symbols[i].address) {
      clear(symbols, n);
      dlclose(lib);
      return ss_error_set(err, SS_ERR_UNSUPPORTED, "%s has no %s (%s expected)", path,
                          symbols[i].name, expected);
    }
  }
  return SS_OK;
}
