/* pbrt-v3's materials (matte, glass, none, subsurface, kdsubsurface),
 * textures (constant, imagemap, checkerboard, scale) and named media
 * (homogeneous) as subsurf's materials, textures and media (pbrt.h,
 * docs/pbrt-import.md). */
#include "io/pbrt.h"

#include "subsurf/albedo_inversion.h"
#include "subsurf/texture_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* pbrt-v3 microfacet.cpp, TrowbridgeReitzDistribution::RoughnessToAlpha:
 * a quartic polynomial in x = ln(roughness) fitted by its authors. */
double ss_pbrt_roughness_to_alpha(double roughness) {
  double x = log(fmax(roughness, 1e-3));
  return 1.62142 + 0.819955 * x + 0.1734 * x * x + 0.0171201 * x * x * x +
         0.000640711 * x * x * x * x;
}

/* A float parameter that may name a texture: only constants are used. */
static double float_param(ss_pbrt *P, ss_pbrt_params *ps, const char *what, const char *name,
                          double fallback) {
  ss_rgb v = ss_rgb_gray(fallback);
  const ss_texture *tex = NULL;
  if (ss_pbrt_texturable(P, ps, name, 1, &v, &tex) && tex) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: a non-constant texture for \"%s\" is not supported; %g is used", what, name,
                 fallback);
    return fallback;
  }
  return v.c[0];
}

static ss_rgb rgb_param(ss_pbrt *P, ss_pbrt_params *ps, const char *what, const char *name,
                        ss_rgb fallback) {
  ss_rgb v = fallback;
  const ss_texture *tex = NULL;
  if (ss_pbrt_texturable(P, ps, name, 0, &v, &tex) && tex) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: a non-constant texture for \"%s\" is not supported; its default is used",
                 what, name);
    return fallback;
  }
  return v;
}

/* Kr and Kt scale reflection and transmission in pbrt-v3; subsurf's
 * dielectrics are physical (Fresnel only). */
static void check_unit_scales(ss_pbrt *P, ss_pbrt_params *ps, const char *what) {
  static const char *const names[] = {"Kr", "Kt"};
  for (int i = 0; i < 2; ++i) {
    ss_rgb k = rgb_param(P, ps, what, names[i], ss_rgb_gray(1.0));
    if (k.c[0] != 1.0 || k.c[1] != 1.0 || k.c[2] != 1.0) {
      ss_pbrt_warn(P, ps->file, ps->line,
                   "%s: %s (%g %g %g) is not supported: the boundary reflects and transmits by "
                   "Fresnel alone (as %s 1)",
                   what, names[i], k.c[0], k.c[1], k.c[2], names[i]);
    }
  }
}

/* eta and the boundary: smooth, or rough (GGX, pbrt-v3's Trowbridge-Reitz)
 * from uroughness/vroughness with pbrt-v3's remapping. */
static void read_boundary(ss_pbrt *P, ss_pbrt_params *ps, const char *what, double eta,
                          ss_material *m) {
  m->kind = SS_MATERIAL_INTERFACE;
  m->eta = float_param(P, ps, what, "eta", eta);
  if (!strcmp(what, "Material \"glass\"")) {
    m->eta = float_param(P, ps, what, "index", m->eta);
  }
  double u = float_param(P, ps, what, "uroughness", 0.0);
  double v = float_param(P, ps, what, "vroughness", 0.0);
  ss_rgb r;
  const ss_texture *tex = NULL;
  if (ss_pbrt_texturable(P, ps, "roughness", 1, &r, &tex)) { /* pbrt-v4's spelling */
    u = v = tex ? 0.0 : r.c[0];
  }
  int remap = 1;
  ss_pbrt_bool(P, ps, "remaproughness", &remap);
  check_unit_scales(P, ps, what);
  if (ss_pbrt_array(P, ps, "bumpmap", (const char *const[]){"texture", NULL})) {
    ss_pbrt_warn(P, ps->file, ps->line, "%s: bumpmap is not supported (ignored)", what);
  }
  if (u != v) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: anisotropic roughness (%g, %g) is approximated by the isotropic %g", what, u,
                 v, 0.5 * (u + v));
    u = 0.5 * (u + v);
  }
  if (u <= 0.0) {
    m->boundary = SS_BOUNDARY_SMOOTH;
    return;
  }
  m->boundary = SS_BOUNDARY_ROUGH;
  m->mf.type = SS_MICROFACET_GGX;
  m->mf.alpha = remap ? ss_pbrt_roughness_to_alpha(u) : u;
}

/* pbrt-v3's phase: Henyey-Greenstein of mean cosine g (isotropic at 0). */
static void set_phase(ss_medium *med, double g) {
  med->optics.g = ss_rgb_gray(g);
  med->optics.phase = g == 0.0 ? SS_PHASE_ISOTROPIC : SS_PHASE_HG;
}

