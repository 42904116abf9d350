/* Spatially varying subsurface scattering: the coefficients of a
 * translucent material given by a textured albedo or mfp, at a surface
 * point (see material.h). */
#include "subsurf/albedo_inversion.h"
#include "subsurf/material.h"

int ss_material_varies(const ss_material *m) {
  return m->by_albedo && (m->textures[SS_PARAM_ALBEDO] || m->textures[SS_PARAM_MFP]);
}

int ss_material_optics_at(const ss_material *m, const ss_medium *base, ss_texcoord tc,
                          ss_medium *out) {
  if (!ss_material_varies(m)) {
    return 0;
  }
  const ss_texture *ta = m->textures[SS_PARAM_ALBEDO], *tm = m->textures[SS_PARAM_MFP];
  ss_rgb albedo = ta ? ss_texture_eval(ta, tc) : m->albedo;
  ss_rgb mfp = tm ? ss_texture_eval(tm, tc) : m->mfp;
  double eta = m->boundary == SS_BOUNDARY_INDEX_MATCHED ? 1.0 : m->eta;
  *out = *base;
  for (int c = 0; c < 3; ++c) {
    double s, a;
    /* The texture's range was checked invertible when the scene was read,
     * and a bilinear or blended value lies inside it. */
    if (ss_albedo_to_coefficients((ss_albedo_inversion)m->albedo_inversion, albedo.c[c], mfp.c[c],
                                  base->optics.g.c[c], eta, &s, &a, NULL) == SS_OK) {
      out->optics.sigma_s.c[c] = s;
      out->optics.sigma_a.c[c] = a;
    }
  }
  out->sigma_t = ss_rgb_add(out->optics.sigma_s, out->optics.sigma_a);
  return 1;
}
