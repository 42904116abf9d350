/* Media and materials of a scene.
 *
 * A medium is homogeneous, described by its optical coefficients
 * (medium_optics.h: RGB sigma_s and sigma_a per unit length of the scene, g
 * and the phase family), with one g for all channels: volpath traces one
 * phase function per medium. A material is either a dielectric interface
 * (index matched, smooth or rough) that may enclose a medium
 * ("translucent" = interface + interior medium + the name of the BSSRDF
 * model that BSSRDF integrators use for it; volpath ignores the name and
 * traces the medium exactly), or a surface with the same medium on both
 * sides (diffuse, conductor, mirror, thin dielectric, diffuse transmission,
 * coated diffuse, two-sided, mix) that integrators see only through its BSDF. Normals
 * point outward; eta = n_inside / n_outside. */
#ifndef SUBSURF_MATERIAL_H
#define SUBSURF_MATERIAL_H

#include "subsurf/bsdf.h"
#include "subsurf/bssrdf.h"
#include "subsurf/medium_optics.h"
#include "subsurf/microfacet.h"
#include "subsurf/phase.h"
#include "subsurf/rgb.h"
#include "subsurf/status.h"
#include "subsurf/texture.h"

#include <stddef.h>
#include <stdint.h>

#define SS_NAME_SIZE 64
#define SS_PRIORITY_MAX 1000

typedef struct {
  char name[SS_NAME_SIZE];
  ss_medium_optics optics; /* the description */
  ss_rgb sigma_t;          /* derived: sigma_s + sigma_a */
  ss_phase phase;          /* derived: optics.phase with g = optics.g */
  /* A heterogeneous medium's density and flake axes (grid.h, volume.h), or
   * NULL; the scene takes ownership in ss_scene_add_medium. */
  struct ss_grid *grid;
  /* Derived at commit for flakes or a grid (ss_medium_prepare_volume): the
   * flakes about +z with albedo shape alpha / alpha1 (owned by the scene),
   * the flakes' axis frame, and the majorant: the largest sigma_t over
   * points and directions is majorant (sigma_s + sigma_a) in every channel. */
  ss_microflake *flakes;
  ss_frame axis;
  double majorant;
  /* A grid's count of tracking collisions that found sigma_t above the
   * majorant (volume.h, ss_medium_majorant_exceeded); shared by copies of
   * the medium, allocated with the flakes. */
  uint64_t *majorant_exceeded;
} ss_medium;

/* Validates the optics (ss_medium_optics_check, and the same g in every
 * channel), derives sigma_t and builds the phase function; the message names
 * the medium. */
ss_status ss_medium_init(ss_medium *m, ss_error *err);
/* Fills optics.sigma_s and optics.sigma_a from a preset of media.h scaled by
 * `scale` for the medium's optics.g and phase (ss_medium_optics_from_preset).
 * Returns SS_ERR_INVALID_ARGUMENT for an unknown name. */
ss_status ss_medium_from_preset(ss_medium *m, const char *preset, double scale, ss_error *err);

typedef enum {
  SS_MATERIAL_DIFFUSE,              /* Lambertian reflector */
  SS_MATERIAL_INTERFACE,            /* dielectric interface, optionally enclosing a medium */
  SS_MATERIAL_CONDUCTOR,            /* metal, smooth or rough (boundary, mf) */
  SS_MATERIAL_MIRROR,               /* perfect mirror of reflectance albedo */
  SS_MATERIAL_THIN_DIELECTRIC,      /* window pane of index eta */
  SS_MATERIAL_DIFFUSE_TRANSMISSION, /* reflects albedo, transmits transmittance */
  SS_MATERIAL_TWO_SIDED,            /* parts[0] seen from both sides */
  SS_MATERIAL_MIX,                  /* mix_weight parts[0] + (1 - mix_weight) parts[1] */
  SS_MATERIAL_COATED_DIFFUSE,       /* plastic: a coat of index eta over albedo */
} ss_material_kind;

typedef enum {
  SS_BOUNDARY_INDEX_MATCHED, /* no interface event: rays pass straight on */
  SS_BOUNDARY_SMOOTH,        /* smooth dielectric (delta reflection/refraction) */
  SS_BOUNDARY_ROUGH,         /* rough dielectric (Walter et al. 2007) */
} ss_boundary_type;

/* What stands for a translucent material's medium in the `bssrdf`
 * integrator (level of detail, subsurface.h). */
typedef enum {
  SS_LOD_BSSRDF,  /* the material's BSSRDF model */
  SS_LOD_AUTO,    /* chosen from the object's size over the mean free path */
  SS_LOD_VOLPATH, /* a volumetric random walk inside, as volpath */
  SS_LOD_BRDF,    /* the effective BRDF (SS_LOD_BRDF_MODEL) */
} ss_lod;

/* The material parameters that a texture may replace. A colour
 * parameter takes the texture's RGB value; a data parameter (roughness)
 * its first channel. */
typedef enum {
  SS_PARAM_ALBEDO, /* diffuse reflectance, colour in [0, 1]; or a translucent
                      material's surface albedo, in (0, 1) (albedo_inversion.h) */
  SS_PARAM_ALPHA,  /* rough boundary roughness, data in [0, 4]; below 1e-3
                      the boundary is smooth there (as a constant alpha) */
  SS_PARAM_MFP,    /* a translucent material's mean free path, colour > 0 */
  SS_PARAM_COUNT,
} ss_material_param;

/* The parameter's name in scene files ("albedo", "alpha", "mfp"). */
const char *ss_material_param_name(ss_material_param p);
/* 1 for colour parameters (8-bit images are sRGB-decoded), 0 for data. */
int ss_material_param_is_colour(ss_material_param p);

