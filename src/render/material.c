/* Media and materials: validation and boundary BSDF construction. */
#include "subsurf/material.h"

#include "render/material_surface.h"
#include "subsurf/media.h"

#include <math.h>
#include <string.h>

static int rgb_valid(ss_rgb v) {
  return ss_rgb_is_finite(v) && v.c[0] >= 0.0 && v.c[1] >= 0.0 && v.c[2] >= 0.0;
}

ss_status ss_medium_init(ss_medium *m, ss_error *err) {
  const ss_medium_optics *o = &m->optics;
  ss_status st = ss_medium_optics_check(o, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "medium '%s': ", m->name);
    return st;
  }
  if (o->g.c[1] != o->g.c[0] || o->g.c[2] != o->g.c[0]) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "medium '%s': g must be the same in every channel", m->name);
  }
  if (o->flakes.type != SS_FLAKE_NONE && o->g.c[0] != 0.0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "medium '%s': a micro-flake medium scatters by its flakes, not by a "
                        "phase function: leave out phase",
                        m->name);
  }
  m->sigma_t = ss_rgb_add(o->sigma_s, o->sigma_a);
  return ss_phase_init(&m->phase, o->phase, o->g.c[0], err);
}

ss_status ss_medium_from_preset(ss_medium *m, const char *preset, double scale, ss_error *err) {
  const ss_medium_preset *p = ss_medium_preset_find(preset);
  if (!p) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "unknown medium preset '%s'", preset);
  }
  if (!(isfinite(scale) && scale > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "preset scale must be > 0, got %g", scale);
  }
  m->optics = ss_medium_optics_from_preset(p, scale, m->optics.g.c[0], m->optics.phase);
  return SS_OK;
}

const char *ss_material_param_name(ss_material_param p) {
  static const char *const names[SS_PARAM_COUNT] = {"albedo", "alpha", "mfp"};
  return names[p];
}

int ss_material_param_is_colour(ss_material_param p) { return p != SS_PARAM_ALPHA; }

ss_status ss_material_check_texture(const ss_material *m, ss_material_param p, ss_error *err) {
  static const double lo[SS_PARAM_COUNT] = {0.0, 0.0, 0.0},
                      hi[SS_PARAM_COUNT] = {1.0, 4.0, HUGE_VAL};
  const ss_texture *t = m->textures[p];
  if (!t) {
    return SS_OK;
  }
  int has = p == SS_PARAM_ALPHA
                ? m->kind == SS_MATERIAL_INTERFACE && m->boundary == SS_BOUNDARY_ROUGH
            : p == SS_PARAM_MFP ? m->by_albedo
                                : m->kind == SS_MATERIAL_DIFFUSE || m->by_albedo;
  const char *name = ss_material_param_name(p);
  if (!has) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "this material has no parameter '%s' to texture", name);
  }
  ss_rgb tlo, thi;
  ss_texture_range(t, &tlo, &thi);
  int channels = ss_material_param_is_colour(p) ? 3 : 1;
  for (int c = 0; c < channels; ++c) {
    if (m->by_albedo && (!(tlo.c[c] > 0.0) || (p == SS_PARAM_ALBEDO && !(thi.c[c] < 1.0)))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "the texture has values in [%g, %g], outside the range of '%s', %s",
                          tlo.c[c], thi.c[c], name, p == SS_PARAM_MFP ? "> 0" : "(0, 1)");
    }
    if (!(tlo.c[c] >= lo[p] && thi.c[c] <= hi[p])) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "the texture has values in [%g, %g], outside the range of '%s', "
                          "[%g, %g]",
                          tlo.c[c], thi.c[c], name, lo[p], hi[p]);
    }
  }
  return SS_OK;
}

int ss_material_is_textured(const ss_material *m) {
  for (int p = 0; p < SS_PARAM_COUNT; ++p) {
    if (m->textures[p]) {
      return 1;
    }
  }
  return 0;
}

int ss_material_uses_uv(const ss_material *m, ss_material_param *param) {
  for (int p = 0; p < SS_PARAM_COUNT; ++p) {
    if (m->textures[p] && ss_texture_uses_uv(m->textures[p])) {
      *param = (ss_material_param)p;
      return 1;
    }
  }
  return 0;
}

