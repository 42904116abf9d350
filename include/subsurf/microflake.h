/* Micro-flake media (Jakob2010 sec. 4):
 * a medium of tiny mirror flakes whose normals follow a
 * distribution D(m) on the sphere. Scattering and extinction depend on the
 * direction of travel w:
 *   sigma_t(w) = a rho sigma(w),   sigma(w) = int |w.m| D(m) dm,
 *   sigma_s(w) = a rho int alpha(|w.m|) |w.m| D(m) dm,
 *   f_p(w' -> w) = a rho alpha(|w'.h|) [D(h) + D(-h)] / (4 sigma_s(w')),
 * h = (w - w') / |w - w'|, with w' and w propagation directions.
 * a rho (flake area times density) is the medium's density; this module
 * works per unit density: ss_microflake_sigma_t(w) is sigma(w), so that
 * sigma_t(w) = density * sigma(w).
 *
 * The distributions are axially symmetric about a unit axis v, so sigma(w)
 * and sigma_s(w) depend only on |w.v| and are tabulated in 1D at init (the
 * paper's general route is a spherical-harmonics expansion). */
#ifndef SUBSURF_MICROFLAKE_H
#define SUBSURF_MICROFLAKE_H

#include "subsurf/rng.h"
#include "subsurf/status.h"
#include "subsurf/table_index.h"
#include "subsurf/vec3.h"

typedef enum {
  SS_FLAKE_NONE,    /* not a micro-flake medium (ss_medium_flakes) */
  SS_FLAKE_UNIFORM, /* D = 1/(4 pi): the isotropic medium (Jakob2010 eq. 14-15) */
  SS_FLAKE_SURFACE, /* D ~ |cos(v, m)|^p: flakes facing the axis (layered media) */
  SS_FLAKE_FIBER,   /* D ~ |sin(v, m)|^p: normals around the axis (fibres along v) */
} ss_flake_type;

/* The flake albedo alpha(|w.m|) = alpha0 + (alpha1 - alpha0) |w.m|^k: constant
 * with alpha0 = alpha1, otherwise a function of the incidence on the flake. */
typedef struct {
  double alpha0, alpha1, k;
} ss_flake_albedo;

/* sigma(w) and sigma_s(w) are tabulated over x = 1 - |w.v| at the ends of
 * equal cells: a fine table over x in [0, SS_MICROFLAKE_FINE_X] (near the
 * axis, where fibre-like flakes of large p change sigma on a scale x ~ 1/(2p))
 * followed by a coarse one over [0, 1]; the lookup needs no square root. */
#define SS_MICROFLAKE_FINE 1024   /* cells of the fine table */
#define SS_MICROFLAKE_COARSE 2048 /* cells of the coarse table */
#define SS_MICROFLAKE_FINE_X 0.0625
#define SS_MICROFLAKE_TABLE (SS_MICROFLAKE_FINE + SS_MICROFLAKE_COARSE + 2) /* entries */
#define SS_MICROFLAKE_MEAN 256     /* cells of the table of g(w) over theta (below) */
#define SS_MICROFLAKE_ENVELOPE 256 /* cells of the rejection envelopes over |m.v| */

/* A piecewise-constant upper bound of a log-concave function f over equal
 * cells of [0, 1], drawn by Walker's alias method (a column, then the
 * column's cell or its alias; no search) and thinned by rejection, with a
 * piecewise-linear lower squeeze that spares most evaluations of f;
 * integral is f's exact integral over [0, 1]. */
typedef struct {
  double bound[SS_MICROFLAKE_ENVELOPE];
  /* The squeeze at the position t in [0, 1) across cell k:
   * squeeze[k] + t squeeze_slope[k] <= f. */
  double squeeze[SS_MICROFLAKE_ENVELOPE];
  double squeeze_slope[SS_MICROFLAKE_ENVELOPE];
  /* Column j keeps cell j with probability keep[j], else gives cell
   * alias[j]; inv_keep and inv_rest rescale the uniform that decided it to
   * the position in the cell. */
  double keep[SS_MICROFLAKE_ENVELOPE];
  double inv_keep[SS_MICROFLAKE_ENVELOPE];
  double inv_rest[SS_MICROFLAKE_ENVELOPE];
  int alias[SS_MICROFLAKE_ENVELOPE];
  double integral;
} ss_flake_envelope;

