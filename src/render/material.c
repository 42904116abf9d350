/* Media and materials: validation and boundary BSDF construction. */
#include "subsurf/material.h"

#include "subsurf/media.h"

#include <math.h>
#include <string.h>

static int rgb_valid(ss_rgb v) {
  return ss_rgb_is_finite(v) && v.c[0] >= 0.0 && v.c[1] >= 0.0 && v.c[2] >= 0.0;
}

ss_status ss_medium_init(ss_medium *m, ss_error *err) {
  if (!rgb_valid(m->sigma_s)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "medium '%s': sigma_s must be finite and >= 0", m->name);
  }
  if (!rgb_valid(m->sigma_a)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "medium '%s': sigma_a must be finite and >= 0", m->name);
  }
  m->sigma_t = ss_rgb_add(m->sigma_s, m->sigma_a);
  if (!(ss_rgb_min(m->sigma_t) > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "medium '%s': sigma_s + sigma_a must be > 0 in every channel", m->name);
  }
  return SS_OK;
}

ss_status ss_medium_from_preset(ss_medium *m, const char *preset, double scale, ss_error *err) {
  const ss_medium_preset *p = ss_medium_preset_find(preset);
  if (!p) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "unknown medium preset '%s'", preset);
  }
  if (!(isfinite(scale) && scale > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "preset scale must be > 0, got %g", scale);
  }
  /* sigma_s' = (1 - g) sigma_s (similarity relation, SPEC "reduced quantities"). */
  double one_minus_g = 1.0 - m->phase.g;
  for (int c = 0; c < 3; ++c) {
    m->sigma_s.c[c] = p->sigma_s_prime[c] * scale / one_minus_g;
    m->sigma_a.c[c] = p->sigma_a[c] * scale;
  }
  return SS_OK;
}

ss_status ss_material_init(ss_material *m, ss_error *err) {
  if (m->kind == SS_MATERIAL_DIFFUSE) {
    if (!rgb_valid(m->albedo) || ss_rgb_max(m->albedo) > 1.0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "material '%s': albedo must be in [0, 1]", m->name);
    }
    ss_vec3 r = ss_vec3_make(m->albedo.c[0], m->albedo.c[1], m->albedo.c[2]);
    return ss_bsdf_diffuse_init(&m->bsdf, r, err);
  }
  if (m->boundary == SS_BOUNDARY_INDEX_MATCHED) {
    m->eta = 1.0;
  }
  if (!(isfinite(m->eta) && m->eta > 0.0 && m->eta <= 10.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "material '%s': eta must be in (0, 10], got %g", m->name, m->eta);
  }
  ss_status st;
  if (m->boundary == SS_BOUNDARY_ROUGH) {
    ss_microfacet mf;
    st = ss_microfacet_init(&mf, m->mf.type, m->mf.alpha, err);
    if (st == SS_OK) {
      st = ss_bsdf_rough_dielectric_init(&m->bsdf, m->eta, &mf, SS_TRANSPORT_RADIANCE, err);
    }
  } else {
    st = ss_bsdf_dielectric_init(&m->bsdf, m->eta, SS_TRANSPORT_RADIANCE, err);
  }
  if (st != SS_OK) {
    ss_error_prefix(err, "material '%s': ", m->name);
  }
  return st;
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