const ss_bsdf *ss_material_bsdf_at(const ss_material *m, ss_texcoord tc, ss_bsdf *scratch) {
  if (!(m->textures[SS_PARAM_ALBEDO] && m->kind == SS_MATERIAL_DIFFUSE) &&
      !m->textures[SS_PARAM_ALPHA]) {
    return &m->bsdf;
  }
  *scratch = m->bsdf;
  if (m->textures[SS_PARAM_ALBEDO] && m->kind == SS_MATERIAL_DIFFUSE) {
    ss_rgb a = ss_texture_eval(m->textures[SS_PARAM_ALBEDO], tc);
    scratch->reflectance = ss_vec3_make(a.c[0], a.c[1], a.c[2]);
  }
  if (m->textures[SS_PARAM_ALPHA]) {
    ss_microfacet mf = m->mf;
    mf.alpha = fmax(ss_texture_eval(m->textures[SS_PARAM_ALPHA], tc).c[0], 1e-4);
    if (m->ms_alpha) {
      ss_bsdf_rough_dielectric_ms_at(scratch, m->eta, &mf, m->bsdf.mode, m->ms_alpha, NULL);
    } else {
      ss_bsdf_rough_dielectric_init(scratch, m->eta, &mf, m->bsdf.mode, NULL);
    }
  }
  return scratch;
}

ss_status ss_material_init(ss_material *m, ss_error *err) {
  for (int p = 0; p < SS_PARAM_COUNT; ++p) {
    if (ss_material_check_texture(m, (ss_material_param)p, err) != SS_OK) {
      ss_error_prefix(err, "material '%s': ", m->name);
      return SS_ERR_INVALID_ARGUMENT;
    }
  }
  if (m->kind == SS_MATERIAL_DIFFUSE) {
    if (!rgb_valid(m->albedo) || ss_rgb_max(m->albedo) > 1.0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "material '%s': albedo must be in [0, 1]",
                          m->name);
    }
    ss_vec3 r = ss_vec3_make(m->albedo.c[0], m->albedo.c[1], m->albedo.c[2]);
    return ss_bsdf_diffuse_init(&m->bsdf, r, err);
  }
  if (ss_material_is_surface_kind(m->kind)) {
    return ss_material_surface_init(m, err);
  }
  if (m->boundary == SS_BOUNDARY_INDEX_MATCHED) {
    m->eta = 1.0;
  }
  if (!(isfinite(m->eta) && m->eta > 0.0 && m->eta <= 10.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "material '%s': eta must be in (0, 10], got %g", m->name, m->eta);
  }
  if (m->priority < 0 || m->priority > SS_PRIORITY_MAX) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "material '%s': priority must be in [0, %d], got %d", m->name,
                        SS_PRIORITY_MAX, m->priority);
  }
  ss_status st;
  m->ms_alpha = NULL;
  if (m->boundary == SS_BOUNDARY_ROUGH) {
    const ss_texture *ta = m->textures[SS_PARAM_ALPHA];
    ss_microfacet mf;
    st = ss_microfacet_init(&mf, m->mf.type, m->mf.alpha, err);
    if (st == SS_OK && ta && m->energy_compensation && m->eta != 1.0) {
      /* A textured alpha: the shared tables over the texture's range, and
       * the constant's BSDF without tables of its own (never used). */
      ss_rgb lo, hi;
      ss_texture_range(ta, &lo, &hi);
      st = ss_dielectric_ms_alpha_get(m->mf.type, m->eta, lo.c[0], hi.c[0], &m->ms_alpha, err);
      if (st == SS_OK) {
        st = ss_bsdf_rough_dielectric_init(&m->bsdf, m->eta, &mf, SS_TRANSPORT_RADIANCE, err);
      }
    } else if (st == SS_OK) {
      st = m->energy_compensation
               ? ss_bsdf_rough_dielectric_ms_init(&m->bsdf, m->eta, &mf, SS_TRANSPORT_RADIANCE, err)
               : ss_bsdf_rough_dielectric_init(&m->bsdf, m->eta, &mf, SS_TRANSPORT_RADIANCE, err);
    }
  } else {
    st = ss_bsdf_dielectric_init(&m->bsdf, m->eta, SS_TRANSPORT_RADIANCE, err);
  }
  if (st != SS_OK) {
    ss_error_prefix(err, "material '%s': ", m->name);
  }
  return st;
}

ss_status ss_material_check(const ss_material *m, ss_error *err) {
  ss_material copy = *m;
  copy.energy_compensation = 0; /* building the tables cannot fail */
  return ss_material_init(&copy, err);
}

int ss_boundary_type_from_name(const char *name, ss_boundary_type *type) {
  if (!strcmp(name, "index-matched")) {
    *type = SS_BOUNDARY_INDEX_MATCHED;
  } else if (!strcmp(name, "smooth")) {
    *type = SS_BOUNDARY_SMOOTH;
  } else if (!strcmp(name, "rough")) {
    *type = SS_BOUNDARY_ROUGH;
  } else {
    return 0;
  }
  return 1;
}

const char *ss_boundary_type_name(ss_boundary_type type) {
  switch (type) {
  case SS_BOUNDARY_INDEX_MATCHED:
    return "index-matched";
  case SS_BOUNDARY_SMOOTH:
    return "smooth";
  default:
    return "rough";
  }
}
