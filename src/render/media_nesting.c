/* Nested and touching media (media_nesting.h): the rules of priorities of
 * Schmidt & Budge 2002, "Simple Nested Dielectrics in Ray Traced Images",
 * checked on the geometry once, for the pairs of shapes whose bounds meet. */
#include "render/media_nesting.h"

#include "render/box_overlaps.h"
#include "render/clique.h"
#include "render/mesh_apart.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int is_region(const ss_scene *s, const ss_shape *sh) {
  return sh->material >= 0 && s->materials[sh->material].kind == SS_MATERIAL_INTERFACE;
}

/* The rules for two different materials whose regions overlap. */
static ss_status check_pair(const ss_scene *s, const ss_shape *a, const ss_shape *b,
                            const char *how, ss_error *err) {
  const ss_material *ma = &s->materials[a->material], *mb = &s->materials[b->material];
  if (ma->priority == mb->priority) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "shapes '%s' (material '%s') and '%s' (material '%s') %s with the same "
                        "priority %d: give the material that fills the overlap a higher "
                        "'priority'",
                        a->name, ma->name, b->name, mb->name, how, ma->priority);
  }
  for (int k = 0; k < 2; ++k) {
    const ss_material *m = k ? mb : ma, *o = k ? ma : mb;
    if (m->boundary == SS_BOUNDARY_INDEX_MATCHED && o->eta != 1.0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "shapes '%s' and '%s' %s, and material '%s' is index-matched (no index "
                          "of its own) against '%s' of eta %g: the interface between them has no "
                          "defined index; give '%s' a \"smooth\" or \"rough\" 'boundary' and an "
                          "'eta'",
                          a->name, b->name, how, m->name, o->name, o->eta, m->name);
    }
  }
  return SS_OK;
}

/* The shapes bounding regions, with their bounds grown by their own
 * tolerance (1e-6 of their size): two shapes within the larger tolerance of
 * each other have boxes that meet. */
typedef struct {
  size_t n, *shape;
  ss_vec3 *lo, *hi;
  double *eps;
} regions;

static void regions_free(regions *r) {
  free(r->shape);
  free(r->lo);
  free(r->hi);
  free(r->eps);
}

static ss_status regions_of(const ss_scene *s, regions *r, ss_error *err) {
  size_t n = s->num_shapes + 1;
  *r = (regions){0, malloc(n * sizeof *r->shape), malloc(n * sizeof *r->lo),
                 malloc(n * sizeof *r->hi), malloc(n * sizeof *r->eps)};
  if (!r->shape || !r->lo || !r->hi || !r->eps) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  for (size_t i = 0; i < s->num_shapes; ++i) {
    if (!is_region(s, &s->shapes[i])) {
      continue;
    }
    ss_vec3 lo, hi;
    ss_mesh_bounds(s->shapes[i].mesh, &lo, &hi);
    double eps = 1e-6 * ss_vec3_length(ss_vec3_sub(hi, lo));
    ss_vec3 e = ss_vec3_make(eps, eps, eps);
    r->shape[r->n] = i;
    r->lo[r->n] = ss_vec3_sub(lo, e);
    r->hi[r->n] = ss_vec3_add(hi, e);
    r->eps[r->n++] = eps;
  }
  return SS_OK;
}

/* Keeps the pairs of regions that touch or nest (dropping those apart),
 * checking each as it goes. */
static ss_status relate(ss_scene *s, const regions *r, ss_box_pair *pairs, size_t *num_pairs,
                        ss_error *err) {
  size_t kept = 0;
  for (size_t p = 0; p < *num_pairs; ++p) {
    const ss_shape *a = &s->shapes[r->shape[pairs[p].i]], *b = &s->shapes[r->shape[pairs[p].j]];
    double eps = fmax(r->eps[pairs[p].i], r->eps[pairs[p].j]);
    ss_mesh_relation rel = ss_mesh_relation_of(a->mesh, b->mesh, eps);
    if (rel == SS_MESHES_UNKNOWN) {
      return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
    }
    if (rel == SS_MESHES_APART) {
      continue;
    }
    const char *how = rel == SS_MESHES_TOUCH ? "touch or cross" : "nest";
    ss_status st;
    if (a->material != b->material && (st = check_pair(s, a, b, how, err)) != SS_OK) {
      return st;
    }
    s->nested_material = a->material;
    pairs[kept++] = pairs[p];
  }
  *num_pairs = kept;
  return SS_OK;
}

/* A point inside several regions lies in each pair of them, so the regions
 * holding a point pairwise overlap: with no SS_MEDIUM_STACK_SIZE + 1 such
 * regions, a path's stack never overflows. */
static ss_status check_depth(const ss_scene *s, const regions *r, const ss_box_pair *pairs,
                             size_t num_pairs, ss_error *err) {
  enum { K = SS_MEDIUM_STACK_SIZE + 1 };
  size_t clique[K];
  int found = ss_clique_find(r->n, pairs, num_pairs, K, clique);
  if (found < 0) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "scene: out of memory");
  }
  if (found == 0) {
    return SS_OK;
  }
  char names[SS_ERROR_MESSAGE_SIZE / 2];
  size_t used = 0;
  for (int k = 0; k < K && used < sizeof names; ++k) {
    int w = snprintf(names + used, sizeof names - used, "%s'%s'", k ? ", " : "",
                     s->shapes[r->shape[clique[k]]].name);
    used += w > 0 ? (size_t)w : 0;
  }
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "shapes %s bound %d media that all nest, touch or cross one another: at "
                      "most %d may overlap",
                      names, K, SS_MEDIUM_STACK_SIZE);
}

static int in_box(ss_vec3 p, ss_vec3 lo, ss_vec3 hi) {
  return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
}

ss_status ss_scene_check_media(ss_scene *s, ss_error *err) {
  s->nested_material = -1;
  s->camera_media.n = 0;
  regions r;
  ss_box_pair *pairs = NULL;
  size_t num_pairs = 0;
  ss_status st = regions_of(s, &r, err);
  if (st == SS_OK) {
    st = ss_box_overlaps(r.lo, r.hi, r.n, &pairs, &num_pairs, err);
  }
  if (st == SS_OK) {
    st = relate(s, &r, pairs, &num_pairs, err);
  }
  if (st == SS_OK) {
    st = check_depth(s, &r, pairs, num_pairs, err);
  }
  free(pairs);
  for (size_t i = 0; i < s->num_materials && st == SS_OK && s->nested_material >= 0; ++i) {
    if (ss_material_varies(&s->materials[i])) {
      st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "material '%s' has a textured 'albedo' or 'mfp', and the media of "
                        "material '%s' touch or nest: a scene with nested media needs "
                        "constant coefficients",
                        s->materials[i].name, s->materials[s->nested_material].name);
    }
  }
  for (size_t k = 0; k < r.n && st == SS_OK && s->nested_material >= 0; ++k) {
    const ss_shape *sh = &s->shapes[r.shape[k]];
    if (!in_box(s->camera.position, r.lo[k], r.hi[k]) ||
        !ss_mesh_contains(sh->mesh, s->camera.position)) {
      continue;
    }
    if (s->camera_media.n == SS_MEDIUM_STACK_SIZE) {
      st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "the camera lies inside more than %d shapes bounding media",
                        SS_MEDIUM_STACK_SIZE);
      break;
    }
    s->camera_media.material[s->camera_media.n++] = sh->material;
  }
  regions_free(&r);
  return st;
}
