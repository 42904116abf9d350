/* The library's version, as CMake's project(VERSION) sets it: printed by
 * `subsurf --version` and written into every JSON output
 * ("subsurf_version"), so that a result names the code that made it. */
#ifndef SUBSURF_VERSION_H
#define SUBSURF_VERSION_H

/* "MAJOR.MINOR.PATCH". */
const char *ss_version(void);

#endif
