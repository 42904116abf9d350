/* Sampling warps: maps from the unit square to common domains, each with its
 * density. Every warp is covered by the chi-square harness (chi2.h). */
#ifndef SUBSURF_SAMPLING_H
#define SUBSURF_SAMPLING_H

#include "subsurf/rng.h"
#include "subsurf/vec3.h"

#include <stddef.h>

#define SS_PI 3.14159265358979323846
#define SS_INV_PI 0.31830988618379067154
#define SS_INV_4PI 0.07957747154594766788

ss_vec3 ss_sample_uniform_sphere(double u1, double u2);
double ss_pdf_uniform_sphere(void);

/* Hemisphere about +z. */
ss_vec3 ss_sample_uniform_hemisphere(double u1, double u2);
double ss_pdf_uniform_hemisphere(void);
ss_vec3 ss_sample_cosine_hemisphere(double u1, double u2);
double ss_pdf_cosine_hemisphere(double cos_theta);

/* Cone of directions about +z with cos(theta) >= cos_max. */
ss_vec3 ss_sample_uniform_cone(double u1, double u2, double cos_max);
double ss_pdf_uniform_cone(double cos_max);

/* Concentric map of the square onto the unit disk (Shirley & Chiu 1997). */
void ss_sample_concentric_disk(double u1, double u2, double *x, double *y);

/* Uniform barycentrics on a triangle (Heitz 2019, low-distortion map). */
void ss_sample_uniform_triangle(double u1, double u2, double *b0, double *b1);

/* Distance with density sigma exp(-sigma t) on [0, inf). */
static inline double ss_sample_exponential(double u, double sigma) { return -log1p(-u) / sigma; }

/* A piecewise-constant 1D distribution over n cells (cdf of n + 1 entries). */
typedef struct {
  size_t n;
  double *func;
  double *cdf;
  double integral;
} ss_distribution1d;

/* Builds the distribution of `func` (n >= 1 non-negative values). Returns 0 on
 * success, -1 when allocation fails or every value is zero. */
int ss_distribution1d_init(ss_distribution1d *d, const double *func, size_t n);
void ss_distribution1d_free(ss_distribution1d *d);
/* Picks a cell with probability func[i] / sum; returns it and its probability. */
size_t ss_distribution1d_sample_discrete(const ss_distribution1d *d, double u, double *prob);
/* Continuous sample in [0, 1) with density func(x) / integral. */
double ss_distribution1d_sample_continuous(const ss_distribution1d *d, double u, double *pdf);

/* A piecewise-constant 2D distribution over nu x nv cells of the unit
 * square (pbrt-v3 sec. 13.6.7): v from the marginal density of the rows,
 * then u from the chosen row's conditional density (distribution2d.c). */
typedef struct {
  size_t nu, nv;
  ss_distribution1d *rows;    /* nv conditional densities of u (a black row: uniform) */
  ss_distribution1d marginal; /* over v: the rows' integrals */
} ss_distribution2d;

/* Builds the distribution of `func` (nu * nv non-negative finite values,
 * row-major). Returns 0 on success, -1 when allocation fails or every value
 * is zero. */
int ss_distribution2d_init(ss_distribution2d *d, const double *func, size_t nu, size_t nv);
void ss_distribution2d_free(ss_distribution2d *d);
/* A point (u, v) of [0, 1)^2 with density func(u, v) / integral, returned
 * in *pdf. */
void ss_distribution2d_sample(const ss_distribution2d *d, double u1, double u2, double *u,
                              double *v, double *pdf);
/* The density of (u, v) in [0, 1]^2 (the last cell's closed edge included). */
double ss_distribution2d_pdf(const ss_distribution2d *d, double u, double v);

/* (cos phi, sin phi) for a uniform azimuth without trigonometry: a point
 * uniform in the unit disk, by rejection from the square, has a uniform
 * angle; the double-angle formulas then give a uniform azimuth on [0, 2 pi)
 * from the half-angle (von Neumann 1951). */
static inline void ss_sample_uniform_azimuth(ss_rng *rng, double *cos_phi, double *sin_phi) {
  double x, y, s;
  do {
    x = 2.0 * ss_rng_uniform(rng) - 1.0;
    y = 2.0 * ss_rng_uniform(rng) - 1.0;
    s = x * x + y * y;
  } while (s >= 1.0 || s == 0.0);
  *cos_phi = (x * x - y * y) / s;
  *sin_phi = 2.0 * x * y / s;
}

#endif
