/* subsurf's plugins: shared objects that hold the code needing a heavy
 * library (OpenVDB, Open MPI, PLplot), opened on first use instead of
 * linked, so that a process that does not use them does not load them
 * (bench/RESULTS.md: each costs every process milliseconds of
 * dynamic loading). A plugin is looked for beside the library or executable
 * holding this code (the build tree, an installed libsubsurf.so), then
 * beside the running executable, and in the library directory next to each
 * (an installed bin/subsurf). */
#ifndef SUBSURF_IO_PLUGIN_H
#define SUBSURF_IO_PLUGIN_H

#include "core/dynlib.h"
#include "subsurf/status.h"

/* Opens the plugin named `file` ("libsubsurf_vdb.so") and stores the
 * addresses of its n symbols (core/dynlib.h). SS_OK, or SS_ERR_UNSUPPORTED
 * with err naming `file` and `what` needs it ("OpenVDB files") when it is
 * not found, with `needs`, the library the plugin links ("libopenvdb"),
 * when it does not load, or the symbol it lacks. */
ss_status ss_plugin_open(const char *file, const char *what, const char *needs,
                         const ss_dynlib_symbol *symbols, size_t n, ss_error *err);

#endif
