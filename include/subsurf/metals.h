/* Named metals: measured optical constants n + i k converted to the three
 * linear sRGB channels that conductors take (src/optics/metals.c says
 * how). */
#ifndef SUBSURF_METALS_H
#define SUBSURF_METALS_H

#include "subsurf/vec3.h"

#include <stddef.h>

size_t ss_metal_count(void);
/* The chemical symbol ("Au") and the measurement's key in
 * docs/references.md. */
const char *ss_metal_name(size_t i);
const char *ss_metal_source(size_t i);
/* Finds a metal by symbol (case-insensitive); -1 when unknown. */
int ss_metal_find(const char *name);
/* The known symbols, comma separated ("Ag, Al, ..."). */
const char *ss_metal_names(void);
/* The measured n, k at a wavelength in [380, 780] nm, interpolated
 * linearly between the measured points. */
void ss_metal_index_at(size_t i, double lambda_nm, double *n, double *k);
/* The normal-incidence reflectance of the measured spectrum in linear
 * sRGB (equal-energy light, a perfect reflector mapped to 1). */
ss_vec3 ss_metal_reflectance(size_t i);
/* The per-channel eta and k conductors use: the same normal-incidence
 * reflectance per channel as ss_metal_reflectance. */
void ss_metal_rgb(size_t i, ss_vec3 *eta, ss_vec3 *k);

#endif
