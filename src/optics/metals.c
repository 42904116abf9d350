/* Named metals from measured optical constants, and their conversion to
 * RGB.
 *
 * Data: the measured points of JohnsonChristy1972 (Ag, Au, Cu),
 * JohnsonChristy1974 (Cr, Fe, Ni, Ti) and Rakic1995 (Al, evaporated films)
 * that cover 380-780 nm, wavelengths in micrometres as published.
 *
 * RGB: a conductor's colour is its reflectance, so the conversion keeps the
 * reflectance at normal incidence exact and fits the index to it. Per
 * channel c:
 *  1. R_c: the spectrum R(lambda) = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2)
 *     (BornWolf1999 sec. 14.2) under equal-energy light, integrated against
 *     the CIE 1931 matching functions (Wyman2013) from 380 to 780 nm in 1 nm
 *     steps, converted to linear sRGB and divided by the RGB of a perfect
 *     reflector (so R = 1 is white: a von Kries adaptation in RGB); a
 *     colour outside the gamut is scaled to a largest channel of 0.99
 *     (gold's red comes out at 1.006, the r-bar's negative lobe);
 *  2. eta_c: n averaged over the channel's sensitivity (the positive part of
 *     the sRGB matching function r-bar, g-bar or b-bar);
 *  3. k_c: the k that gives eta_c the reflectance R_c at normal incidence,
 *     k^2 = (R (eta + 1)^2 - (eta - 1)^2) / (1 - R) (0 when negative).
 * So a smooth metal seen head-on has the measured colour, and the
 * reflectance climbs to 1 at grazing angles as its Fresnel curve does; what
 * is approximate is the shape of the curve in between (one index for a
 * channel's band). */
#include "subsurf/metals.h"

#include "subsurf/cie.h"

#include <math.h>
#include <strings.h>

typedef struct {
  double lambda_um, n, k;
} point;

typedef struct {
  const char *name, *source;
  const point *points;
  size_t count;
} metal;

