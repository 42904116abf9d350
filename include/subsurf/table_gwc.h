/* Ferrier's non-perpendicular multiple-scattering table (Ferrier2016 sec. 3-4
 * and 7.1): photon beam diffusion tabulated over albedo x incidence x
 * radius (100 x 10 x 64, sigma_t = 1) as the radial energy
 * E = r int S_ms dphi plus an analytic azimuthal model per cell.
 *
 * Two azimuthal models share the table layout:
 * - SS_TABLE_GWC_ANCHORS (the paper): General Wrapped Cauchy
 *   f = alpha + beta pdf_WC(phi; c) through three PBD anchors; cells store
 *   E, c and beta as the fraction beta r / E (the same information as the
 *   paper's beta, but bounded, which interpolates better), with
 *   alpha = (E/r - beta)/(2 pi); 1 MiB with the cumulative radial energy.
 * - SS_TABLE_GWC_TWO_LOBE (subsurf's improvement, the default): two Wrapped
 *   Cauchy lobes f = (E/r) [lambda pdf_WC(phi; c1) + (1 - lambda) pdf_WC(phi; c2)]
 *   least-squares fitted to 17 azimuths, E integrated exactly. The shape is
 *   stored as its harmonics H_1..H_3 (gwc.h: smooth where (lambda, c1, c2)
 *   is degenerate) on every other radius (32 nodes: it varies slowly with
 *   log r), so the table is smaller than the paper's (885 KiB). It contains
 *   the GWC (c2 = 0) and follows PBD's azimuthal harmonics, which decay
 *   faster than geometrically near the beam: 2-8x smaller errors.
 *
 * Both sample r by Catmull-Rom inversion of the cumulative radial energy and
 * phi by inverting the analytic CDF (gwc.c), both started near the answer
 * (guide tables, a Cauchy-mixture quantile) and finished by safeguarded
 * fourth-order steps.
 * Values are multiple scattering only, per unit area, sigma_t = 1. */
#ifndef SUBSURF_TABLE_GWC_H
#define SUBSURF_TABLE_GWC_H

#include "subsurf/catmull_rom.h"
#include "subsurf/status.h"

#include <stddef.h>

#define SS_TABLE_THETA_COUNT 10

typedef enum {
  SS_TABLE_GWC_ANCHORS = 0,
  SS_TABLE_GWC_TWO_LOBE = 1,
} ss_table_gwc_fit;

typedef struct {
  double eta, g;
  int fit; /* ss_table_gwc_fit */
  size_t n_rho, n_theta, n_r;
  size_t n_rs;    /* radius nodes of the shape parameters (64 or 32) */
  size_t n_shape; /* shape parameters per node: 2 (beta, c) or 3 (lambda, c1, c2) */
  /* theta has n_theta + 1 nodes: the last, a ghost at 100 deg, mirrors the
   * one at 80 deg. Every tabulated quantity depends on theta through
   * sin(theta), even about 90 deg, so the theta splines get the exact zero
   * slope there instead of a one-sided difference (3x smaller errors near
   * grazing incidence). */
  double *rho, *theta, *radius, *radius_shape;
  float *energy;     /* [rho][theta][r]: E = r int S_ms dphi */
  float *shape;      /* [rho][theta][rs][n_shape]: anchors (beta r/E, c), two-lobe (H1, H2, H3) */
  float *cdf;        /* [rho][theta][r]: cumulative spline integral of E along r */
  float *albedo;     /* [rho][theta + ghost]: rho_eff(theta) = int E dr */
  float *albedo_cdf; /* [rho][theta + ghost]: cumulative spline integral along theta */
  double theta_weight[SS_TABLE_THETA_COUNT]; /* int_0^{pi/2} of each node's spline basis */
  /* Derived for fast queries, not tabulated data (ss_table_gwc_bytes leaves
   * them out): the axes' spline pieces (from the grids, at allocation) and
   * the radius marginal of the path sampler per albedo row with its
   * cumulative integral (ss_table_gwc_finish). */
  ss_cr_grid rho_grid, theta_grid, r_grid, rs_grid; /* rho_grid only when n_rho >= 4 */
  float *radial_energy; /* [rho][r]: sum_j theta_weight[j] E(rho, theta_j, r) */
  float *radial_cdf;    /* [rho][r] */
  /* Guide tables for inverting the cumulative rows: entry b of a row is the
   * interval where its cumulative energy reaches b / SS_TABLE_GWC_GUIDE of
   * its total (a start that is checked and corrected at each query). */
  uint8_t *cdf_guide;    /* [rho][theta][SS_TABLE_GWC_GUIDE] */
  uint8_t *radial_guide; /* [rho][SS_TABLE_GWC_GUIDE] */
  /* The shape interval holding each radius interval (the shape radii are
   * radius nodes): known once r's interval is, before r itself. */
  uint8_t *shape_interval; /* [n_r - 1] */
} ss_table_gwc;