typedef struct {
  char name[SS_NAME_SIZE];
  ss_material_kind kind;
  ss_rgb albedo; /* diffuse reflectance, or translucent surface albedo */
  /* A translucent material given by albedo and mfp: its medium
   * holds the coefficients of the constants; with textures on albedo or mfp
   * the coefficients vary over the surface (ss_material_optics_at). */
  int by_albedo;
  ss_rgb mfp;
  int albedo_inversion; /* ss_albedo_inversion */
  ss_boundary_type boundary;
  double eta;       /* n_inside / n_outside (interfaces; 1 when index matched) */
  ss_microfacet mf; /* rough boundary */
  /* Rough boundary: add the multiple-scattering energy compensation of
   * Kulla & Conty 2017 (ss_bsdf_rough_dielectric_ms_init); scene files turn
   * it on by default for translucent materials. Where alpha is textured the
   * tables over alpha (ss_dielectric_ms_alpha) are interpolated per point. */
  int energy_compensation;
  int medium; /* index into the scene's media, or -1 (clear interior) */
  /* Nested and touching media (SchmidtBudge2002): where the regions of
   * two interfaces overlap, the one of higher priority fills the overlap;
   * 0..SS_PRIORITY_MAX. */
  int priority;
  char bssrdf[SS_NAME_SIZE]; /* BSSRDF model name, "" when none */
  /* The model options set on the material (ss_bssrdf_params_set_option);
   * its coefficients are filled from the medium when the scene is committed. */
  ss_bssrdf_params bssrdf_options;
  int bssrdf_single; /* add Jensen et al. 2001's single scattering */
  ss_lod lod;
  /* Conductors: the complex index eta + i k per channel (boundary smooth
   * or rough with mf; energy_compensation as for dielectrics). */
  ss_rgb conductor_eta, conductor_k;
  ss_rgb transmittance; /* diffuse transmission */
  /* Two-sided and mix: the materials they are made of (indices into the
   * scene's materials, lower than this material's own: surfaces without
   * textures) and the mix's weight of parts[0]. */
  int parts[2];
  double mix_weight;
  ss_bsdf bsdf; /* built by ss_material_init (two-sided and mix: ss_material_link) */
  /* Built by ss_material_init: the shared compensation tables over alpha of
   * a compensated rough boundary with a textured alpha, else NULL. */
  const ss_dielectric_ms_alpha *ms_alpha;
  /* Textures in place of parameters, NULL where the constant field holds;
   * owned by the scene (ss_scene_add_texture). */
  const ss_texture *textures[SS_PARAM_COUNT];
} ss_material;

/* Parses "bssrdf", "auto", "volpath", "brdf"; 0 on an unknown name. */
int ss_lod_from_name(const char *name, ss_lod *lod);
const char *ss_lod_name(ss_lod lod);

/* Validates the fields and builds the BSDF; the message names the field.
 * Textures must be on parameters the material has, with values in the
 * parameter's range (ss_texture_range). */
ss_status ss_material_init(ss_material *m, ss_error *err);
/* Two-sided and mix materials: checks the parts (materials[0..count) holds
 * this material's predecessors, already initialised) and builds the BSDF
 * from theirs; nothing for other kinds. The materials must not move after. */
ss_status ss_material_link(ss_material *m, const ss_material *materials, size_t count,
                           ss_error *err);
/* The material kind's name in scene files ("conductor"). */
const char *ss_material_kind_name(ss_material_kind kind);
/* The checks of ss_material_init without building anything: for scene
 * readers, which report errors where the material is read, while the scene
 * builds its materials once when it is committed (a rough boundary's energy
 * compensation tables take about 0.2 M BSDF samples). */
ss_status ss_material_check(const ss_material *m, ss_error *err);

/* SS_OK unless parameter p is textured on a material that lacks it or with
 * values outside its range (albedo [0, 1] or, translucent, (0, 1) and
 * invertible; alpha [0, 4]; mfp > 0). */
ss_status ss_material_check_texture(const ss_material *m, ss_material_param p, ss_error *err);
/* 1 when some parameter is textured. */
int ss_material_is_textured(const ss_material *m);
/* 1 when a texture of the material reads (u, v): its shapes need uvs.
 * *param receives the first such parameter. */
int ss_material_uses_uv(const ss_material *m, ss_material_param *param);
/* The BSDF at a surface point: &m->bsdf when nothing is textured (so an
 * untextured material costs nothing), else *scratch rebuilt from the
 * texture values at tc. */
const ss_bsdf *ss_material_bsdf_at(const ss_material *m, ss_texcoord tc, ss_bsdf *scratch);

/* 1 when a translucent material's coefficients vary over its surface
 * (textured albedo or mfp). */
int ss_material_varies(const ss_material *m);
/* The coefficients of a translucent material at a surface point: its
 * medium `base`'s with sigma_s and sigma_a converted from the albedo and
 * mfp there (ss_albedo_to_coefficients, the material's inversion, the
 * medium's g and the boundary's eta). Returns 0 (and leaves *out) when the
 * material does not vary. */
int ss_material_optics_at(const ss_material *m, const ss_medium *base, ss_texcoord tc,
                          ss_medium *out);

/* Parses "index-matched", "smooth", "rough"; 0 on an unknown name. */
int ss_boundary_type_from_name(const char *name, ss_boundary_type *type);
const char *ss_boundary_type_name(ss_boundary_type type);

/* 1 when rays cross this material's surface without any event (an index
 * matched interface). */
static inline int ss_material_is_null(const ss_material *m) {
  return m->kind == SS_MATERIAL_INTERFACE && m->boundary == SS_BOUNDARY_INDEX_MATCHED;
}

#endif