static const point ag[] = {
    {0.3679, 0.07, 1.657}, {0.3815, 0.05, 1.864}, {0.3974, 0.05, 2.070}, {0.4133, 0.05, 2.275},
    {0.4305, 0.04, 2.462}, {0.4509, 0.04, 2.657}, {0.4714, 0.05, 2.869}, {0.4959, 0.05, 3.093},
    {0.5209, 0.05, 3.324}, {0.5486, 0.06, 3.586}, {0.5821, 0.05, 3.858}, {0.6168, 0.06, 4.152},
    {0.6595, 0.05, 4.483}, {0.7045, 0.04, 4.838}, {0.7560, 0.03, 5.242}, {0.8211, 0.04, 5.727},
};
static const point al[] = {
    {0.36466, 0.39877, 4.3957}, {0.41328, 0.52135, 5.0008}, {0.44280, 0.60790, 5.3676},
    {0.47687, 0.72780, 5.7781}, {0.51660, 0.87340, 6.2418}, {0.56357, 1.0728, 6.7839},
    {0.61993, 1.3660, 7.4052},  {0.65225, 1.5724, 7.7354},  {0.68881, 1.8301, 8.0601},
    {0.72932, 2.1606, 8.3565},  {0.77491, 2.6154, 8.4914},  {0.79478, 2.7675, 8.3866},
};
static const point au[] = {
    {0.3679, 1.48, 1.895}, {0.3815, 1.46, 1.933}, {0.3974, 1.47, 1.952}, {0.4133, 1.46, 1.958},
    {0.4305, 1.45, 1.948}, {0.4509, 1.38, 1.914}, {0.4714, 1.31, 1.849}, {0.4959, 1.04, 1.833},
    {0.5209, 0.62, 2.081}, {0.5486, 0.43, 2.455}, {0.5821, 0.29, 2.863}, {0.6168, 0.21, 3.272},
    {0.6595, 0.14, 3.697}, {0.7045, 0.13, 4.103}, {0.7560, 0.14, 4.542}, {0.8211, 0.16, 5.083},
};
static const point cr[] = {
    {0.368, 1.87, 2.69}, {0.381, 1.92, 2.74}, {0.397, 2.00, 2.83}, {0.413, 2.08, 2.93},
    {0.431, 2.19, 3.04}, {0.451, 2.33, 3.14}, {0.471, 2.51, 3.24}, {0.496, 2.75, 3.30},
    {0.521, 2.94, 3.33}, {0.549, 3.18, 3.33}, {0.582, 3.22, 3.30}, {0.617, 3.17, 3.30},
    {0.659, 3.09, 3.34}, {0.704, 3.05, 3.39}, {0.756, 3.08, 3.42}, {0.821, 3.20, 3.48},
};
static const point cu[] = {
    {0.3679, 1.36, 1.975}, {0.3815, 1.33, 2.045}, {0.3974, 1.32, 2.116}, {0.4133, 1.28, 2.207},
    {0.4305, 1.25, 2.305}, {0.4509, 1.24, 2.397}, {0.4714, 1.25, 2.483}, {0.4959, 1.22, 2.564},
    {0.5209, 1.18, 2.608}, {0.5486, 1.02, 2.577}, {0.5821, 0.70, 2.704}, {0.6168, 0.30, 3.205},
    {0.6595, 0.22, 3.747}, {0.7045, 0.21, 4.205}, {0.7560, 0.24, 4.665}, {0.8211, 0.26, 5.180},
};
static const point fe[] = {
    {0.368, 2.02, 2.43}, {0.381, 2.12, 2.50}, {0.397, 2.24, 2.58}, {0.413, 2.35, 2.65},
    {0.431, 2.48, 2.71}, {0.451, 2.59, 2.77}, {0.471, 2.67, 2.82}, {0.496, 2.74, 2.88},
    {0.521, 2.86, 2.91}, {0.549, 2.95, 2.93}, {0.582, 2.94, 2.99}, {0.617, 2.88, 3.05},
    {0.659, 2.92, 3.10}, {0.704, 2.86, 3.19}, {0.756, 2.87, 3.28}, {0.821, 2.94, 3.39},
};
static const point ni[] = {
    {0.368, 1.70, 2.40}, {0.381, 1.72, 2.48}, {0.397, 1.72, 2.57}, {0.413, 1.70, 2.69},
    {0.431, 1.71, 2.82}, {0.451, 1.73, 2.95}, {0.471, 1.78, 3.09}, {0.496, 1.82, 3.25},
    {0.521, 1.85, 3.42}, {0.549, 1.92, 3.61}, {0.582, 1.96, 3.80}, {0.617, 1.99, 4.02},
    {0.659, 1.99, 4.26}, {0.704, 2.06, 4.50}, {0.756, 2.13, 4.73}, {0.821, 2.26, 4.97},
};
static const point ti[] = {
    {0.368, 1.90, 2.90}, {0.381, 1.99, 2.93}, {0.397, 2.08, 2.95}, {0.413, 2.14, 2.98},
    {0.431, 2.21, 3.01}, {0.451, 2.27, 3.04}, {0.471, 2.32, 3.10}, {0.496, 2.36, 3.19},
    {0.521, 2.44, 3.30}, {0.549, 2.54, 3.43}, {0.582, 2.60, 3.58}, {0.617, 2.67, 3.72},
    {0.659, 2.76, 3.84}, {0.704, 2.86, 3.96}, {0.756, 3.00, 4.01}, {0.821, 3.21, 4.01},
};

#define METAL(sym, src, pts)                                                                       \
  { sym, src, pts, sizeof pts / sizeof pts[0] }
static const metal metals[] = {
    METAL("Ag", "JohnsonChristy1972", ag), METAL("Al", "Rakic1995", al),
    METAL("Au", "JohnsonChristy1972", au), METAL("Cr", "JohnsonChristy1974", cr),
    METAL("Cu", "JohnsonChristy1972", cu), METAL("Fe", "JohnsonChristy1974", fe),
    METAL("Ni", "JohnsonChristy1974", ni), METAL("Ti", "JohnsonChristy1974", ti),
};
#define METAL_COUNT (sizeof metals / sizeof metals[0])

