/* The exact albedo of a translucent material: the diffuse
 * reflectance at normal incidence, per unit incident power and specular
 * reflection excluded, of a half-space of reduced single-scattering albedo
 * alpha' = (1 - g) alpha / (1 - g alpha) behind a smooth boundary eta with a
 * Henyey-Greenstein phase function of mean cosine g, tabulated from the
 * half-space Monte Carlo reference (halfspace.h) by
 * scripts/make_albedo_table.py and shipped as data/halfspace_albedo.txt
 * (format and accuracy: docs/albedo.md). By reciprocity it is also the
 * radiance of a thick slab's face seen head-on under a uniform environment of
 * radiance 1, specular reflection excluded: the surface colour users give.
 *
 * Interpolation: in u = sqrt(1 - alpha') by a monotone piecewise cubic
 * (PCHIP, Fritsch & Carlson 1980 with the slopes of Fritsch & Butland 1984),
 * linear in eta and g between the table's curves (positive weights keep each
 * interpolated curve strictly decreasing in u, so the inversion is unique).
 * The ends are exact: u = 1 (alpha = 0) reflects 0, u = 0 (no absorption)
 * returns all that entered, 1 - F(0). */
#ifndef SUBSURF_ALBEDO_TABLE_H
#define SUBSURF_ALBEDO_TABLE_H

#include "subsurf/status.h"

#include <stddef.h>

#define SS_ALBEDO_TABLE_VERSION 1
#define SS_ALBEDO_TABLE_MAX_GRID 64

typedef struct ss_albedo_table ss_albedo_table;

/* Parses a table's text (`label` names it in messages: "FILE:LINE: ..."):
 * version, grids (strictly increasing; u from 0 to 1), one curve per (eta,
 * g) in order, each strictly decreasing with its exact ends, standard errors
 * finite and >= 0, and the CRC-32 of everything before its last line. */
ss_status ss_albedo_table_parse(const char *text, size_t size, const char *label,
                                ss_albedo_table **out, ss_error *err);
/* Reads a table file (regular files only, at most 1 MiB) and parses it. */
ss_status ss_albedo_table_load(const char *path, ss_albedo_table **out, ss_error *err);
void ss_albedo_table_destroy(ss_albedo_table *t);

/* The shipped table, compiled into the library at build time and parsed
 * (with every check above) on first use; thread-safe; never destroyed. */
ss_status ss_albedo_table_builtin(const ss_albedo_table **out, ss_error *err);

/* The table's range: eta in [eta_lo, eta_hi], g in [g_lo, g_hi]. */
void ss_albedo_table_range(const ss_albedo_table *t, double *eta_lo, double *eta_hi, double *g_lo,
                           double *g_hi);
/* SS_OK when (g, eta) lies in the table's range; else a message naming
 * the value and the range. */
ss_status ss_albedo_table_check(const ss_albedo_table *t, double g, double eta, ss_error *err);

/* The albedo of reduced albedo alpha' in [0, 1] (g, eta in range); *error
 * (may be NULL) receives its interpolated standard error. */
double ss_albedo_table_albedo(const ss_albedo_table *t, double alpha_reduced, double g, double eta,
                              double *error);
/* The reduced albedo whose albedo is `albedo`, in [0, 1 - F(0)] (clamped to
 * it); the exact inverse of ss_albedo_table_albedo. */
double ss_albedo_table_invert(const ss_albedo_table *t, double albedo, double g, double eta);

/* 1 - F(0): the albedo of a medium without absorption, the largest a
 * boundary of index eta lets through. */
double ss_albedo_max(double eta);

#endif