/* pbrt-v3's coefficients of a medium or subsurface material: the default
 * (.0011 .0024 .014 / 2.55 3.21 3.77, per mm), a measured medium's (its
 * reduced scattering coefficient taken as sigma_s), or sigma_a/sigma_s,
 * each times scale. Returns 1 when a preset was found. */
static int read_coefficients(ss_pbrt *P, ss_pbrt_params *ps, const char *what, const char *key,
                             ss_medium *med) {
  med->optics = ss_medium_optics_gray(0.0, 0.0, 0.0, SS_PHASE_ISOTROPIC);
  med->optics.sigma_a = ss_rgb_make(.0011, .0024, .014);
  med->optics.sigma_s = ss_rgb_make(2.55, 3.21, 3.77);
  char preset[SS_NAME_SIZE] = "";
  int found = 0;
  if (ss_pbrt_string(P, ps, key, preset, sizeof preset) && preset[0]) {
    ss_error e;
    found = ss_medium_from_preset(med, preset, 1.0, &e) == SS_OK;
    if (!found) {
      ss_pbrt_warn(P, ps->file, ps->line,
                   "%s: no measured medium named \"%s\"; pbrt-v3's default coefficients are used",
                   what, preset);
    }
  }
  med->optics.sigma_a = rgb_param(P, ps, what, "sigma_a", med->optics.sigma_a);
  med->optics.sigma_s = rgb_param(P, ps, what, "sigma_s", med->optics.sigma_s);
  double scale = float_param(P, ps, what, "scale", 1.0);
  med->optics.sigma_a = ss_rgb_scale(med->optics.sigma_a, scale);
  med->optics.sigma_s = ss_rgb_scale(med->optics.sigma_s, scale);
  return found;
}

static void add_medium(ss_pbrt *P, ss_pbrt_params *ps, ss_medium *med, int *index) {
  ss_error e;
  if (P->st == SS_OK && (ss_medium_init(med, &e) != SS_OK ||
                         ss_scene_add_medium(P->scene, med, index, &e) != SS_OK)) {
    ss_pbrt_fail(P, ps->file, ps->line, "%s", e.message);
  }
}

/* kdsubsurface: Kd and mfp (times scale) inverted for eta and g, by PBD's
 * effective albedo as pbrt-v3's SubsurfaceFromDiffuse (the exact table where
 * Kd is a texture: PBD's inversion is too slow per shading point). */
static void kd_subsurface(ss_pbrt *P, ss_pbrt_params *ps, const char *what, ss_material *m) {
  const ss_texture *kd_tex = NULL, *mfp_tex = NULL;
  ss_rgb kd = ss_rgb_gray(0.5), mfp = ss_rgb_gray(1.0);
  ss_pbrt_texturable(P, ps, "Kd", 0, &kd, &kd_tex);
  ss_pbrt_texturable(P, ps, "mfp", 0, &mfp, &mfp_tex);
  double scale = float_param(P, ps, what, "scale", 1.0);
  double g = float_param(P, ps, what, "g", 0.0);
  if (P->st != SS_OK) {
    return;
  }
  if (mfp_tex && scale != 1.0) {
    ss_pbrt_warn(P, ps->file, ps->line, "%s: scale %g is not applied to a textured mfp", what,
                 scale);
  }
  mfp = ss_rgb_scale(mfp, scale);
  ss_albedo_inversion method = kd_tex ? SS_ALBEDO_INVERSION_EXACT : SS_ALBEDO_INVERSION_PBD;
  if (kd_tex) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: a textured Kd is inverted with the exact half-space table, not PBD's "
                 "effective albedo",
                 what);
    ss_rgb lo, hi;
    ss_texture_range(kd_tex, &lo, &hi);
    kd = ss_rgb_scale(ss_rgb_add(lo, hi), 0.5);
  }
  if (mfp_tex) {
    ss_rgb lo, hi;
    ss_texture_range(mfp_tex, &lo, &hi);
    mfp = ss_rgb_scale(ss_rgb_add(lo, hi), 0.5);
  }
  m->textures[SS_PARAM_ALBEDO] = kd_tex;
  m->textures[SS_PARAM_MFP] = mfp_tex;
  m->by_albedo = 1;
  m->albedo = kd;
  m->mfp = mfp;
  m->albedo_inversion = (int)method;
  double eta = m->boundary == SS_BOUNDARY_INDEX_MATCHED ? 1.0 : m->eta;
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "%.40s.medium", m->name);
  set_phase(&med, g);
  for (int k = 0; k < 3; ++k) {
    ss_error e;
    /* pbrt-v3 clamps Kd to [0, 1]; the inversion needs (0, 1) */
    double a = fmin(fmax(kd.c[k], 1e-4), 1.0 - 1e-4);
    if (a != kd.c[k]) {
      ss_pbrt_warn(P, ps->file, ps->line, "%s: Kd %g clamped to %g", what, kd.c[k], a);
    }
    if (ss_albedo_to_coefficients(method, a, mfp.c[k], g, eta, &med.optics.sigma_s.c[k],
                                  &med.optics.sigma_a.c[k], &e) != SS_OK) {
      ss_pbrt_fail(P, ps->file, ps->line, "%s: %s", what, e.message);
      return;
    }
  }
  add_medium(P, ps, &med, &m->medium);
}

