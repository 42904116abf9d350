/* A translucent material given by its surface colour and mean free path
 * (albedo_inversion.h) instead of a medium:
 *     "albedo": [0.8, 0.5, 0.3], "mfp": [1.2, 0.6, 0.3], "g": 0.8,
 *     "albedo_inversion": "exact"
 * becomes a medium named "<material>.medium" with sigma_s, sigma_a per
 * channel and a Henyey-Greenstein phase function of mean cosine g (default
 * 0), for the material's boundary eta (1 when index matched). */
#include "io/scene_json.h"

#include "subsurf/albedo_inversion.h"
#include "subsurf/albedo_table.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int ss_scene_json_has_albedo(const cJSON *obj) {
  return cJSON_HasObjectItem(obj, "albedo") || cJSON_HasObjectItem(obj, "mfp");
}

/* "g" and "albedo_inversion" belong to the albedo form only. */
static ss_status check_pairing(ss_json_ctx *c, const cJSON *obj) {
  int has_medium = cJSON_HasObjectItem(obj, "medium");
  int has_albedo = cJSON_HasObjectItem(obj, "albedo"), has_mfp = cJSON_HasObjectItem(obj, "mfp");
  if (has_medium && (has_albedo || has_mfp)) {
    return ss_json_fail_key(c, has_albedo ? "albedo" : "mfp",
                            "give either a medium or albedo and mfp, not both");
  }
  if (has_albedo != has_mfp) {
    return ss_json_fail_key(c, has_albedo ? "albedo" : "mfp", "needs \"%s\" as well",
                            has_albedo ? "mfp" : "albedo");
  }
  static const char *const own[] = {"g", "albedo_inversion"};
  for (int i = 0; i < 2; ++i) {
    if (!has_albedo && cJSON_HasObjectItem(obj, own[i])) {
      return ss_json_fail_key(c, own[i],
                              "only with \"albedo\" and \"mfp\" (a medium carries its "
                              "own phase function and coefficients)");
    }
  }
  return SS_OK;
}

static ss_status read_method(ss_json_ctx *c, const cJSON *obj, ss_albedo_inversion *m) {
  char name[32] = "exact";
  ss_status st = ss_json_string(c, obj, "albedo_inversion", name, sizeof name);
  if (st == SS_OK && !ss_albedo_inversion_from_name(name, m)) {
    st = ss_json_fail_key(c, "albedo_inversion", "unknown inversion '%s' (%s)", name,
                          SS_ALBEDO_INVERSION_NAMES);
  }
  return st;
}

/* The exact table's range, checked first so that the message names g or eta. */
static ss_status check_table_range(ss_json_ctx *c, double g, double eta) {
  const ss_albedo_table *t;
  if (ss_albedo_table_builtin(&t, c->err) != SS_OK) {
    return ss_json_wrap(c, SS_ERR_PARSE);
  }
  double eta_lo, eta_hi, g_lo, g_hi;
  ss_albedo_table_range(t, &eta_lo, &eta_hi, &g_lo, &g_hi);
  if (!(g >= g_lo && g <= g_hi)) {
    return ss_json_fail_key(c, "g", "%g is outside the exact albedo table's range [%g, %g]", g,
                            g_lo, g_hi);
  }
  if (!(eta >= eta_lo && eta <= eta_hi)) {
    return ss_json_fail_key(c, "eta",
                            "%g is outside the exact albedo table's range [%g, %g] (needed by "
                            "\"albedo\")",
                            eta, eta_lo, eta_hi);
  }
  return SS_OK;
}

/* A textured albedo or mfp (docs/textures.md) or a constant; for
 * a texture, *value is the middle of its range, from which the material's
 * medium is built (what the level of detail and single scattering use). */
static ss_status read_param(ss_scene_reader *r, const cJSON *obj, ss_material *m,
                            ss_material_param p, ss_rgb *value) {
  const char *key = ss_material_param_name(p);
  ss_status st = ss_scene_json_texture(r, obj, m, p);
  if (st != SS_OK || !m->textures[p]) {
    return st == SS_OK ? ss_json_rgb(&r->json, obj, key, -HUGE_VAL, value) : st;
  }
  ss_rgb lo, hi;
  ss_texture_range(m->textures[p], &lo, &hi);
  *value = ss_rgb_scale(ss_rgb_add(lo, hi), 0.5);
  return SS_OK;
}

