/* Photon beam diffusion (Habel2013) as written in the
 * appendix of Ferrier2016: the multiple-scattering
 * exitance of a refracted beam for any incidence angle and exit azimuth, the
 * single-scattering exitance at normal incidence (as pbrt-v3's
 * BeamDiffusionSS), and the effective albedo.
 *
 * Units: the functions return exitance per unit area per unit power carried
 * by the refracted beam (Fresnel transmission into the medium is not
 * included). theta is the incidence angle outside the medium; phi is the exit
 * point's azimuth measured from the beam's forward horizontal direction (the
 * incidence plane), so phi = 0 lies where the refracted beam heads.
 *
 * Integration along the beam: Gauss-Legendre in the variable s of
 * t = t* + h sinh(s), where t* is the beam depth closest to the exit point and
 * h that closest distance. The sinh map resolves the near-singular peak of the
 * dipole kernels at any radius, so a few dozen nodes converge to ~1e-7 where
 * pbrt-v3's 100 stratified exponential samples err by percent at r << 1/sigma_t'. */
#ifndef SUBSURF_PBD_H
#define SUBSURF_PBD_H

#include "subsurf/phase.h"
#include "subsurf/status.h"

#define SS_PBD_MAX_NODES 128

typedef struct {
  double sigma_s, sigma_a, g, eta;
  double sigma_t, rho;     /* unreduced extinction and albedo (single scattering) */
  double sigma_t_p, rho_p; /* reduced sigma_t' and alpha' (diffusion) */
  double D_g, sigma_tr;    /* Grosjean diffusion coefficient, sqrt(sigma_a / D_g) */
  double z_b;              /* extrapolation distance 2 D_G (1 + 3 C2)/(1 - 2 C1) */
  double c1, c2;           /* Fresnel moments of the boundary seen from inside */
  double c_phi, c_e;       /* exitance weights (1 - 2 C1)/4, (1 - 3 C2)/2 */
  ss_phase phase;          /* Henyey-Greenstein with g, for single scattering */
  int nodes;               /* Gauss-Legendre nodes per integration piece */
  double gl_x[SS_PBD_MAX_NODES], gl_w[SS_PBD_MAX_NODES]; /* rule on [0, 1] */
} ss_pbd;

/* Validates (sigma_s, sigma_a >= 0 finite, sigma_t > 0, |g| < 1, eta > 0,
 * 2 <= nodes <= SS_PBD_MAX_NODES) and precomputes the constants. */
ss_status ss_pbd_init(ss_pbd *p, double sigma_s, double sigma_a, double g, double eta, int nodes,
                      ss_error *err);

/* Changes sigma_s and sigma_a of an initialised model, keeping eta, g, the
 * Fresnel moments and the quadrature rule (no GSL call: safe in threads).
 * The caller guarantees sigma_s, sigma_a >= 0 with a positive sum. */
void ss_pbd_set_albedo(ss_pbd *p, double sigma_s, double sigma_a);

/* Refraction of the beam, precomputed once per incidence angle. */
typedef struct {
  double sin_t, cos_t; /* refracted angle theta' inside the medium */
} ss_pbd_beam;

ss_pbd_beam ss_pbd_beam_make(const ss_pbd *p, double theta);

/* S_p^MS(r, phi; theta): Ferrier2016 eq. of sec. 2.1, appendix table 4. */
double ss_pbd_ms(const ss_pbd *p, const ss_pbd_beam *beam, double r, double phi);

/* The point source S_p^MS integrates along the beam: the exitance (R_phi^d
 * + R_E^d) kappa at lateral distance r from an isotropic source at depth z
 * per unit power scattered there (Ferrier2016, table 4), so that
 * S_p^MS(r, 0; 0) = int_0^inf rho' sigma_t' e^{-sigma_t' z} M(z, r) dz. */
double ss_pbd_point_source(const ss_pbd *p, double z, double r);

/* Single-scattering exitance at normal incidence (pbrt-v3 BeamDiffusionSS
 * integrated exactly rather than with 100 samples). */
double ss_pbd_ss(const ss_pbd *p, double r);

/* rho_eff = int_0^inf 2 pi r (E_ms + E_ss) dr at normal incidence. */
double ss_pbd_effective_albedo(const ss_pbd *p);

/* int int S_p^MS(r, phi; theta) r dr dphi: the diffuse albedo of the
 * multiple-scattering term for one incidence angle. */
double ss_pbd_ms_albedo(const ss_pbd *p, double theta);

/* E(r) = r int_{-pi}^{pi} S_p^MS(r, phi; theta) dphi: the radial energy that
 * Ferrier's table stores (trapezoid rule in phi, exact for the smooth
 * periodic integrand to ~1e-9 with 64 points). */
double ss_pbd_ms_radial(const ss_pbd *p, const ss_pbd_beam *beam, double r);

#endif