static void subsurface(ss_pbrt *P, ss_pbrt_params *ps, const char *what, ss_material *m) {
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "%.40s.medium", m->name);
  int preset = read_coefficients(P, ps, what, "name", &med);
  double g = float_param(P, ps, what, "g", 0.0);
  if (preset && g != 0.0) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: g %g replaced by 0 with a measured medium (as pbrt-v3 does: its "
                 "coefficients are reduced ones)",
                 what, g);
    g = 0.0;
  }
  set_phase(&med, g);
  add_medium(P, ps, &med, &m->medium);
}

static void add_material(ss_pbrt *P, const ss_pbrt_material *pm, const char *name) {
  void *grown = realloc(P->materials, (P->num_materials + 1) * sizeof *P->materials);
  if (!grown) {
    ss_pbrt_fail(P, pm->file, pm->line, "out of memory");
    return;
  }
  P->materials = grown;
  P->materials[P->num_materials] = *pm;
  int index = (int)P->num_materials++;
  if (!name) {
    P->gs.material = index;
    return;
  }
  grown = realloc(P->named, (P->num_named + 1) * sizeof *P->named);
  if (!grown) {
    ss_pbrt_fail(P, pm->file, pm->line, "out of memory");
    return;
  }
  P->named = grown;
  snprintf(P->named[P->num_named].name, SS_NAME_SIZE, "%s", name);
  P->named[P->num_named++].material = index;
}

void ss_pbrt_default_material(ss_pbrt *P) {
  ss_pbrt_material pm;
  memset(&pm, 0, sizeof pm);
  pm.kind = SS_PBRT_MAT_SURFACE;
  pm.m.kind = SS_MATERIAL_DIFFUSE;
  pm.m.albedo = ss_rgb_gray(0.5); /* pbrt-v3: matte, Kd 0.5 */
  pm.m.medium = -1;
  snprintf(pm.m.name, sizeof pm.m.name, "pbrt0");
  snprintf(pm.file, sizeof pm.file, "%s", P->lex->file);
  add_material(P, &pm, NULL);
}

void ss_pbrt_material_directive(ss_pbrt *P, const char *type, const char *name,
                                ss_pbrt_params *ps) {
  ss_pbrt_material pm;
  memset(&pm, 0, sizeof pm);
  snprintf(pm.file, sizeof pm.file, "%s", ps->file);
  pm.line = ps->line;
  ss_material *m = &pm.m;
  m->medium = -1;
  snprintf(m->name, sizeof m->name, "pbrt%zu", P->num_materials);
  char what[2 * SS_NAME_SIZE];
  snprintf(what, sizeof what, "Material \"%s\"", type);
  pm.kind = SS_PBRT_MAT_SURFACE;
  if (!strcmp(type, "matte") || !strcmp(type, "")) {
    m->kind = SS_MATERIAL_DIFFUSE;
    m->albedo = ss_rgb_gray(0.5);
    const ss_texture *tex = NULL;
    ss_pbrt_texturable(P, ps, "Kd", 0, &m->albedo, &tex);
    m->textures[SS_PARAM_ALBEDO] = tex;
    if (float_param(P, ps, what, "sigma", 0.0) != 0.0) {
      ss_pbrt_warn(P, ps->file, ps->line,
                   "%s: sigma (Oren-Nayar roughness) is not supported; the surface is Lambertian",
                   what);
    }
    if (!tex && m->albedo.c[0] == 0.0 && m->albedo.c[1] == 0.0 && m->albedo.c[2] == 0.0) {
      pm.kind = SS_PBRT_MAT_BLACK;
    }
  } else if (!strcmp(type, "glass")) {
    read_boundary(P, ps, what, 1.5, m);
  } else if (!strcmp(type, "none")) {
    pm.kind = SS_PBRT_MAT_NONE;
    m->kind = SS_MATERIAL_INTERFACE;
    m->boundary = SS_BOUNDARY_INDEX_MATCHED;
    m->eta = 1.0;
  } else if (!strcmp(type, "subsurface") || !strcmp(type, "kdsubsurface")) {
    pm.kind = SS_PBRT_MAT_SUBSURFACE;
    read_boundary(P, ps, what, 1.33, m);
    /* pbrt-v3 renders these with its tabulated photon beam diffusion
     * BSSRDF: the bssrdf integrator's pbd */
    snprintf(m->bssrdf, sizeof m->bssrdf, "pbd");
    if (type[0] == 'k') {
      kd_subsurface(P, ps, what, m);
    } else {
      subsurface(P, ps, what, m);
    }
    P->has_subsurface = 1;
  } else {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s is not supported; a diffuse surface of its Kd (default 0.5) is used", type);
    m->kind = SS_MATERIAL_DIFFUSE;
    m->albedo = rgb_param(P, ps, what, "Kd", ss_rgb_gray(0.5));
  }
  ss_error e;
  if (P->st == SS_OK && ss_material_check(m, &e) != SS_OK) {
    ss_pbrt_fail(P, ps->file, ps->line, "%s: %s", what, e.message);
  }
  if (P->st == SS_OK) {
    add_material(P, &pm, name);
  }
}

