/* Layered surfaces: the reflection and transmission of a slab or a stack of
 * slabs as a surface (a BRDF and a BTDF instead of a BSSRDF).
 *
 * Geometry: the stack lies below its top face, outward normal +z; the
 * outside has index 1 and every layer the index eta (the top face is a
 * smooth dielectric of ratio eta; 1: index matched). Layers are given by
 * their optical depth tau = sigma_t d, albedo and phase function. Below the
 * last layer: the same face as the top (the slab of `subsurf halfspace
 * --thickness`), nothing (open to a medium of the layers' index), or a
 * Lambertian base of albedo A.
 *
 * A collimated beam of irradiance E (normal to the beam) arrives at polar
 * angle theta_i travelling toward +x; outgoing directions theta_o lie in the
 * plane of incidence, positive on the side the beam travels toward (the
 * halfspace reference's convention). f = dL_o / (E cos theta_i dw_i) in 1/sr;
 * the totals are per unit incident power.
 *
 * ss_layer_adding solves the scattering and adding equations
 * (PharrHanrahan2000 sec. 3.3-3.4) by adding-doubling on Gauss-Legendre
 * nodes in cosine x Fourier modes in azimuth (Jakob2014);
 * ss_layer_first_order gives the single-scattering closed forms (Blinn1982,
 * HanrahanKrueger1993), ss_layer_mc a Monte Carlo random walk. docs/layer.md has the derivations
 * and the measured accuracy. */
#ifndef SUBSURF_LAYER_H
#define SUBSURF_LAYER_H

#include "subsurf/phase.h"
#include "subsurf/progress.h"
#include "subsurf/status.h"

#include <signal.h>
#include <stdint.h>

#define SS_LAYER_MAX_LAYERS 16
#define SS_LAYER_MAX_DIRECTIONS 64
#define SS_LAYER_MAX_TAU 1e6
#define SS_LAYER_MIN_TAU 1e-9
#define SS_LAYER_MAX_NODES 512
#define SS_LAYER_MAX_MODES 1024

typedef enum {
  SS_LAYER_BOTTOM_SAME,    /* the top's dielectric face again, the outside below */
  SS_LAYER_BOTTOM_MATCHED, /* no face: a medium of the layers' index below */
  SS_LAYER_BOTTOM_DIFFUSE, /* a Lambertian base of albedo bottom_albedo */
} ss_layer_bottom;

typedef struct {
  double tau;    /* optical depth, in [SS_LAYER_MIN_TAU, SS_LAYER_MAX_TAU] */
  double albedo; /* in [0, 1] */
  ss_phase phase;
} ss_layer_medium;

typedef struct {
  int n_layers; /* from the top */
  ss_layer_medium layers[SS_LAYER_MAX_LAYERS];
  double eta; /* n_layers / n_outside, [0.1, 10] */
  ss_layer_bottom bottom;
  double bottom_albedo;
  double theta_i; /* radians, [0, pi/2) */
  int n_theta_o;
  double theta_o[SS_LAYER_MAX_DIRECTIONS]; /* radians, (-pi/2, pi/2) */

  /* Discretisation (adding-doubling): Gauss-Legendre nodes per hemisphere
   * (0: chosen from the phase function) and azimuthal Fourier modes (0:
   * those whose phase coefficients at grazing exceed `accuracy` of the
   * zeroth), and the optical depth of the thin layer doubling starts from. */
  int nodes;
  int modes;
  double accuracy;
  double thin_tau;
  int threads; /* 0: OpenMP's default */

  /* The random walk (ss_layer_mc): paths, in [1, 1e15], and the seed;
   * results are identical for any thread count at a fixed seed. */
  uint64_t paths;
  uint64_t seed;

  /* Stops early when *cancel becomes non-zero (adding: SS_ERR_INTERRUPTED,
   * no result; the walk: the paths done, marked interrupted). `progress`
   * is called from one thread at a time with the work done and its total:
   * the Fourier modes solved, or the paths traced. */
  const volatile sig_atomic_t *cancel;
  ss_progress_fn progress;
  void *progress_ctx;
} ss_layer_params;

typedef struct {
  /* Per unit incident power. specular: reflected at the top face at entry;
   * reflectance_unscattered: the beam reflected back out by the bottom face
   * without scattering; reflectance and transmittance: scattered light
   * leaving through the top and the bottom; transmittance_unscattered: the
   * beam through the bottom unscattered. */
  double specular, reflectance, reflectance_unscattered;
  double transmittance, transmittance_unscattered, absorbed;
  double brdf[SS_LAYER_MAX_DIRECTIONS]; /* 1/sr, diffuse part (no specular delta) */
  double btdf[SS_LAYER_MAX_DIRECTIONS]; /* 1/sr; 0 with a diffuse base */
  /* The discretisation used. */
  int nodes, modes, outside_nodes, medium_nodes, doublings;
} ss_layer_result;

/* Defaults: one isotropic layer of tau 1 and albedo 0.9, eta 1, bottom
 * same, normal incidence, no theta_o, automatic nodes and modes with
 * accuracy 1e-4, thin_tau 2^-30, 10^6 paths, seed 0. */
void ss_layer_params_default(ss_layer_params *p);

/* Checks every parameter; the message names the offending one. */
ss_status ss_layer_validate(const ss_layer_params *p, ss_error *err);

/* The nodes and modes ss_layer_adding will use (after the automatic choice). */
void ss_layer_discretisation(const ss_layer_params *p, int *nodes, int *modes);

/* Bytes ss_layer_adding allocates at its peak, for a check before the run. */
double ss_layer_bytes(const ss_layer_params *p);

ss_status ss_layer_adding(const ss_layer_params *p, ss_layer_result *out, ss_error *err);

/* First-order light (one scattering event, in a layer or at the diffuse
 * base) with the specular bounces between the faces, in closed form. */
ss_status ss_layer_first_order(const ss_layer_params *p, ss_layer_result *out, ss_error *err);

/* The random walk's answer: each field of `value` with its standard error
 * in `error` (batch means; the specular reflection is exact). */
typedef struct {
  ss_layer_result value, error;
  uint64_t paths, scatter_events;
  double seconds;
  int interrupted; /* stopped by *cancel after `paths` paths */
} ss_layer_mc_result;

/* The 1D scattering equation (PharrHanrahan2000 eq. 3.4) by a random walk
 * in depth alone, which the layers' lateral invariance allows: free flights
 * in optical depth, phase sampling, Fresnel events at the faces, a
 * Lambertian base; f at the exact directions by next-event estimates at
 * every scattering event, through the specular bounces between the faces. */
ss_status ss_layer_mc(const ss_layer_params *p, ss_layer_mc_result *out, ss_error *err);

#endif
