/* The path tracer of surfaces whose translucent materials scatter below
 * their surface through a BSSRDF (bssrdf_path.h). */
#include "render/integrators/bssrdf_path.h"

#include "render/integrators/emission.h"
#include "render/integrators/roulette.h"
#include "render/integrators/spectral_mis.h"

#include "subsurf/fresnel.h"
#include "subsurf/fwddip.h"
#include "subsurf/subsurface.h"
#include "subsurf/volume.h"

#include <math.h>
#include <string.h>

/* The path's state; media traced volumetrically (level of detail
 * "volpath") sample distances with the hero channel's extinction and
 * combine the channels by the one-sample balance heuristic (spectral_mis.h,
 * its r_u only: no light sampling inside but through index-matched
 * boundaries, weighted by the power heuristic as on surfaces). */
typedef struct {
  ss_path_state k;
  ss_spectral sp;
  int all_hits; /* option all_hits: every hit of a probe chord is an entry point */
} path;

int ss_bssrdf_path_volumetric(const ss_scene *scene, const ss_material *m) {
  return ss_material_is_translucent(m) &&
         ss_subsurface_lod(scene->subsurface, (int)(m - scene->materials)) == SS_LOD_VOLPATH;
}

/* Free flight along the segment ending at `hit` inside a volumetric medium
 * (material m; volume.h's homogeneous segment): returns 1 and moves the ray
 * on after a scattering event (light sampled through an index-matched
 * boundary, phase sampled), 0 when the segment reaches the hit (weighted by
 * its survival; beta black when the path's density vanished). */
static int free_flight(const ss_scene *scene, const ss_material *m, const ss_hit *hit, ss_ray *ray,
                       path *s, ss_rgb *L, ss_rng *rng, ss_path_stats *stats) {
  const ss_medium *med = &scene->media[m->medium];
  ss_vec3 dn = ss_vec3_normalize(ray->d);
  double tmax = hit->t * ss_vec3_length(ray->d);
  double t = ss_volume_sample_distance(med, dn, s->sp.hero, rng);
  ss_volume_weights w = {&s->k.beta, &s->sp.r_u, &s->sp.r_l};
  int event = ss_volume_segment(med, ray->o, dn, t, tmax, s->sp.hero, rng, w, &t, NULL);
  if (event < 0) {
    s->k.beta = ss_rgb_gray(0.0);
    return 0;
  }
  ss_spectral_renormalise(&s->k.beta, &s->sp);
  if (event == 0) {
    return 0;
  }
  stats->scatter_events++;
  ss_vertex v = {
      .kind = SS_VERTEX_PHASE, .d = dn, .scale = 1.0, .phase = &med->phase, .medium = m->medium};
  v.p = ss_vec3_madd(ray->o, v.d, t);
  /* A straight shadow ray leaves only through an index-matched boundary. */
  s->k.specular = !ss_material_is_null(m);
  if (!s->k.specular) {
    *L = ss_rgb_add(*L, ss_rgb_mul(s->k.beta, ss_vertex_direct(scene, &v, rng, stats)));
  }
  ss_vec3 wi = ss_phase_sample(&med->phase, v.d, ss_rng_uniform(rng), ss_rng_uniform(rng));
  s->k.prev_pdf = ss_phase_eval(&med->phase, ss_vec3_dot(v.d, wi));
  s->k.prev_p = v.p;
  *ray = (ss_ray){v.p, wi, 0.0, INFINITY};
  stats->extension_rays++;
  return 1;
}

/* The exit vertex of a translucent surface: fills v and returns 1 to
 * continue from it, 0 when the path ends; single scattering is added to *L. */
static int exit_vertex(const ss_scene *scene, const ss_material *m, const ss_hit *hit, ss_vec3 d,
                       ss_rng *rng, path *s, ss_rgb *L, ss_vertex *v, ss_path_stats *stats) {
  int mi = (int)(m - scene->materials);
  const ss_bssrdf *b = ss_subsurface_bssrdf(scene->subsurface, mi);
  ss_vec3 w_o = ss_vec3_neg(d);
  double cos_o = ss_vec3_dot(w_o, hit->ng);
  if (!b || !(cos_o > 0.0)) {
    return 0;
  }
  memset(v, 0, sizeof *v);
  v->p = hit->p;
  v->ng = hit->ng;
  v->frame = ss_frame_from_normal(hit->ng);
  v->d = d;
  v->wo_local = ss_frame_to_local(v->frame, w_o);
  double q = ss_material_is_null(m) ? 0.0 : ss_fresnel_dielectric(cos_o, m->eta);
  if (ss_rng_uniform(rng) < q) {
    v->kind = SS_VERTEX_REFLECTION;
    v->bsdf = ss_material_bsdf_at(m, ss_hit_texcoord(hit), &v->local);
    v->scale = 1.0 / q;
    return 1;
  }
  s->k.beta = ss_rgb_scale(s->k.beta, 1.0 / (1.0 - q));
  /* Spatially varying coefficients (textures, a grid's density and axes):
   * the model is built for those at the exit point (as production renderers
   * evaluate them), and the entry point is sampled and weighted with that
   * same model, so the pdf is the one the sample was drawn from. */
  const ss_medium *med = &scene->media[m->medium];
  ss_medium local;
  int varies = ss_material_optics_at(m, med, ss_hit_texcoord(hit), &local);
  if (varies || med->grid) {
    ss_bssrdf_params p = *ss_bssrdf_get_params(b);
    p.single_use = 1;
    p.base = b;
    if (varies) {
      p.medium = local.optics;
    } else if (!ss_subsurface_grid_params(med, hit->p, hit->ng, &p)) {
      return 0; /* no dense matter below x_o */
    }
    if (ss_bssrdf_create(ss_bssrdf_name(b), &p, &v->owned, NULL) != SS_OK) {
      return 0;
    }
    b = v->owned;
  }
  v->bssrdf = b;
  unsigned flags = ss_bssrdf_flags(b);
  if ((flags & SS_BSSRDF_SINGULAR) || m->bssrdf_single) {
    *L = ss_rgb_add(*L, ss_rgb_mul(s->k.beta, ss_single_scatter(scene, m, hit, d, rng, stats)));
  }
  if (flags & SS_BSSRDF_SINGULAR) {
    ss_vertex_release(v);
    return 0;
  }
  v->scale = 1.0;
  if (flags & SS_BSSRDF_BRDF) {
    v->kind = SS_VERTEX_BRDF;
    return 1;
  }
  v->query.x_o = hit->p;
  v->query.n_o = hit->ng;
  v->query.w_o = w_o;
  ss_probe probe;
  ss_probe_init(&probe, scene->accel, hit->geom_id, b, hit->p, v->frame, w_o);
  if (s->all_hits && ss_fwddip_ballistic_fraction(b) == 0.0) {
    v->kind = SS_VERTEX_ENTRY;
    if (!ss_vertex_sample_entries(scene, &probe, hit, s->k.beta, rng, v, L, stats)) {
      ss_vertex_release(v);
      return 0;
    }
    return 1;
  }
  double pdf = ss_vertex_sample_entry(scene, &probe, hit, rng, v, stats);
  if (!(pdf > 0.0)) {
    ss_vertex_release(v);
    return 0;
  }
  v->scale = 1.0 / pdf;
  return 1;
}

