/* The multipole profiles of one slab (DonnerJensen2005
 * eq. 10-13), shared by the `multipole` model and the layer adding of layers.c.
 * Private to src/bssrdf. */
#ifndef SUBSURF_BSSRDF_MULTIPOLE_H
#define SUBSURF_BSSRDF_MULTIPOLE_H

#include "subsurf/bssrdf.h"

typedef struct {
  double alpha_prime, sigma_tr;
  double d;       /* thickness (INFINITY: half-space, one pair) */
  int n;          /* pairs i = -n..n */
  double period;  /* 2 (d + z_b,top + z_b,bottom) */
  double l, z_bt; /* source depth 1/sigma_t', top extrapolation distance */
} ss_multipole;

/* Sets up a slab of thickness d (> 0 or INFINITY) whose top and bottom faces
 * have boundary terms A_top and A_bottom (Jensen et al. 2001's A of the
 * relative index across each face); n is chosen so that the omitted pairs
 * weigh less than 1e-8 (at most max_pairs). */
void ss_multipole_setup(ss_multipole *m, ss_bssrdf_coeffs k, double d, double A_top,
                        double A_bottom, int max_pairs);
/* Reflectance and transmittance profiles R(r), T(r) per unit power entering. */
double ss_multipole_reflectance(const ss_multipole *m, double r);
double ss_multipole_transmittance(const ss_multipole *m, double r);
/* 2 pi int_0^rho r R(r) dr and the same for T (rho = INFINITY: the totals). */
double ss_multipole_reflectance_disk(const ss_multipole *m, double rho);
double ss_multipole_transmittance_disk(const ss_multipole *m, double rho);

#endif
