/* Finding and opening subsurf's plugins (plugin.h). */
#define _GNU_SOURCE /* dladdr */
#include "io/plugin.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef SUBSURF_INSTALL_LIBDIR
#error                                                                                             \
    "SUBSURF_INSTALL_LIBDIR (the library directory relative to the prefix, set by CMake) is required"
#endif

/* The path of `plugin` in the directory of `file` followed by `sub`
 * (malloc'ed; NULL when `file` names no directory or memory is short). */
static char *plugin_path(const char *file, const char *sub, const char *plugin) {
  const char *slash = file ? strrchr(file, '/') : NULL;
  if (!slash) {
    return NULL;
  }
  int dir = (int)(slash - file);
  size_t size = (size_t)dir + strlen(sub) + strlen(plugin) + 2;
  char *path = malloc(size);
  if (path) {
    snprintf(path, size, "%.*s%s/%s", dir, file, sub, plugin);
  }
  return path;
}

ss_status ss_plugin_open(const char *file, const char *what, const char *needs,
                         const ss_dynlib_symbol *symbols, size_t n, ss_error *err) {
  static const char here;
  Dl_info info;
  char exe[4096];
  ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  exe[len > 0 ? len : 0] = '\0';
  const char *origins[2] = {dladdr(&here, &info) ? info.dli_fname : NULL, exe};
  const char *subs[2] = {"", "/../" SUBSURF_INSTALL_LIBDIR};
  for (int i = 0; i < 4; ++i) {
    char *path = plugin_path(origins[i % 2], subs[i / 2], file);
    if (!path || access(path, R_OK) != 0) {
      free(path);
      continue;
    }
    char plugin[256], remedy[256], expected[256];
    snprintf(plugin, sizeof plugin, "the plugin for %s", what);
    snprintf(remedy, sizeof remedy, "%s comes with scripts/install-deps.sh", needs);
    snprintf(expected, sizeof expected, "subsurf's plugin for %s", what);
    ss_status st = ss_dynlib_open(path, plugin, remedy, expected, symbols, n, err);
    free(path);
    return st;
  }
  return ss_error_set(err, SS_ERR_UNSUPPORTED,
                      "the plugin %s (for %s) was found neither beside %s nor in ../%s from "
                      "there: build subsurf, or install it with make install",
                      file, what, origins[0] ? origins[0] : exe, SUBSURF_INSTALL_LIBDIR);
}
