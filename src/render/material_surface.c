/* Surface materials: a BSDF with the same medium on both sides. */
#include "render/material_surface.h"

#include <math.h>

static ss_vec3 vec(ss_rgb c) { return ss_vec3_make(c.c[0], c.c[1], c.c[2]); }

int ss_material_is_surface_kind(ss_material_kind kind) {
  return kind != SS_MATERIAL_DIFFUSE && kind != SS_MATERIAL_INTERFACE;
}

const char *ss_material_kind_name(ss_material_kind kind) {
  switch (kind) {
  case SS_MATERIAL_DIFFUSE:
    return "diffuse";
  case SS_MATERIAL_INTERFACE:
    return "interface";
  case SS_MATERIAL_CONDUCTOR:
    return "conductor";
  case SS_MATERIAL_MIRROR:
    return "mirror";
  case SS_MATERIAL_THIN_DIELECTRIC:
    return "thindielectric";
  case SS_MATERIAL_DIFFUSE_TRANSMISSION:
    return "diffusetransmission";
  case SS_MATERIAL_TWO_SIDED:
    return "twosided";
  case SS_MATERIAL_COATED_DIFFUSE:
    return "plastic";
  default:
    return "mix";
  }
}

static ss_status conductor(ss_material *m, ss_error *err) {
  for (int c = 0; c < 3; ++c) {
    if (!(m->conductor_k.c[c] >= 0.0 && isfinite(m->conductor_k.c[c]))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "k must be >= 0, got %g",
                          m->conductor_k.c[c]);
    }
    if (!(m->conductor_eta.c[c] > 0.0 && isfinite(m->conductor_eta.c[c]))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "eta must be > 0, got %g",
                          m->conductor_eta.c[c]);
    }
  }
  const ss_microfacet *mf = NULL;
  if (m->boundary == SS_BOUNDARY_ROUGH) {
    ss_microfacet checked;
    ss_status st = ss_microfacet_init_anisotropic(&checked, m->mf.type, m->mf.alpha,
                                                  ss_microfacet_alpha_v(&m->mf), err);
    if (st != SS_OK) {
      return st;
    }
    mf = &m->mf;
  }
  return ss_bsdf_conductor_init(&m->bsdf, vec(m->conductor_eta), vec(m->conductor_k), mf,
                                m->energy_compensation, err);
}

ss_status ss_material_surface_init(ss_material *m, ss_error *err) {
  ss_status st;
  switch (m->kind) {
  case SS_MATERIAL_CONDUCTOR:
    st = conductor(m, err);
    break;
  case SS_MATERIAL_MIRROR:
    st = ss_bsdf_mirror_init(&m->bsdf, vec(m->albedo), err);
    break;
  case SS_MATERIAL_THIN_DIELECTRIC:
    st = m->eta <= 10.0
             ? ss_bsdf_thin_dielectric_init(&m->bsdf, m->eta, err)
             : ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "eta must be in (0, 10], got %g", m->eta);
    break;
  case SS_MATERIAL_DIFFUSE_TRANSMISSION:
    st = ss_bsdf_diffuse_transmission_init(&m->bsdf, vec(m->albedo), vec(m->transmittance), err);
    break;
  case SS_MATERIAL_COATED_DIFFUSE:
    st = m->eta <= 10.0
             ? ss_bsdf_coated_diffuse_init(&m->bsdf, vec(m->albedo), m->eta, err)
             : ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "eta must be in (1, 10], got %g", m->eta);
    break;
  default:
    st = m->kind == SS_MATERIAL_MIX && !(m->mix_weight >= 0.0 && m->mix_weight <= 1.0)
             ? ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "weight must be in [0, 1], got %g",
                            m->mix_weight)
             : SS_OK;
  }
  if (st != SS_OK) {
    ss_error_prefix(err, "material '%s': ", m->name);
  }
  return st;
}

ss_status ss_material_link(ss_material *m, const ss_material *materials, size_t count,
                           ss_error *err) {
  if (m->kind != SS_MATERIAL_TWO_SIDED && m->kind != SS_MATERIAL_MIX) {
    return SS_OK;
  }
  int n = m->kind == SS_MATERIAL_MIX ? 2 : 1;
  for (int i = 0; i < n; ++i) {
    int p = m->parts[i];
    if (p < 0 || (size_t)p >= count) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "material '%s': part %d must be a material defined before it", m->name,
                          p);
    }
    const ss_material *q = &materials[p];
    if (q->kind == SS_MATERIAL_INTERFACE || ss_material_is_textured(q)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "material '%s': part '%s' must be a surface material without textures "
                          "(not a dielectric interface)",
                          m->name, q->name);
    }
  }
  const ss_bsdf *a = &materials[m->parts[0]].bsdf;
  ss_status st =
      m->kind == SS_MATERIAL_MIX
          ? ss_bsdf_mix_init(&m->bsdf, a, &materials[m->parts[1]].bsdf, m->mix_weight, err)
          : ss_bsdf_two_sided_init(&m->bsdf, a, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "material '%s': ", m->name);
  }
  return st;
}