typedef struct {
  ss_flake_type type;
  double p;       /* exponent of the surface- or fibre-like distribution */
  ss_frame frame; /* the axis v as the frame's normal */
  double norm;    /* D(m) = norm |cos|^p or norm |sin|^p over the sphere */
  ss_flake_albedo albedo;
  double sigma_t[SS_MICROFLAKE_TABLE]; /* sigma(w): fine, then coarse table */
  double sigma_s[SS_MICROFLAKE_TABLE]; /* int alpha |w.m| D(m) dm, likewise */
  /* Visible normals are drawn from the envelope D(m) (s r |cos psi| + c |u|)
   * of |w.m| D(m) (u = m.v, r = sqrt(1 - u^2), psi the azimuth about the
   * axis from w's, c and s the cosine and sine of w to the axis): a mixture
   * of |u| D and r D over |u|, each from its own piecewise-constant bound. */
  ss_flake_envelope along;  /* |u| D(u) over |u| in [0, 1] */
  ss_flake_envelope across; /* sqrt(1 - u^2) D(u) over |u| in [0, 1] */
  /* g(w) (ss_microflake_scattered_mean) once tabulated: by the axial
   * symmetry and the mirror symmetry u -> -u of D, g lies in the plane of w
   * and v and is g = sgn(c) mean_along(|c|) v + mean_across(|c|) (w - c v),
   * c = w.v; mean_along is g.v at c >= 0, mean_across is g's component
   * across the axis divided by sin(theta) = sqrt(1 - c^2) (smooth in theta
   * up to the axis, where the component itself goes as sin(theta)). At the
   * ends of SS_MICROFLAKE_MEAN equal cells of theta = acos(|c|) in
   * [0, pi/2] (equal in angle: fibre-like flakes of p = 1000 change g within
   * theta ~ 0.03 of the axis); filled by
   * ss_microflake_tabulate_scattered_mean. */
  int mean_tabulated;
  double mean_along[SS_MICROFLAKE_MEAN + 1];
  double mean_across[SS_MICROFLAKE_MEAN + 1];
} ss_microflake;

/* Validates the distribution (p in [0, 1000] for the surface and fibre types,
 * a non-zero finite axis, alpha0 and alpha1 in [0, 1], k in [0, 100]) and builds the
 * tables. The axis need not be unit length. */
ss_status ss_microflake_init(ss_microflake *mf, ss_flake_type type, double p, ss_vec3 axis,
                             ss_flake_albedo albedo, ss_error *err);

/* The normalised flake distribution D(m) for a unit m. */
double ss_microflake_D(const ss_microflake *mf, ss_vec3 m);

/* The flake albedo at incidence cosine |w.m|. */
double ss_microflake_albedo(const ss_microflake *mf, double cos_wm);

/* Projected flake area sigma(w) = int |w.m| D(m) dm (per unit density) and
 * the scattering part int alpha(|w.m|) |w.m| D(m) dm, from the tables. */
double ss_microflake_sigma_t(const ss_microflake *mf, ss_vec3 w);
double ss_microflake_sigma_s(const ss_microflake *mf, ss_vec3 w);

/* A table (ss_microflake.sigma_t or sigma_s) at c = w.v, |c| <= 1: linear
 * interpolation in x = 1 - |c| (inline: the walks look it up every event). */
static inline double ss_microflake_table_at(const double *table, double c) {
  double x = 1.0 - (c < 0.0 ? -c : c);
  x = x > 0.0 ? x : 0.0; /* |c| a rounding above 1 */
  int fine = x < SS_MICROFLAKE_FINE_X;
  double xi = x * (fine ? SS_MICROFLAKE_FINE / SS_MICROFLAKE_FINE_X : SS_MICROFLAKE_COARSE);
  /* x = 1 (c = 0) is the coarse table's last entry: its last cell at t = 1. */
  int i = ss_table_cell_clamped(xi, fine ? SS_MICROFLAKE_FINE : SS_MICROFLAKE_COARSE);
  double t = xi - i;
  const double *cell = table + (fine ? 0 : SS_MICROFLAKE_FINE + 1) + i;
  return cell[0] + t * (cell[1] - cell[0]);
}

/* The largest sigma(w) over all directions: the tables are piecewise linear,
 * so their largest entry (a delta-tracking majorant's direction factor). */
double ss_microflake_sigma_max(const ss_microflake *mf);

/* The probability of surviving a collision while travelling along w,
 * sigma_s(w) / sigma(w): the albedo itself when it is constant. */
double ss_microflake_collision_albedo(const ss_microflake *mf, ss_vec3 w);

/* 1 when alpha(|w.m|) is the constant alpha1. */
static inline int ss_flake_albedo_is_constant(const ss_flake_albedo *a) {
  return a->alpha0 == a->alpha1 || a->k == 0.0;
}

