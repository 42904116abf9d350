/* Chi-square goodness-of-fit harness for samplers (after pbrt-v4's and
 * Mitsuba's tests): draw many samples into a histogram, integrate the claimed
 * pdf over each cell, pool cells whose expected count is below 5, and report
 * the p-value of Pearson's statistic. */
#ifndef SUBSURF_CHI2_H
#define SUBSURF_CHI2_H

#include "subsurf/rng.h"
#include "subsurf/vec3.h"

#include <stddef.h>
#include <stdint.h>

typedef struct {
  double statistic;
  int dof;
  double p_value;
  double pdf_integral; /* integral of the pdf over the binned domain */
  uint64_t invalid;    /* samples the sampler refused or that fell outside */
  char message[256];   /* why the test failed, or a summary */
} ss_chi2_result;

/* Draws a direction; returns 0 when the sampler has no sample for (u1,u2,u3). */
typedef int (*ss_chi2_sample_dir_fn)(void *ctx, double u1, double u2, double u3, ss_vec3 *dir);
/* Density of the sampler with respect to solid angle. */
typedef double (*ss_chi2_pdf_dir_fn)(void *ctx, ss_vec3 dir);

typedef struct {
  size_t theta_bins;  /* default 80 */
  size_t phi_bins;    /* default 160 */
  double theta_max;   /* pi for the sphere, pi/2 for the upper hemisphere */
  double theta_power; /* theta edges at theta_max (k/n)^power; > 1 resolves a peak at +z */
  uint64_t samples;   /* default 10^6 */
  uint64_t seed;
} ss_chi2_sphere_options;

void ss_chi2_sphere_options_default(ss_chi2_sphere_options *o);

/* Tests a direction sampler against its pdf over (theta, phi) bins. */
void ss_chi2_test_sphere(ss_chi2_sample_dir_fn sample, ss_chi2_pdf_dir_fn pdf, void *ctx,
                         const ss_chi2_sphere_options *opt, ss_chi2_result *res);

/* 1D: returns 0 to refuse; the sample must lie in [edges[0], edges[n]). */
typedef int (*ss_chi2_sample_1d_fn)(void *ctx, double u1, double u2, double *x);
typedef double (*ss_chi2_pdf_1d_fn)(void *ctx, double x);

/* Tests a 1D sampler against its pdf over the cells between `edges` (n + 1
 * increasing values). */
void ss_chi2_test_1d(ss_chi2_sample_1d_fn sample, ss_chi2_pdf_1d_fn pdf, void *ctx,
                     const double *edges, size_t n, uint64_t samples, uint64_t seed,
                     ss_chi2_result *res);

/* 2D over a rectangle: the sampler returns (x, y), the pdf is per unit x*y. */
typedef int (*ss_chi2_sample_2d_fn)(void *ctx, double u1, double u2, double u3, double *x,
                                    double *y);
typedef double (*ss_chi2_pdf_2d_fn)(void *ctx, double x, double y);

void ss_chi2_test_2d(ss_chi2_sample_2d_fn sample, ss_chi2_pdf_2d_fn pdf, void *ctx,
                     const double *x_edges, size_t nx, const double *y_edges, size_t ny,
                     uint64_t samples, uint64_t seed, ss_chi2_result *res);

/* Significance level for one of `tests` tests so that the family has level
 * alpha (Sidak correction). */
double ss_chi2_sidak_alpha(double alpha, int tests);

#endif
