/* The BSSRDFs of a committed scene.
 *
 * ss_scene_commit creates (for micro-flake and gridded media: plans, see
 * ss_subsurface_build) one ss_bssrdf for every translucent material that
 * names a model, from its medium (sigma_s, sigma_a, the phase function's g,
 * per channel) and its boundary eta. Materials whose model and parameters
 * are identical share one BSSRDF, and the tabulated models take their tables
 * from one ss_table_cache (table_cache.h), so a table is built once per
 * distinct (model, eta, g, options) that the scene uses, whatever the
 * materials' coefficients, and read from the disk cache when the scene's
 * render settings keep one (scene.h). The handles are read-only once built
 * and safe to share between threads. */
#ifndef SUBSURF_SUBSURFACE_H
#define SUBSURF_SUBSURFACE_H

#include "subsurf/bssrdf.h"
#include "subsurf/material.h"
#include "subsurf/status.h"
#include "subsurf/table_cache.h"

#include <stddef.h>

/* Level of detail. A translucent material's "lod" (material.h)
 * picks what stands for its medium: its BSSRDF model, the effective BRDF, or
 * a volumetric random walk inside (volpath's). "auto" decides per material
 * from n = L / l, L the smallest bounding-box extent of the shapes that use
 * it and l = 1 / min_c sigma_t'_c the transport mean free path of its most
 * translucent channel: volpath below SS_LOD_VOLPATH_BELOW, the BRDF above
 * SS_LOD_BRDF_ABOVE, the BSSRDF in between (thresholds measured in
 * docs/results.md). A material with no model uses SS_LOD_DEFAULT_MODEL. */
#define SS_LOD_VOLPATH_BELOW 30.0
#define SS_LOD_BRDF_ABOVE 1000.0
#define SS_LOD_DEFAULT_MODEL "pbd"
/* The effective BRDF: a model flagged SS_BSSRDF_BRDF (the forward
 * scattering dipole's BRDF can take its place here once it exists). */
#define SS_LOD_BRDF_MODEL "dipole-brdf"
/* The model of a translucent material whose medium has micro-flakes or a
 * grid (volume.h) and names none: the anisotropic dipole, which takes the
 * medium's flakes. Such materials are never at the BRDF level. */
#define SS_VOLUME_MODEL "aniso-dipole"

struct ss_scene;
typedef struct ss_subsurface ss_subsurface;

/* Builds the BSSRDFs of the scene's translucent materials (those of volume
 * media only when ss_subsurface_build is called); the message names the
 * material. The scene's media must be initialised. */
ss_status ss_subsurface_create(const struct ss_scene *scene, ss_subsurface **out, ss_error *err);
void ss_subsurface_destroy(ss_subsurface *s);

/* The level of detail chosen for material `material` (never SS_LOD_AUTO
 * for a translucent material; SS_LOD_BSSRDF for any other). */
ss_lod ss_subsurface_lod(const ss_subsurface *s, int material);
/* n = L / l above (0 for a material no shape uses). */
double ss_subsurface_size_ratio(const struct ss_scene *scene, int material);

/* The BSSRDF of material `material`, or NULL when it has none or it is
 * not built yet. */
const ss_bssrdf *ss_subsurface_bssrdf(const ss_subsurface *s, int material);
/* The models of micro-flake and gridded media (volume.h; the anisotropic
 * dipole's flake tables take tens of ms) are checked by
 * ss_subsurface_create but built only here: an integrator that uses the
 * BSSRDFs calls this in its prepare, before rendering (not thread-safe;
 * a no-op once built); the message names the material. */
ss_status ss_subsurface_build(ss_subsurface *s, ss_error *err);
/* 1 when material `material` has a BSSRDF and it is built. */
int ss_subsurface_built(const ss_subsurface *s, int material);
/* Number of distinct BSSRDFs, built or deferred (the size of the cache). */
size_t ss_subsurface_count(const ss_subsurface *s);

/* What the table cache did while the scene was committed; a default cache
 * directory that could not be created counts as a write failure (the
 * tables then stay in memory), a directory the scene names is an error of
 * ss_subsurface_create. */
void ss_subsurface_table_stats(const ss_subsurface *s, ss_table_cache_stats *stats);
/* The disk cache directory the scene's render settings and the environment
 * name ("" : none): render.table_cache_dir when set, else
 * $SUBSURF_TABLE_CACHE ("off": none), else the user's cache directory
 * (ss_table_cache_user_dir); "" when render.table_cache is 0. */
void ss_subsurface_cache_dir(const struct ss_scene *scene, char *buf, size_t size);

/* The parameters a material's BSSRDF is created from: its medium's
 * coefficients and phase-function g, its boundary eta. */
void ss_subsurface_params(const struct ss_scene *scene, int material, ss_bssrdf_params *p);

/* Gridded media (an approximation): the BSSRDF at an exit point
 * x_o with outward normal n is the model of the homogeneous medium whose
 * density and flake axis are the grid's at the first point below x_o, along
 * -n in steps of half the smallest voxel side until the grid's box ends,
 * where the density reaches SS_GRID_EXIT_DENSITY of the grid's largest (the
 * surface of the dense matter the model stands for). Scales p's sigma_s and
 * sigma_a by that density and sets its flakes' axis to that point's; returns
 * 0 when no point below x_o is that dense (no light leaves there). */
#define SS_GRID_EXIT_DENSITY 0.05
int ss_subsurface_grid_params(const ss_medium *med, ss_vec3 x_o, ss_vec3 n, ss_bssrdf_params *p);

#endif
