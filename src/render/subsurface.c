/* One BSSRDF per translucent material, shared between identical materials
 * (see subsurface.h). */
#include "subsurf/subsurface.h"

#include "subsurf/scene.h"
#include "subsurf/volume.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct ss_subsurface {
  size_t num_materials;
  int *index;  /* per material: index into `models`, or -1 */
  ss_lod *lod; /* per material: the level of detail chosen */
  size_t count;
  ss_bssrdf **models; /* the distinct BSSRDFs; NULL while deferred */
  /* Per distinct BSSRDF: what it is created from, and its first material
   * (for the error message of a deferred creation). */
  const ss_bssrdf_ops **ops;
  ss_bssrdf_params *params;
  int *owner;
  const ss_scene *scene;
  ss_table_cache *tables;
  /* Why the default cache directory could not be used (then the tables
   * stay in memory), "" when it could. */
  char cache_failure[SS_ERROR_MESSAGE_SIZE];
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
static int same_model(const ss_bssrdf_ops *ops, const ss_bssrdf_params *q, const char *name,
                      const ss_bssrdf_params *p) {
  if (strcmp(ops->name, name) || q->eta != p->eta || q->n_options != p->n_options ||
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

double ss_subsurface_size_ratio(const ss_scene *scene, int material) {
  const ss_material *m = &scene->materials[material];
  double size = INFINITY, sigma = INFINITY;
  for (size_t k = 0; k < scene->num_shapes; ++k) {
    if (scene->shapes[k].material == material) {
      ss_vec3 lo, hi;
      ss_mesh_bounds(scene->shapes[k].mesh, &lo, &hi);
      size = fmin(size, fmin(hi.x - lo.x, fmin(hi.y - lo.y, hi.z - lo.z)));
    }
  }
  const ss_medium_optics *o = &scene->media[m->medium].optics;
  for (int c = 0; c < 3; ++c) {
    sigma = fmin(sigma, (1.0 - o->g.c[c]) * o->sigma_s.c[c] + o->sigma_a.c[c]);
  }
  return isfinite(size) ? size * sigma : 0.0;
}

static ss_lod choose_lod(const ss_scene *scene, int i) {
  ss_lod lod = scene->materials[i].lod;
  if (lod != SS_LOD_AUTO) {
    return lod;
  }
  double n = ss_subsurface_size_ratio(scene, i);
  return n < SS_LOD_VOLPATH_BELOW ? SS_LOD_VOLPATH
         : n > SS_LOD_BRDF_ABOVE  ? SS_LOD_BRDF
                                  : SS_LOD_BSSRDF;
}

/* The model standing for material i at its level of detail. */
static const char *model_name(const ss_material *m, ss_lod lod) {
  if (lod == SS_LOD_BRDF) {
    return SS_LOD_BRDF_MODEL;
  }
  return m->bssrdf[0] ? m->bssrdf : SS_LOD_DEFAULT_MODEL;
}

static ss_status build_model(ss_subsurface *s, size_t k, ss_error *err) {
  return ss_bssrdf_create_ops(s->ops[k], &s->params[k], &s->models[k], err);
}

static ss_status add_material(ss_subsurface *s, const ss_scene *scene, int i, ss_error *err) {
  const ss_material *m = &scene->materials[i];
  int volume = ss_medium_is_volume(&scene->media[m->medium]);
  /* Oriented or gridded media: volpath's walk, or a model that takes
   * micro-flakes (aniso-dipole by default); never the BRDF level. */
  if (volume) {
    s->lod[i] = m->lod == SS_LOD_VOLPATH ? SS_LOD_VOLPATH : SS_LOD_BSSRDF;
  } else {
    s->lod[i] = choose_lod(scene, i);
  }
  if (s->lod[i] == SS_LOD_VOLPATH) {
    return SS_OK;
  }
  const char *name = volume && !m->bssrdf[0] ? SS_VOLUME_MODEL : model_name(m, s->lod[i]);
  const ss_bssrdf_ops *ops = ss_bssrdf_model_find(name);
  if (ss_material_varies(m) && ops && (ops->flags & SS_BSSRDF_TABULATED)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "material '%s': a textured albedo or mfp builds the BSSRDF at every exit "
                        "point, and model '%s' tabulates (too slow for that): choose an analytic "
                        "model (e.g. dipole, better-dipole, burley) or lod \"volpath\"",
                        m->name, name);
  }
  ss_bssrdf_params p;
  ss_subsurface_params(scene, i, &p);
  p.tables = s->tables;
  if (strcmp(name, m->bssrdf)) {
    ss_bssrdf_params_clear_options(&p); /* options of the named model only */
  }
  if (!ops) {
    ss_status st = ss_bssrdf_create(name, &p, &s->models[s->count], err); /* names the models */
    ss_error_prefix(err, "material '%s': ", m->name);
    return st;
  }
  for (size_t k = 0; k < s->count; ++k) {
    if (same_model(s->ops[k], &s->params[k], name, &p)) {
      s->index[i] = (int)k;
      return SS_OK;
    }
  }
  size_t k = s->count;
  s->ops[k] = ops;
  s->params[k] = p;
  s->owner[k] = i;
  /* The anisotropic dipole of a flake or grid medium takes 40-85 ms to
   * build its flake tables: only the integrators that use a BSSRDF build it
   * (ss_subsurface_build), not a volpath render. */
  ss_status st = volume ? ss_bssrdf_check(ops, &p, err) : build_model(s, k, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "material '%s': ", m->name);
    return st;
  }
  s->index[i] = (int)s->count++;
  return SS_OK;
}

