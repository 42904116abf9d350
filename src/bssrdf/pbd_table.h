/* A per-material table of photon beam diffusion's exitance (private to
 * src/bssrdf): S_ms(r, phi; theta) on a (theta, phi, r) grid and S_ss(r) on
 * the same radii, for one channel of one medium, so that the `pbd` model's
 * eval costs a trilinear lookup instead of a beam integral (Habel et al.
 * 2013's quadrature, ~3.6 us per channel). Interpolation is linear in theta
 * and phi and in r of the logarithm (exact for the e^{-sigma r} tails); radii
 * outside the grid are evaluated directly. */
#ifndef SUBSURF_BSSRDF_PBD_TABLE_H
#define SUBSURF_BSSRDF_PBD_TABLE_H

#include "subsurf/pbd.h"

#define SS_PBD_TABLE_THETA 16 /* incidence 0..90 degrees, 6 degree steps */
#define SS_PBD_TABLE_PHI 17   /* exit azimuth 0..180 degrees */
#define SS_PBD_TABLE_R 64     /* geometric radii */

typedef struct {
  double r[SS_PBD_TABLE_R], inv_log_q;
  double ln_ms[SS_PBD_TABLE_THETA][SS_PBD_TABLE_PHI][SS_PBD_TABLE_R];
  double ln_ss[SS_PBD_TABLE_R];
} ss_pbd_table;

/* Tabulates p between radii r_lo and r_hi (0 < r_lo < r_hi). */
void ss_pbd_table_build(ss_pbd_table *t, const ss_pbd *p, double r_lo, double r_hi);
/* S_ms + S_ss at incidence theta in [0, pi/2], radius r, azimuth phi in
 * [0, pi] (ss_entry_geometry's convention), as ss_pbd_ms + ss_pbd_ss. */
double ss_pbd_table_eval(const ss_pbd_table *t, const ss_pbd *p, double theta, double r,
                         double phi);

#endif
