/* A homogeneous medium's optical coefficients, one description shared by the
 * scene's media (material.h), the BSSRDF models (bssrdf.h) and the half-space
 * reference (halfspace.h); the measured presets of media.h convert into it.
 *
 * The boundary's relative index eta = n_inside / n_outside is not part of a
 * medium: the same medium can sit behind interfaces of different index (an
 * index-matched variant of a scene, a slab in water), so eta stays with the
 * interface (ss_material.eta, ss_bssrdf_params.eta, ss_halfspace_params.eta).
 * A preset's measured eta is read from the preset (media.h). */
#ifndef SUBSURF_MEDIUM_OPTICS_H
#define SUBSURF_MEDIUM_OPTICS_H

#include "subsurf/media.h"
#include "subsurf/microflake.h"
#include "subsurf/phase.h"
#include "subsurf/rgb.h"
#include "subsurf/status.h"

typedef struct {
  ss_rgb sigma_s;      /* scattering coefficient (unreduced), per unit length */
  ss_rgb sigma_a;      /* absorption coefficient, per unit length */
  ss_rgb g;            /* phase function mean cosine per channel */
  ss_phase_type phase; /* the phase function's family */
  /* Micro-flakes (microflake.h): with a flake type, the phase function and g
   * above are replaced by the flakes' specular scattering and extinction
   * depends on the direction of travel. type SS_FLAKE_NONE: no flakes. */
  ss_medium_flakes flakes;
} ss_medium_optics;

/* The same coefficients in all three channels (no flakes). */
ss_medium_optics ss_medium_optics_gray(double sigma_s, double sigma_a, double g,
                                       ss_phase_type phase);

/* A preset scaled by `scale` for phase mean cosine g: the preset gives the
 * reduced scattering sigma_s', and sigma_s = sigma_s' scale / (1 - g) keeps
 * it (similarity relation; g = 0: sigma_s = sigma_s'). */
ss_medium_optics ss_medium_optics_from_preset(const ss_medium_preset *preset, double scale,
                                              double g, ss_phase_type phase);

/* Checks every channel: sigma_s, sigma_a finite and >= 0, sigma_t > 0, the
 * reduced extinction (1 - g) sigma_s + sigma_a > 0, and g valid for the phase
 * family (ss_phase_init). The message names the field and the channel
 * ("sigma_a[G] must be finite and >= 0, got -1"); callers prefix their
 * context. */
ss_status ss_medium_optics_check(const ss_medium_optics *m, ss_error *err);

#endif
