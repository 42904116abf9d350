/* One BSSRDF per translucent material, shared between identical materials
 * (see subsurface.h). */
#include "subsurf/subsurface.h"

#include "subsurf/scene.h"

#include <stdlib.h>
#include <string.h>

struct ss_subsurface {
  size_t num_materials;
  int *index; /* per material: index into `models`, or -1 */
  size_t count;
  ss_bssrdf **models; /* the distinct BSSRDFs */
};

void ss_subsurface_params(const ss_scene *scene, int material, ss_bssrdf_params *p) {
  const ss_material *m = &scene->materials[material];
  const ss_medium *med = &scene->media[m->medium];
  *p = m->bssrdf_options;
  p->medium = med->optics;
  p->eta = m->boundary == SS_BOUNDARY_INDEX_MATCHED ? 1.0 : m->eta;
}

/* Two materials share a BSSRDF when the model, the coefficients and every
 * option set agree. */
static int same_model(const ss_bssrdf *b, const char *name, const ss_bssrdf_params *p) {
  const ss_bssrdf_params *q = ss_bssrdf_get_params(b);
  if (strcmp(ss_bssrdf_name(b), name) || q->eta != p->eta || q->n_options != p->n_options ||
      q->medium.phase != p->medium.phase ||
      memcmp(&q->medium.sigma_s, &p->medium.sigma_s, sizeof p->medium.sigma_s) ||
      memcmp(&q->medium.sigma_a, &p->medium.sigma_a, sizeof p->medium.sigma_a) ||
      memcmp(&q->medium.g, &p->medium.g, sizeof p->medium.g)) {
    return 0;
  }
  for (int k = 0; k < p->n_options; ++k) {
    if (strcmp(q->options[k].name, p->options[k].name) ||
        strcmp(q->options[k].text, p->options[k].text)) {
      return 0;
    }
  }
  return 1;
}

static ss_status add_material(ss_subsurface *s, const ss_scene *scene, int i, ss_error *err) {
  const ss_material *m = &scene->materials[i];
  ss_bssrdf_params p;
  ss_subsurface_params(scene, i, &p);
  for (size_t k = 0; k < s->count; ++k) {
    if (same_model(s->models[k], m->bssrdf, &p)) {
      s->index[i] = (int)k;
      return SS_OK;
    }
  }
  ss_status st = ss_bssrdf_create(m->bssrdf, &p, &s->models[s->count], err);
  if (st != SS_OK) {
    ss_error_prefix(err, "material '%s': ", m->name);
    return st;
  }
  s->index[i] = (int)s->count++;
  return SS_OK;
}

ss_status ss_subsurface_create(const ss_scene *scene, ss_subsurface **out, ss_error *err) {
  *out = NULL;
  ss_subsurface *s = calloc(1, sizeof *s);
  size_t n = scene->num_materials;
  if (s) {
    s->num_materials = n;
    s->index = malloc((n ? n : 1) * sizeof *s->index);
    s->models = calloc(n ? n : 1, sizeof *s->models);
  }
  if (!s || !s->index || !s->models) {
    ss_subsurface_destroy(s);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  for (size_t i = 0; i < n; ++i) {
    const ss_material *m = &scene->materials[i];
    s->index[i] = -1;
    if (m->kind != SS_MATERIAL_INTERFACE || m->medium < 0 || !m->bssrdf[0]) {
      continue;
    }
    ss_status st = add_material(s, scene, (int)i, err);
    if (st != SS_OK) {
      ss_subsurface_destroy(s);
      return st;
    }
  }
  *out = s;
  return SS_OK;
}

void ss_subsurface_destroy(ss_subsurface *s) {
  if (!s) {
    return;
  }
  for (size_t k = 0; k < s->count; ++k) {
    ss_bssrdf_destroy(s->models[k]);
  }
  free(s->models);
  free(s->index);
  free(s);
}

const ss_bssrdf *ss_subsurface_bssrdf(const ss_subsurface *s, int material) {
  if (!s || material < 0 || (size_t)material >= s->num_materials || s->index[material] < 0) {
    return NULL;
  }
  return s->models[s->index[material]];
}

size_t ss_subsurface_count(const ss_subsurface *s) { return s ? s->count : 0; }
