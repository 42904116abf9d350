/* The pbrt-style perpendicular-incidence BSSRDF table (Ferrier2016 sec. 2.2 and
 * 3.1): photon beam diffusion (multiple + single scattering) tabulated
 * over albedo x radius in units where sigma_t = 1, interpolated and sampled
 * with Catmull-Rom splines, and inverted from a desired diffuse colour to the
 * single-scattering albedo (pbrt-v3's SubsurfaceFromDiffuse). */
#ifndef SUBSURF_TABLE_RADIAL_H
#define SUBSURF_TABLE_RADIAL_H

#include "subsurf/status.h"

#include <stddef.h>

#define SS_TABLE_RHO_COUNT 100
#define SS_TABLE_RADIUS_COUNT 64

/* The grids (Ferrier2016 sec. 2.2, pbrt-v3's):
 * rho_i = (1 - e^{-8 i/(n-1)})/(1 - e^{-8}); r_0 = 0, r_1 = 0.0025,
 * r_{i+1} = 1.2 r_i (optical units, sigma_t = 1). */
void ss_table_rho_grid(double *rho, size_t n);
void ss_table_radius_grid(double *r, size_t n);

typedef struct {
  double eta, g;
  size_t n_rho, n_r;
  double *rho;     /* n_rho albedo nodes */
  double *radius;  /* n_r optical radius nodes */
  float *profile;  /* n_rho x n_r: 2 pi r (E_ms + E_ss)(r), sigma_t = 1 */
  float *cdf;      /* n_rho x n_r: cumulative spline integral of the profile */
  double *rho_eff; /* n_rho: spline integral of each profile row */
} ss_table_radial;

/* Allocates a table on those grids with zero data. */
ss_status ss_table_radial_alloc(double eta, double g, ss_table_radial **out, ss_error *err);
void ss_table_radial_destroy(ss_table_radial *t);

/* Fills the profile by direct PBD (OpenMP over albedos) and finishes it. */
ss_status ss_table_radial_build(double eta, double g, ss_table_radial **out, ss_error *err);
/* Computes cdf and rho_eff from the profile (after building or loading). */
void ss_table_radial_finish(ss_table_radial *t);

/* S_p(r) per unit area at optical radius r (0 outside the table). */
double ss_table_radial_sp(const ss_table_radial *t, double rho, double r);
/* Effective albedo int 2 pi r S_p dr of the interpolated profile. */
double ss_table_radial_rho_eff(const ss_table_radial *t, double rho);
/* Samples an optical radius with density profile(r)/rho_eff; returns -1 when
 * the albedo has no energy. */
double ss_table_radial_sample(const ss_table_radial *t, double rho, double u);
/* Density of ss_table_radial_sample per unit area of the plane
 * (profile / (2 pi r rho_eff)); 0 at r = 0 and outside the table. */
double ss_table_radial_pdf_area(const ss_table_radial *t, double rho, double r);
/* Single-scattering albedo whose rho_eff is the given value (clamped). */
double ss_table_radial_invert(const ss_table_radial *t, double rho_eff);

/* pbrt-v3 SubsurfaceFromDiffuse: per channel, the coefficients whose
 * effective albedo is diffuse[c] with mean free path mfp[c] = 1/sigma_t. */
ss_status ss_subsurface_from_diffuse(const ss_table_radial *t, const double diffuse[3],
                                     const double mfp[3], double sigma_s[3], double sigma_a[3],
                                     ss_error *err);

#endif
