/* The plane-parallel Monte Carlo reference (docs/halfspace.md): a collimated
 * unit-power beam enters a homogeneous half-space z < 0 (or a slab -d < z < 0) at the
 * origin, with polar angle theta_i, travelling toward +x: its propagation
 * direction outside is (sin theta_i, 0, -cos theta_i). The boundary is a
 * smooth dielectric with eta = n_inside / n_outside (1: index matched); the
 * medium outside both faces of a slab has the same index.
 *
 * Light is traced with exact free-flight and phase sampling, Fresnel
 * reflection or refraction at every boundary crossing, absorption by weight
 * and unbiased Russian roulette. Results are per unit incident power, each
 * with its standard error (batch means over fixed batches of paths, so they
 * are bit-identical for any number of threads at a fixed seed). */
#ifndef SUBSURF_HALFSPACE_H
#define SUBSURF_HALFSPACE_H

#include "subsurf/arg.h"
#include "subsurf/medium_optics.h"
#include "subsurf/progress.h"
#include "subsurf/status.h"

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#define SS_HALFSPACE_MAX_DIRECTIONS 16
/* The ranges ss_halfspace_validate accepts (docs/halfspace.md, "Limits"):
 * beyond them Fresnel terms round to exactly 0 or 1, Russian roulette loses
 * its threshold and the models' distances overflow. Lengths (thickness, bin
 * ranges, profile radii) are in the unit of 1/sigma. */
#define SS_HALFSPACE_ETA_MIN 0.1
#define SS_HALFSPACE_ETA_MAX 10.0
#define SS_HALFSPACE_MAX_COEFF 1e6
#define SS_HALFSPACE_MIN_SIGMA_T 1e-6
#define SS_HALFSPACE_MAX_LENGTH 1e6
/* Bins of each axis (radial, x, y). */
#define SS_HALFSPACE_MAX_BINS 100000

/* A batch's per-bin sums (nbins doubles) for runs split across processes:
 * the source fills them for a batch traced elsewhere and returns its paths
 * (adding its scattering events to *events); the sink receives them. */
typedef uint64_t (*ss_halfspace_batch_source_fn)(void *ctx, int64_t batch, double *sums,
                                                 size_t nbins, uint64_t *events);
typedef void (*ss_halfspace_batch_sink_fn)(void *ctx, int64_t batch, const double *sums,
                                           size_t nbins, uint64_t paths, uint64_t events);

typedef struct {
  ss_medium_optics medium; /* per unit length; the run traces one channel of it */
  int channel;             /* 0, 1, 2: which channel's sigma_s, sigma_a and g */
  double eta;
  double theta_i;   /* radians, [0, pi/2) */
  double thickness; /* INFINITY for a half-space */
  /* The medium's lateral extent: |x|, |y| < width / 2 (with a finite
   * thickness, a box; light leaving through the sides counts as
   * transmitted). INFINITY: unbounded. Needs n_theta_o = 0. */
  double width;
  /* 0: the collimated beam at the origin. > 0: a diffuse spot instead, unit
   * power of Lambertian irradiance spread uniformly over the disc of this
   * radius about the origin (each path enters at a uniform point of it, from
   * a cosine-distributed direction, Fresnel-weighted and refracted); needs
   * theta_i = 0. Jakob et al. 2010's validation of the finite elements. */
  double spot_radius;

  uint64_t paths;
  double time_limit; /* seconds; 0: none */
  uint64_t seed;
  int threads;        /* 0: OpenMP's default */
  uint64_t max_depth; /* paths scatter at most this often (1: first-order light);
                         one that would scatter again is cut and its power
                         reported as "truncated"; matters only for albedo ~ 1 */

  /* Radial exitance: bin 0 is [0, rmin), then rbins - 1 log-spaced bins up to rmax. */
  double rmin, rmax;
  int rbins;
  /* Exitant radiance for exact outgoing directions (radians in the x-z plane,
   * positive toward +x), integrated over y and averaged over x bins. */
  int n_theta_o;
  double theta_o[SS_HALFSPACE_MAX_DIRECTIONS];
  double xmin, xmax;
  int xbins;
  /* Exitance map over [xmin, xmax] x [ymin, ymax] (computed when want_map). */
  double ymin, ymax;
  int ybins;
  int want_map;

  /* Stops early (partial result) when *cancel becomes non-zero. */
  const volatile sig_atomic_t *cancel;
  /* Called from one thread at a time with the number of paths finished. */
  ss_progress_fn progress;
  void *progress_ctx;

  /* Runs split across processes (the CLI's MPI job; the library knows no
   * MPI). With batch_stride > 1 only the batches b with b % batch_stride ==
   * batch_offset are traced here; the sums of any other batch come from
   * batch_source, which returns its paths (NULL: the batch is skipped).
   * Merged in batch order as ever, so a run whose source supplies every
   * other batch's sums is bit-identical to one process's. batch_sink, when
   * set, sees each batch traced here (also one cut short). Both are called
   * concurrently from the worker threads, in no set order. */
  int batch_stride, batch_offset;
  ss_halfspace_batch_source_fn batch_source;
  ss_halfspace_batch_sink_fn batch_sink;
  void *batch_ctx;
} ss_halfspace_params;

