/* The stack of media of a path (medium_stack.h): Schmidt & Budge 2002,
 * "Simple Nested Dielectrics in Ray Traced Images", sec. 3 (an interface
 * is true only where the region of highest priority changes). */
#include "render/integrators/medium_stack.h"

#include <math.h>

int ss_medium_stack_top(const ss_scene *s, const ss_medium_stack *st) {
  int top = -1;
  for (int k = 0; k < st->n; ++k) {
    int m = st->material[k];
    if (top < 0 || s->materials[m].priority >= s->materials[top].priority) {
      top = m;
    }
  }
  return top;
}

double ss_region_index(const ss_scene *s, int mat) { return mat < 0 ? 1.0 : s->materials[mat].eta; }

int ss_medium_stack_medium(const ss_scene *s, const ss_medium_stack *st) {
  int top = ss_medium_stack_top(s, st);
  return top < 0 ? -1 : s->materials[top].medium;
}

ss_crossing ss_medium_stack_cross(const ss_scene *s, ss_medium_stack *st, int mat, int entering,
                                  double *eta) {
  *eta = 1.0;
  int before = ss_medium_stack_top(s, st);
  if (entering) {
    if (st->n == SS_MEDIUM_STACK_SIZE) {
      return SS_CROSSING_LOST;
    }
    st->material[st->n++] = mat;
  } else {
    int k = st->n - 1;
    while (k >= 0 && st->material[k] != mat) {
      --k;
    }
    if (k < 0) {
      return SS_CROSSING_LOST;
    }
    for (--st->n; k < st->n; ++k) {
      st->material[k] = st->material[k + 1];
    }
  }
  int after = ss_medium_stack_top(s, st);
  if (after == before) {
    return SS_CROSSING_FALSE;
  }
  double n_before = ss_region_index(s, before), n_after = ss_region_index(s, after);
  if (n_before == n_after) {
    return SS_CROSSING_MATCHED;
  }
  /* Entering, the new owner is `mat` (inside); leaving, the old one was. */
  *eta = entering ? n_after / n_before : n_before / n_after;
  return SS_CROSSING_TRUE;
}

const ss_bsdf *ss_interface_bsdf(const ss_material *m, ss_texcoord tc, double eta,
                                 ss_bsdf *scratch) {
  const ss_bsdf *b = ss_material_bsdf_at(m, tc, scratch);
  if (eta == m->eta) {
    return b;
  }
  ss_microfacet mf = b->mf;
  ss_transport_mode mode = b->mode;
  if (m->boundary == SS_BOUNDARY_ROUGH) {
    ss_bsdf_rough_dielectric_init(scratch, eta, &mf, mode, NULL);
  } else {
    ss_bsdf_dielectric_init(scratch, eta, mode, NULL);
  }
  return scratch;
}

/* Beer-Lambert attenuation over `dist` in `med` (NULL: none). */
static ss_rgb attenuate(ss_rgb tr, const ss_medium *med, double dist) {
  for (int c = 0; c < 3 && med; ++c) {
    tr.c[c] *= exp(-med->sigma_t.c[c] * dist);
  }
  return tr;
}

ss_rgb ss_medium_stack_shadow(const ss_scene *scene, ss_vec3 p, ss_vec3 n, ss_medium_stack *st,
                              const ss_light_sample *ls, ss_path_stats *stats) {
  ss_rgb tr = ss_rgb_gray(1.0);
  int finite = isfinite(ls->dist);
  ss_ray ray = finite ? ss_ray_spawn_to(p, n, ls->p, ls->n) : ss_ray_spawn(p, n, ls->wi);
  for (int crossing = 0; crossing < SS_MAX_NULL_CROSSINGS; ++crossing) {
    int medium = ss_medium_stack_medium(scene, st);
    const ss_medium *med = medium >= 0 ? &scene->media[medium] : NULL;
    ss_hit hit;
    stats->shadow_rays++;
    if (!ss_accel_intersect(scene->accel, &ray, &hit)) {
      if (!finite) {
        return st->n ? ss_rgb_gray(0.0) : tr; /* a leak out of a closed mesh: no light */
      }
      return attenuate(tr, med, ss_vec3_length(ss_vec3_sub(ls->p, ray.o)));
    }
    int mat = scene->shapes[hit.geom_id].material;
    if (mat < 0 || scene->materials[mat].kind != SS_MATERIAL_INTERFACE) {
      return ss_rgb_gray(0.0);
    }
    tr = attenuate(tr, med, hit.t * ss_vec3_length(ray.d));
    double eta;
    ss_crossing c = ss_medium_stack_cross(scene, st, mat, ss_vec3_dot(ray.d, hit.ng) < 0.0, &eta);
    if (c == SS_CROSSING_TRUE || c == SS_CROSSING_LOST) {
      return ss_rgb_gray(0.0);
    }
    ray =
        finite ? ss_ray_spawn_to(hit.p, hit.ng, ls->p, ls->n) : ss_ray_spawn(hit.p, hit.ng, ls->wi);
  }
  return ss_rgb_gray(0.0);
}
