/* subsurf's plugins: shared objects that hold the code needing a heavy
 * library (OpenVDB, Open MPI, PLplot), opened on first use instead of
 * linked, so that a process that does not use them does not load them
 * (bench/RESULTS.md, issue 14: each costs every process milliseconds of
 * dynamic loading). A plugin is looked for beside the library or executable
 * holding this code (the build tree, an installed libsubsurf.so), then
 * beside the running executable, and in the library directory next to each
 * (an installed bin/subsurf). */
#ifndef SUBSURF_IO_PLUGIN_H
#define SUBSURF_IO_PLUGIN_H

#include "subsurf/status.h"

/* dlopen's handle of the plugin named `file` ("libsubsurf_vdb.so"), or NULL
 * with err set (SS_ERR_UNSUPPORTED) naming `file` and `what` needs it
 * ("OpenVDB files"); `needs` names the library the plugin links, for the
 * message when it does not load ("libopenvdb"). */
void *ss_plugin_open(const char *file, const char *what, const char *needs, ss_error *err);

#endif
