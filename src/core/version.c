#include "subsurf/version.h"

const char *ss_version(void) { return SUBSURF_VERSION; }
