/* Colour matching: the CIE 1931 2-degree standard observer by the
 * multi-lobe Gaussian fit of Wyman, Sloan & Shirley 2013 (within the
 * measured functions' own uncertainty for rendering), and linear sRGB. */
#ifndef SUBSURF_CIE_H
#define SUBSURF_CIE_H

#include "subsurf/vec3.h"

/* x-bar, y-bar, z-bar at a wavelength in nanometres. */
ss_vec3 ss_cie_xyz(double lambda_nm);
/* CIE XYZ to linear sRGB (IEC 61966-2-1 primaries, D65 white). */
ss_vec3 ss_xyz_to_linear_srgb(ss_vec3 xyz);

#endif