/* The grammar of the numbers of ss_halfspace_params as the command line
 * (`subsurf halfspace --NAME`) and the flat interface take them: sigma-s,
 * sigma-a, g, eta, theta-i (degrees on the command line), thickness, paths,
 * time-limit, seed, threads, max-depth, rmin, rmax, rbins, theta-o, xmin,
 * xmax, xbins, ymin, ymax, ybins; ended by {NULL}. */
extern const ss_arg ss_halfspace_args[];

typedef struct {
  double value, error; /* error: one standard error */
} ss_estimate;

typedef struct {
  uint64_t paths;
  uint64_t scatter_events;
  double seconds;
  int partial;     /* stopped by the time limit or by *cancel */
  int interrupted; /* stopped by *cancel */

  ss_estimate reflectance;   /* diffuse: entered, then left through the top */
  ss_estimate transmittance; /* left through the bottom of a slab or the sides */
  ss_estimate specular;      /* reflected at entry (exact, error 0, for the beam) */
  ss_estimate absorbed;
  ss_estimate truncated; /* cut by max_depth */

  int rbins;
  double *r_lo, *r_hi;
  ss_estimate *radial; /* exitance per unit area, annulus average */

  int xbins;
  double *x_lo, *x_hi;
  int n_theta_o;
  double theta_o[SS_HALFSPACE_MAX_DIRECTIONS];
  ss_estimate *directions; /* [n_theta_o][xbins]: int L dy averaged over the x bin */

  int ybins;
  double *y_lo, *y_hi;
  ss_estimate *map; /* [ybins][xbins] exitance per unit area, or NULL */
} ss_halfspace_result;

/* Defaults: gray isotropic medium sigma_s 1, sigma_a 0.01, channel 0, eta 1,
 * normal incidence of the beam (spot_radius 0),
 * half-space (thickness and width infinite), 10^6 paths, rmin 0.01, rmax 10, 64 radial bins, x and
 * y in
 * [-5, 5] with 100 bins, max_depth 10^6. */
void ss_halfspace_params_default(ss_halfspace_params *p);

/* Checks every parameter; the message names the offending one. */
ss_status ss_halfspace_validate(const ss_halfspace_params *p, ss_error *err);

/* Bytes ss_halfspace_run(p) allocates at its peak (tallies of every bin per
 * thread, the merged tally and the result), for a check before the run. */
double ss_halfspace_bytes(const ss_halfspace_params *p);

ss_status ss_halfspace_run(const ss_halfspace_params *p, ss_halfspace_result **out, ss_error *err);
/* An empty result with the bins of `p` laid out (edges filled, values 0):
 * what ss_halfspace_run fills, and what a model fills to answer the same
 * questions. */
ss_status ss_halfspace_result_create(const ss_halfspace_params *p, ss_halfspace_result **out,
                                     ss_error *err);
void ss_halfspace_result_destroy(ss_halfspace_result *r);

#endif