/* The collision albedo at c = w.v (inline: the walks take it every event). */
static inline double ss_microflake_collision_albedo_at(const ss_microflake *mf, double c) {
  if (ss_flake_albedo_is_constant(&mf->albedo)) {
    return mf->albedo.alpha1;
  }
  return ss_microflake_table_at(mf->sigma_s, c) / ss_microflake_table_at(mf->sigma_t, c);
}

/* The same integrals by adaptive-free Gauss-Legendre quadrature at a cosine
 * c = |w.v| (what the tables are built from and tested against). */
double ss_microflake_sigma_t_quadrature(const ss_microflake *mf, double c);
double ss_microflake_sigma_s_quadrature(const ss_microflake *mf, double c);

/* The mean direction g(w) of once-scattered light travelling along the unit
 * w: int w_out f_p(w -> w_out) dw_out = w - 2 int alpha (w.m) |w.m| m D dm /
 * int alpha |w.m| D dm (each visible flake m reflects w into w - 2 (w.m) m),
 * by the quadrature above, the azimuth in closed form for a constant albedo.
 * 0 for uniform flakes (an isotropic phase function) and when nothing
 * scatters. */
ss_vec3 ss_microflake_scattered_mean(const ss_microflake *mf, ss_vec3 w);

/* Tabulates g(w) (mean_along, mean_across above) by that quadrature at
 * SS_MICROFLAKE_MEAN + 1 angles: worth it for more than a few hundred
 * directions (the fem integrator's lit faces and rays, per channel). */
void ss_microflake_tabulate_scattered_mean(ss_microflake *mf);

/* g(w) from the table, interpolated linearly in theta (|g| error below 2e-4
 * for p <= 1000: tests/optics/test_microflake.c), or by
 * the quadrature when the table has not been built. */
ss_vec3 ss_microflake_scattered_mean_lookup(const ss_microflake *mf, ss_vec3 w);

/* The phase function f_p(w_in -> w_out) for propagation directions, per unit
 * solid angle of w_out (normalised over the sphere). */
double ss_microflake_phase_eval(const ss_microflake *mf, ss_vec3 w_in, ss_vec3 w_out);

/* Draws a flake normal visible from w, with density |w.m| D(m) / sigma(w)
 * over the sphere (rejection from a mixture envelope: exact for any p, about
 * 1.3 draws per normal). */
ss_vec3 ss_microflake_sample_visible_normal(const ss_microflake *mf, ss_vec3 w, ss_rng *rng);

/* A scattering event: a new propagation direction with density exactly
 * ss_microflake_phase_eval(w_in, .): a visible flake reflects w_in, thinned
 * by alpha(|w_in.m|) / max(alpha) when the albedo varies. The walk weights the
 * event by sigma_s(w_in) / sigma_t(w_in). Needs a non-zero albedo. */
ss_vec3 ss_microflake_sample_phase(const ss_microflake *mf, ss_vec3 w_in, ss_rng *rng);
/* The same in the axis frame, inline for the walks: ss_microflake_sample_phase_local
 * in src/optics/microflake_sample.h. */

/* How a medium's flakes are described next to its coefficients
 * (medium_optics.h). type SS_FLAKE_NONE (a zeroed struct) is an ordinary
 * medium. With flakes, the medium's sigma_s and sigma_a are those of the
 * isotropic medium that uniformly oriented flakes of the same density would
 * form: a rho = 2 (sigma_s + sigma_a), so sigma_t(w) = 2 (sigma_s + sigma_a)
 * sigma(w), and the flake albedo at normal incidence is alpha1 =
 * sigma_s / (sigma_s + sigma_a). The albedo is constant unless
 * albedo_falloff f > 0: alpha(c) = alpha1 (1 - f + f c^k), k the
 * albedo_exponent, so that it drops to alpha1 (1 - f) at grazing incidence. */
typedef struct {
  ss_flake_type type;
  double p;
  ss_vec3 axis;
  double albedo_falloff;
  double albedo_exponent;
} ss_medium_flakes;

/* Checks the description (any type; SS_FLAKE_NONE is valid). */
ss_status ss_medium_flakes_check(const ss_medium_flakes *flakes, ss_error *err);

/* The flakes of a medium with single-scattering albedo sigma_s / sigma_t. */
ss_status ss_microflake_init_medium(ss_microflake *mf, const ss_medium_flakes *flakes,
                                    double albedo, ss_error *err);

/* Parses "uniform", "surface", "fiber"; returns 0 on an unknown name. */
int ss_flake_type_from_name(const char *name, ss_flake_type *type);
const char *ss_flake_type_name(ss_flake_type type);

#endif
