/* Names of the levels of detail of translucent materials (material.h). */
#include "subsurf/material.h"

#include <string.h>

static const char *const names[] = {"bssrdf", "auto", "volpath", "brdf"};

int ss_lod_from_name(const char *name, ss_lod *lod) {
  for (int i = 0; i < 4; ++i) {
    if (!strcmp(name, names[i])) {
      *lod = (ss_lod)i;
      return 1;
    }
  }
  return 0;
}

const char *ss_lod_name(ss_lod lod) { return (unsigned)lod < 4 ? names[lod] : "?"; }