/* Every albedo a texture can produce must invert (the exact inversion stops
 * at 1 - F(0)): the ends of its range do when everything between does. */
static ss_status check_texture_inverts(ss_scene_reader *r, const ss_material *m,
                                       ss_albedo_inversion method, double g, double eta) {
  const ss_texture *t = m->textures[SS_PARAM_ALBEDO];
  if (!t) {
    return SS_OK;
  }
  ss_rgb ends[2];
  ss_texture_range(t, &ends[0], &ends[1]);
  for (int k = 0; k < 2; ++k) {
    for (int c = 0; c < 3; ++c) {
      double s, a;
      if (ss_albedo_to_coefficients(method, ends[k].c[c], 1.0, g, eta, &s, &a, r->json.err) !=
          SS_OK) {
        ss_json_push_key(&r->json, "albedo");
        ss_error_prefix(r->json.err, "the texture's values reach %g: ", ends[k].c[c]);
        ss_status st = ss_json_wrap(&r->json, SS_ERR_PARSE);
        ss_json_pop(&r->json);
        return st;
      }
    }
  }
  return SS_OK;
}

ss_status ss_scene_json_albedo(ss_scene_reader *r, const cJSON *obj, ss_material *m) {
  ss_json_ctx *c = &r->json;
  ss_status st = check_pairing(c, obj);
  if (st != SS_OK || !ss_scene_json_has_albedo(obj)) {
    return st;
  }
  ss_rgb albedo, mfp;
  double g = 0.0;
  ss_albedo_inversion method = SS_ALBEDO_INVERSION_EXACT;
  double eta = m->boundary == SS_BOUNDARY_INDEX_MATCHED ? 1.0 : m->eta;
  m->by_albedo = 1;
  if (st == SS_OK)
    st = read_param(r, obj, m, SS_PARAM_ALBEDO, &albedo);
  if (st == SS_OK)
    st = read_param(r, obj, m, SS_PARAM_MFP, &mfp);
  if (st == SS_OK)
    st = ss_json_number(c, obj, "g", -0.999999, 0.999999, &g);
  if (st == SS_OK)
    st = read_method(c, obj, &method);
  if (st == SS_OK && method == SS_ALBEDO_INVERSION_EXACT)
    st = check_table_range(c, g, eta);
  if (st == SS_OK)
    st = check_texture_inverts(r, m, method, g, eta);
  if (st != SS_OK) {
    return st;
  }
  m->albedo = albedo;
  m->mfp = mfp;
  m->albedo_inversion = (int)method;
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "%.40s.medium", m->name);
  med.optics = ss_medium_optics_gray(0.0, 0.0, g, SS_PHASE_HG);
  static const char ch[] = "RGB";
  for (int k = 0; k < 3; ++k) {
    if (!(albedo.c[k] > 0.0 && albedo.c[k] < 1.0)) {
      return ss_json_fail_key(c, "albedo", "must lie in (0, 1), got %g in %c", albedo.c[k], ch[k]);
    }
    if (!(mfp.c[k] > 0.0 && isfinite(1.0 / mfp.c[k]))) {
      return ss_json_fail_key(c, "mfp", "must be > 0 (with 1/mfp finite), got %g in %c", mfp.c[k],
                              ch[k]);
    }
    if (ss_albedo_to_coefficients(method, albedo.c[k], mfp.c[k], g, eta, &med.optics.sigma_s.c[k],
                                  &med.optics.sigma_a.c[k], c->err) != SS_OK) {
      ss_json_push_key(c, "albedo");
      st = ss_json_wrap(c, SS_ERR_PARSE);
      ss_json_pop(c);
      return st;
    }
  }
  if (ss_medium_init(&med, c->err) != SS_OK ||
      ss_scene_add_medium(r->scene, &med, &m->medium, c->err) != SS_OK) {
    return ss_json_wrap(c, SS_ERR_PARSE);
  }
  return SS_OK;
}