#define SS_TABLE_GWC_GUIDE 64

ss_status ss_table_gwc_alloc(double eta, double g, int fit, ss_table_gwc **out, ss_error *err);
void ss_table_gwc_destroy(ss_table_gwc *t);

/* The table at one albedo (n_rho = 1): what a material needs, 4x fewer
 * memory taps per query and 10 KiB instead of 1 MiB. Every function below
 * accepts a slice and then ignores its rho argument. */
ss_status ss_table_gwc_slice(const ss_table_gwc *t, double rho, ss_table_gwc **out, ss_error *err);

/* Builds the table by direct PBD (OpenMP over (rho, theta) rows). */
ss_status ss_table_gwc_build(double eta, double g, int fit, ss_table_gwc **out, ss_error *err);
/* Derives cdf, albedo, albedo_cdf, theta_weight and the radius marginal
 * from energy. */
void ss_table_gwc_finish(ss_table_gwc *t);
/* Bytes of float32 data and grids the table holds (the paper's 1 MiB budget). */
size_t ss_table_gwc_bytes(const ss_table_gwc *t);
const char *ss_table_gwc_fit_name(int fit);
/* "anchors"/"gwc" or "two-lobe"; returns 0 when unknown. */
int ss_table_gwc_fit_from_name(const char *name, int *fit);

/* S_ms(r, phi; theta) per unit area (optical units); theta in [0, pi/2]. */
double ss_table_gwc_eval(const ss_table_gwc *t, double rho, double theta, double r, double phi);
/* rho_eff(theta) = int int S_ms dA of the interpolated table. */
double ss_table_gwc_albedo(const ss_table_gwc *t, double rho, double theta);

/* Ferrier2016 algorithm 2: (r, phi) with density eval / albedo per unit
 * area. Returns 0 when the cell has no energy. */
int ss_table_gwc_sample(const ss_table_gwc *t, double rho, double theta, double u1, double u2,
                        double *r, double *phi);
double ss_table_gwc_pdf(const ss_table_gwc *t, double rho, double theta, double r, double phi);

/* Ferrier2016 sec. 7.1 (algorithm 3), the path-tracing sampler: theta_i
 * from the effective-albedo table, (r, phi) by algorithm 2, phi' uniform
 * (the azimuth of the entry point about the exit point). */
int ss_table_gwc_sample_path(const ss_table_gwc *t, double rho, const double u[4], double *theta,
                             double *r, double *phi, double *phi_entry);
/* Its density over theta_i in [0, pi/2] (per radian). */
double ss_table_gwc_pdf_theta(const ss_table_gwc *t, double rho, double theta);
/* The radius marginal of the path sampler, drawn with one uniform, and its
 * density per unit area of the entry point (uniform in phi'). */
double ss_table_gwc_sample_radial(const ss_table_gwc *t, double rho, double u);
double ss_table_gwc_pdf_radial(const ss_table_gwc *t, double rho, double r);

#endif