ss_status ss_subsurface_build(ss_subsurface *s, ss_error *err) {
  for (size_t k = 0; s && k < s->count; ++k) {
    if (!s->models[k]) {
      ss_status st = build_model(s, k, err);
      if (st != SS_OK) {
        ss_error_prefix(err, "material '%s': ", s->scene->materials[s->owner[k]].name);
        return st;
      }
    }
  }
  return SS_OK;
}

int ss_subsurface_built(const ss_subsurface *s, int material) {
  return s && material >= 0 && (size_t)material < s->num_materials && s->index[material] >= 0 &&
         s->models[s->index[material]] != NULL;
}

ss_status ss_subsurface_create(const ss_scene *scene, ss_subsurface **out, ss_error *err) {
  *out = NULL;
  ss_subsurface *s = calloc(1, sizeof *s);
  size_t n = scene->num_materials;
  if (s) {
    s->num_materials = n;
    s->index = malloc((n ? n : 1) * sizeof *s->index);
    s->lod = malloc((n ? n : 1) * sizeof *s->lod);
    s->models = calloc(n ? n : 1, sizeof *s->models);
    s->ops = calloc(n ? n : 1, sizeof *s->ops);
    s->params = calloc(n ? n : 1, sizeof *s->params);
    s->owner = calloc(n ? n : 1, sizeof *s->owner);
    s->scene = scene;
  }
  if (!s || !s->index || !s->lod || !s->models || !s->ops || !s->params || !s->owner) {
    ss_subsurface_destroy(s);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  char dir[SS_PATH_SIZE];
  ss_subsurface_cache_dir(scene, dir, sizeof dir);
  ss_status cst = ss_table_cache_create(dir, &s->tables, err);
  if (cst != SS_OK && !scene->render.table_cache_dir[0]) {
    /* A default directory that cannot be made must not stop the render. */
    snprintf(s->cache_failure, sizeof s->cache_failure, "%s", err->message);
    cst = ss_table_cache_create(NULL, &s->tables, err);
  }
  if (cst != SS_OK) {
    ss_error_prefix(err, "render.table_cache: ");
    ss_subsurface_destroy(s);
    return cst;
  }
  for (size_t i = 0; i < n; ++i) {
    const ss_material *m = &scene->materials[i];
    s->index[i] = -1;
    s->lod[i] = SS_LOD_BSSRDF;
    if (m->kind != SS_MATERIAL_INTERFACE || m->medium < 0) {
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
  free(s->ops);
  free(s->params);
  free(s->owner);
  ss_table_cache_destroy(s->tables);
  free(s->index);
  free(s->lod);
  free(s);
}

const ss_bssrdf *ss_subsurface_bssrdf(const ss_subsurface *s, int material) {
  if (!ss_subsurface_built(s, material)) {
    return NULL;
  }
  return s->models[s->index[material]];
}

ss_lod ss_subsurface_lod(const ss_subsurface *s, int material) {
  if (!s || material < 0 || (size_t)material >= s->num_materials) {
    return SS_LOD_BSSRDF;
  }
  return s->lod[material];
}

size_t ss_subsurface_count(const ss_subsurface *s) { return s ? s->count : 0; }

void ss_subsurface_table_stats(const ss_subsurface *s, ss_table_cache_stats *stats) {
  memset(stats, 0, sizeof *stats);
  if (s && s->tables) {
    ss_table_cache_get_stats(s->tables, stats);
  }
  if (s && s->cache_failure[0]) {
    stats->write_failures++;
    snprintf(stats->last_failure, sizeof stats->last_failure, "%s", s->cache_failure);
  }
}

void ss_subsurface_cache_dir(const ss_scene *scene, char *buf, size_t size) {
  const char *env = getenv("SUBSURF_TABLE_CACHE");
  if (!scene->render.table_cache) {
    snprintf(buf, size, "%s", "");
  } else if (scene->render.table_cache_dir[0]) {
    snprintf(buf, size, "%s", scene->render.table_cache_dir);
  } else if (env && env[0]) {
    snprintf(buf, size, "%s", strcmp(env, "off") ? env : "");
  } else {
    ss_table_cache_user_dir(buf, size);
  }
}