#define R_MAX 0.99
#define LAMBDA_MIN 380
#define LAMBDA_MAX 780

size_t ss_metal_count(void) { return METAL_COUNT; }
const char *ss_metal_name(size_t i) { return metals[i].name; }
const char *ss_metal_source(size_t i) { return metals[i].source; }
const char *ss_metal_names(void) { return "Ag, Al, Au, Cr, Cu, Fe, Ni, Ti"; }

int ss_metal_find(const char *name) {
  for (size_t i = 0; i < METAL_COUNT; ++i) {
    if (!strcasecmp(name, metals[i].name)) {
      return (int)i;
    }
  }
  return -1;
}

void ss_metal_index_at(size_t i, double lambda_nm, double *n, double *k) {
  const metal *m = &metals[i];
  double l = lambda_nm * 1e-3;
  size_t j = 1;
  while (j + 1 < m->count && m->points[j].lambda_um < l) {
    ++j;
  }
  const point *a = &m->points[j - 1], *b = &m->points[j];
  double t = (l - a->lambda_um) / (b->lambda_um - a->lambda_um);
  *n = a->n + t * (b->n - a->n);
  *k = a->k + t * (b->k - a->k);
}

/* BornWolf1999 sec. 14.2: reflectance at normal incidence. */
static double normal_reflectance(double n, double k) {
  return ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
}

/* Steps 1 and 2 of the conversion: the normal-incidence reflectance in RGB
 * (1 nm trapezoid sums) and the channels' sensitivity-weighted mean n. */
static void integrate(size_t i, ss_vec3 *reflectance, ss_vec3 *mean_n) {
  double rgb[3] = {0, 0, 0}, white[3] = {0, 0, 0}, wn[3] = {0, 0, 0}, w[3] = {0, 0, 0};
  for (int l = LAMBDA_MIN; l <= LAMBDA_MAX; ++l) {
    double weight = l == LAMBDA_MIN || l == LAMBDA_MAX ? 0.5 : 1.0, n, k;
    ss_metal_index_at(i, l, &n, &k);
    ss_vec3 c = ss_xyz_to_linear_srgb(ss_cie_xyz(l));
    const double cc[3] = {c.x, c.y, c.z};
    double r = normal_reflectance(n, k);
    for (int ch = 0; ch < 3; ++ch) {
      rgb[ch] += weight * cc[ch] * r;
      white[ch] += weight * cc[ch];
      double s = fmax(cc[ch], 0.0);
      wn[ch] += weight * s * n;
      w[ch] += weight * s;
    }
  }
  /* Gold's red lies outside the sRGB gamut (above 1): colours are scaled
   * to at most R_MAX, negative channels clipped. */
  double r[3], top = 0.0;
  for (int ch = 0; ch < 3; ++ch) {
    r[ch] = fmax(rgb[ch] / white[ch], 0.0);
    top = fmax(top, r[ch]);
  }
  double scale = top > R_MAX ? R_MAX / top : 1.0;
  *reflectance = ss_vec3_make(scale * r[0], scale * r[1], scale * r[2]);
  *mean_n = ss_vec3_make(wn[0] / w[0], wn[1] / w[1], wn[2] / w[2]);
}

ss_vec3 ss_metal_reflectance(size_t i) {
  ss_vec3 r, n;
  integrate(i, &r, &n);
  return r;
}

void ss_metal_rgb(size_t i, ss_vec3 *eta, ss_vec3 *k) {
  ss_vec3 r, n;
  integrate(i, &r, &n);
  const double rr[3] = {r.x, r.y, r.z}, nn[3] = {n.x, n.y, n.z};
  double kk[3];
  for (int ch = 0; ch < 3; ++ch) {
    double rc = rr[ch];
    double k2 =
        (rc * (nn[ch] + 1.0) * (nn[ch] + 1.0) - (nn[ch] - 1.0) * (nn[ch] - 1.0)) / (1.0 - rc);
    kk[ch] = sqrt(fmax(k2, 0.0));
  }
  *eta = n;
  *k = ss_vec3_make(kk[0], kk[1], kk[2]);
}