static int surface_vertex(const ss_scene *scene, const ss_material *m, const ss_hit *hit, ss_vec3 d,
                          ss_rng *rng, path *s, ss_rgb *L, ss_vertex *v, ss_path_stats *stats) {
  if (ss_material_is_translucent(m) && !ss_bssrdf_path_volumetric(scene, m)) {
    return ss_vec3_dot(d, hit->ng) < 0.0 && exit_vertex(scene, m, hit, d, rng, s, L, v, stats);
  }
  ss_vertex_at_bsdf(v, m, hit, d);
  return 1;
}

/* Roulette on the throughput without refraction's radiance scaling. */
static int roulette(path *s, int depth, const ss_scene *scene, ss_rng *rng) {
  return ss_path_survives(&s->k.beta, ss_rgb_max(s->k.beta) * s->k.eta_scale, depth,
                          scene->integrator.rr_depth, rng);
}

/* The path from `ray` on, after `depth` events; radiance added to L. */
static ss_rgb trace(const ss_scene *scene, path *s, ss_ray ray, int depth, ss_rgb L, ss_rng *rng,
                    ss_path_stats *stats) {
  int crossings = 0;
  const int max_depth = scene->integrator.max_depth;
  for (;;) {
    ss_hit hit;
    ss_vec3 d = ss_vec3_normalize(ray.d);
    if (!ss_accel_intersect(scene->accel, &ray, &hit)) {
      L = ss_rgb_add(L, ss_path_emitted(scene, &s->k, NULL, d));
      break;
    }
    const ss_material *m = ss_scene_hit_material(scene, &hit);
    if (m && ss_bssrdf_path_volumetric(scene, m) && ss_vec3_dot(d, hit.ng) > 0.0) {
      if (free_flight(scene, m, &hit, &ray, s, &L, rng, stats)) {
        if (++depth >= max_depth || !roulette(s, depth, scene, rng)) {
          break;
        }
        continue;
      }
      if (ss_rgb_is_black(s->k.beta)) {
        break;
      }
    }
    L = ss_rgb_add(L, ss_path_emitted(scene, &s->k, &hit, d));
    if (!m) {
      break;
    }
    if (ss_material_is_null(m) &&
        !(ss_material_is_translucent(m) && !ss_bssrdf_path_volumetric(scene, m))) {
      if (!ss_cross_null_interface(&hit, &ray, &crossings, stats)) {
        break;
      }
      continue;
    }
    ss_vertex v;
    if (depth++ >= max_depth || !surface_vertex(scene, m, &hit, d, rng, s, &L, &v, stats) ||
        !ss_path_advance(scene, &s->k, &v, depth, &ray, &L, rng, stats)) {
      break;
    }
  }
  return L;
}

ss_rgb ss_bssrdf_path_li(const ss_scene *scene, int all_hits, ss_ray ray, ss_rng *rng,
                         ss_path_stats *stats) {
  path s = {ss_path_start(ray.o), ss_spectral_start(0.0), all_hits};
  s.sp.hero = ss_volume_uniform_hero(ss_rng_uniform(rng));
  return trace(scene, &s, ray, 0, ss_rgb_gray(0.0), rng, stats);
}

ss_rgb ss_bssrdf_path_continue(const ss_scene *scene, ss_vertex *v, ss_rgb beta, ss_rgb r, int hero,
                               int depth, double eta_scale, ss_rng *rng, ss_path_stats *stats) {
  path s = {{beta, 0, 0.0, v->p, eta_scale}, ss_spectral_start(0.0), SS_BSSRDF_DEFAULT_ALL_HITS};
  s.sp.r_u = r;
  s.sp.hero = hero;
  ss_rgb L = ss_rgb_gray(0.0);
  ss_ray ray;
  if (depth++ >= scene->integrator.max_depth ||
      !ss_path_advance(scene, &s.k, v, depth, &ray, &L, rng, stats)) {
    return L;
  }
  return trace(scene, &s, ray, depth, L, rng, stats);
}
