/* The BSSRDFs of a committed scene (issue 9).
 *
 * ss_scene_commit creates one ss_bssrdf for every translucent material that
 * names a model, from its medium (sigma_s, sigma_a, the phase function's g,
 * per channel) and its boundary eta. Materials whose model and parameters
 * are identical share one BSSRDF, so a table model builds its table once per
 * distinct (model, eta, g, options) that the scene uses. The handles are
 * read-only once built and safe to share between threads. */
#ifndef SUBSURF_SUBSURFACE_H
#define SUBSURF_SUBSURFACE_H

#include "subsurf/bssrdf.h"
#include "subsurf/status.h"

#include <stddef.h>

struct ss_scene;
typedef struct ss_subsurface ss_subsurface;

/* Builds the BSSRDFs of the scene's translucent materials; the message
 * names the material. The scene's media must be initialised. */
ss_status ss_subsurface_create(const struct ss_scene *scene, ss_subsurface **out, ss_error *err);
void ss_subsurface_destroy(ss_subsurface *s);

/* The BSSRDF of material `material`, or NULL when it has none. */
const ss_bssrdf *ss_subsurface_bssrdf(const ss_subsurface *s, int material);
/* Number of distinct BSSRDFs built (the size of the cache). */
size_t ss_subsurface_count(const ss_subsurface *s);

/* The parameters a material's BSSRDF is created from: its medium's
 * coefficients and phase-function g, its boundary eta. */
void ss_subsurface_params(const struct ss_scene *scene, int material, ss_bssrdf_params *p);

#endif
