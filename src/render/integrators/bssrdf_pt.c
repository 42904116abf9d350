/* `bssrdf`: path tracing of surfaces in which translucent materials scatter
 * light below their surface through their BSSRDF model (King2013; Jensen2001;
 * pbrt-v3 sec. 16.4), instead of the volumetric random walk of
 * `volpath`.
 *
 * A path reaching a translucent surface from outside at x_o, toward the
 * viewer w_o, takes one of two branches: with probability q = Fr(cos_o)
 * (smooth Fresnel at the geometric normal; 0 index matched) the boundary's
 * reflection lobe alone (the lobe choice of the dielectric's sampler forced,
 * its density divided by the Fresnel factor it included), and with 1 - q the
 * subsurface term
 *     L = int int S(x_i, w_i; x_o, w_o) L_i(x_i, w_i) cos_i dw_i dA(x_i),
 * S carrying the model's own Fresnel transmission factors. The entry point
 * is sampled by probe rays (probe.h) with the one-sample MIS density over
 * axes x channels x hits (for fwddip combined with a ray along the ballistic
 * direction, fwddip_entry.h); at x_i the direct light is estimated by light
 * sampling and the path continues along a cosine-sampled direction, the two
 * combined by the power heuristic. A model flagged SS_BSSRDF_BRDF
 * (dipole-brdf) acts as a BRDF at x_o. The `single` model and
 * "single_scattering" materials add Jensen et al. 2001's single scattering
 * (bssrdf_vertex.h). Paths never enter a translucent object. */
#include "render/integrators/bssrdf_path.h"

#include "subsurf/subsurface.h"
#include "subsurf/volume.h"

#include <stdlib.h>

/* The integrator's options (scene key "integrator"); a NULL state (no
 * prepare) takes the defaults. */
typedef struct {
  int all_hits;
} bssrdf_state;

static ss_rgb bssrdf_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                        ss_path_stats *stats) {
  const bssrdf_state *o = state;
  return ss_bssrdf_path_li(scene, o ? o->all_hits : SS_BSSRDF_DEFAULT_ALL_HITS, ray, rng, stats);
}

/* Its volumetric walk is homogeneous and isotropic in direction: oriented
 * or gridded media (volume.h) take a model (aniso-dipole), not lod
 * "volpath" (their single scattering is tracked, single_scatter.h); nested
 * media are refused too. */
static ss_status bssrdf_check(const ss_scene *scene, ss_error *err) {
  double all_hits = ss_scene_integrator_option(scene, "all_hits", SS_BSSRDF_DEFAULT_ALL_HITS);
  if (!(all_hits == 0.0 || all_hits == 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "bssrdf: option all_hits: expected 0 (one hit per probe chord) or 1 "
                        "(every hit), got %g",
                        all_hits);
  }
  for (size_t i = 0; i < scene->num_materials; ++i) {
    const ss_material *m = &scene->materials[i];
    if (ss_material_is_translucent(m) && ss_medium_is_volume(&scene->media[m->medium]) &&
        ss_bssrdf_path_volumetric(scene, m)) {
      return ss_error_set(err, SS_ERR_UNSUPPORTED,
                          "bssrdf: material '%s': micro-flake and gridded media take a model "
                          "(aniso-dipole), not lod \"volpath\"",
                          m->name);
    }
  }
  return ss_refuse_nested_media(scene, "bssrdf", err);
}

static ss_status bssrdf_prepare(const ss_scene *scene, void **state, ss_error *err) {
  *state = NULL;
  ss_status st = bssrdf_check(scene, err);
  if (st == SS_OK) {
    st = ss_subsurface_build(scene->subsurface, err);
  }
  if (st != SS_OK) {
    return st;
  }
  bssrdf_state *o = malloc(sizeof *o);
  if (!o) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "bssrdf: out of memory");
  }
  o->all_hits = (int)ss_scene_integrator_option(scene, "all_hits", SS_BSSRDF_DEFAULT_ALL_HITS);
  *state = o;
  return SS_OK;
}

static void bssrdf_release(void *state) { free(state); }

static const char *const bssrdf_options[] = {"all_hits", NULL};

const ss_integrator_ops ss_integrator_bssrdf = {
    .name = "bssrdf",
    .summary = "path tracing with BSSRDF models for translucent materials, probe-ray entry "
               "sampling (Jensen et al. 2001; King et al. 2013)",
    .options = bssrdf_options,
    .check = bssrdf_check,
    .prepare = bssrdf_prepare,
    .release = bssrdf_release,
    .li = bssrdf_li,
};
