/* The path tracer of the diffusion-term integrators (diffusion_path.h) on
 * the shared vertex (surface_vertex.h). */
#include "render/integrators/diffusion_path.h"
#include "render/integrators/bssrdf_vertex.h"
#include "render/integrators/emission.h"

#include <string.h>

/* The vertex at a surface hit: a translucent one (diffusion and single
 * scattering added to *L, the reflection lobe continues) or any other BSDF. */
static int surface_vertex(const ss_scene *scene, ss_diffusion_term_fn term, const void *ctx,
                          const ss_material *m, const ss_hit *hit, ss_vec3 d, ss_rgb beta,
                          ss_rng *rng, ss_rgb *L, ss_vertex *v, ss_path_stats *stats) {
  memset(v, 0, sizeof *v);
  v->p = hit->p;
  v->ng = hit->ng;
  v->d = d;
  v->bsdf = &m->bsdf;
  v->scale = 1.0;
  v->kind = SS_VERTEX_BSDF;
  v->frame = ss_hit_frame(m, hit);
  if (ss_material_is_translucent(m)) {
    if (!(ss_vec3_dot(d, hit->ng) < 0.0)) {
      return 0;
    }
    ss_rgb t = term(ctx, hit, d, stats);
    if (m->bssrdf_single) {
      t = ss_rgb_add(t, ss_single_scatter(scene, m, hit, d, rng, stats));
    }
    *L = ss_rgb_add(*L, ss_rgb_mul(beta, t));
    if (ss_material_is_null(m)) {
      return 0;
    }
    v->kind = SS_VERTEX_REFLECTION;
    v->frame = ss_frame_from_normal(hit->ng);
  }
  v->wo_local = ss_frame_to_local(v->frame, ss_vec3_neg(d));
  return 1;
}

ss_rgb ss_diffusion_path_li(const ss_scene *scene, ss_diffusion_term_fn term, const void *ctx,
                            ss_ray ray, ss_rng *rng, ss_path_stats *stats) {
  ss_rgb L = ss_rgb_gray(0.0);
  ss_path_state s = ss_path_start(ray.o);
  int depth = 0, crossings = 0;
  for (;;) {
    ss_hit hit;
    ss_vec3 d = ss_vec3_normalize(ray.d);
    int found = ss_accel_intersect(scene->accel, &ray, &hit);
    L = ss_rgb_add(L, ss_path_emitted(scene, &s, found ? &hit : NULL, d));
    const ss_material *m = found ? ss_scene_hit_material(scene, &hit) : NULL;
    if (!m) {
      break;
    }
    if (ss_material_is_null(m) && !ss_material_is_translucent(m)) {
      if (!ss_cross_null_interface(&hit, &ray, &crossings, stats)) {
        break;
      }
      continue;
    }
    ss_vertex v;
    if (depth++ >= scene->integrator.max_depth ||
        !surface_vertex(scene, term, ctx, m, &hit, d, s.beta, rng, &L, &v, stats) ||
        !ss_path_advance(scene, &s, &v, depth, &ray, &L, rng, stats)) {
      break;
    }
  }
  return L;
}
