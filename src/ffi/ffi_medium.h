/* The medium of the flat interface's calls: per-channel sigma_s, sigma_a and
 * g with a Henyey-Greenstein phase function, no flakes. */
#ifndef SUBSURF_FFI_MEDIUM_H
#define SUBSURF_FFI_MEDIUM_H

#include "subsurf/medium_optics.h"

ss_medium_optics ss_ffi_medium(const double sigma_s[3], const double sigma_a[3], const double g[3]);

#endif