int ss_pbrt_scene_material(ss_pbrt *P, const char *file, int line, int *skip) {
  *skip = 0;
  const ss_pbrt_material *pm = &P->materials[P->gs.material];
  int medium = P->gs.inside;
  if (pm->kind == SS_PBRT_MAT_BLACK) {
    return -1;
  }
  if (pm->kind == SS_PBRT_MAT_NONE && medium < 0) {
    *skip = 1;
    return -1;
  }
  if (medium >= 0 && (pm->kind == SS_PBRT_MAT_SUBSURFACE || pm->m.kind == SS_MATERIAL_DIFFUSE)) {
    ss_pbrt_warn(P, file, line,
                 "MediumInterface inside \"%s\" ignored: the shape's material (%s:%d) %s",
                 P->scene->media[medium].name, pm->file, pm->line,
                 pm->kind == SS_PBRT_MAT_SUBSURFACE ? "holds its own medium" : "is opaque");
    medium = -1;
  }
  if (pm->kind == SS_PBRT_MAT_SUBSURFACE) {
    medium = pm->m.medium;
  }
  for (size_t i = 0; i < P->num_made; ++i) {
    if (P->made[i].material == P->gs.material && P->made[i].medium == medium) {
      return P->made[i].scene_material;
    }
  }
  void *grown = realloc(P->made, (P->num_made + 1) * sizeof *P->made);
  if (!grown) {
    ss_pbrt_fail(P, file, line, "out of memory");
    return -1;
  }
  P->made = grown;
  ss_material m = pm->m;
  m.medium = medium;
  if (medium >= 0 && pm->kind != SS_PBRT_MAT_SUBSURFACE) {
    snprintf(m.name, sizeof m.name, "pbrt%d+%.40s", P->gs.material, P->scene->media[medium].name);
  }
  int index = -1;
  ss_error e;
  if (ss_material_check(&m, &e) != SS_OK ||
      ss_scene_add_material(P->scene, &m, &index, &e) != SS_OK) {
    ss_pbrt_fail(P, file, line, "%s", e.message);
    return -1;
  }
  P->made[P->num_made].material = P->gs.material;
  P->made[P->num_made].medium = medium;
  P->made[P->num_made++].scene_material = index;
  return index;
}

void ss_pbrt_named_medium(ss_pbrt *P, const char *name, ss_pbrt_params *ps) {
  char type[SS_NAME_SIZE] = "";
  ss_pbrt_string(P, ps, "type", type, sizeof type);
  char what[2 * SS_NAME_SIZE];
  snprintf(what, sizeof what, "MakeNamedMedium \"%s\"", name);
  if (strcmp(type, "homogeneous")) {
    ss_pbrt_warn(P, ps->file, ps->line,
                 "%s: type \"%s\" is not supported; a homogeneous medium of its sigma_a, sigma_s "
                 "and scale is used",
                 what, type);
  }
  ss_medium med;
  memset(&med, 0, sizeof med);
  if (strlen(name) >= sizeof med.name || !name[0]) {
    ss_pbrt_fail(P, ps->file, ps->line, "%s: the name must have 1 to %zu bytes", what,
                 sizeof med.name - 1);
    return;
  }
  snprintf(med.name, sizeof med.name, "%s", name);
  read_coefficients(P, ps, what, "preset", &med);
  /* media keep g with a preset in pbrt-v3 (unlike subsurface materials) */
  set_phase(&med, float_param(P, ps, what, "g", 0.0));
  add_medium(P, ps, &med, NULL);
}
