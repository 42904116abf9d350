/* The volumetric random walk (medium_walk.h), the ground truth of
 * `volpath` and the walk of `hybrid`.
 *
 * Media bounded by closed meshes. When they are apart (no medium touches or
 * contains another), the medium a ray segment travels through is known
 * after a scattering event or a surface event (the side of the interface
 * the ray leaves into), and otherwise read from the surface that ends it (a
 * ray that hits an interface from the inside was inside its medium). A
 * known medium's segment samples its distance first and traces only that
 * far; a surface found there must agree with the medium (else the path ends
 * as a leak), so tracking cannot drift out of sync with the geometry and
 * needs no medium stack. Nested or touching media (the scene's
 * nested_material) are followed by a stack of the regions the path is in
 * (medium_stack.h, SchmidtBudge2002): only a change of the owning region
 * is a surface event.
 *
 * Chromatic media: free-flight distances are sampled with the extinction of
 * one hero channel chosen per path and the channels combined by spectral
 * MIS (spectral_mis.h). Free flights have no absorption events: a
 * scattering vertex weighs the path by sigma_s T / (sigma_t[h] T[h]), so
 * every channel stays unbiased.
 *
 * Next-event estimation from medium and surface vertices goes through
 * index-matched interfaces with the exact Beer-Lambert transmittance of the
 * media crossed (a straight shadow ray cannot pass a refracting interface:
 * lights sit outside the closed meshes); behind a smooth dielectric
 * boundary medium vertices connect to lights by manifold next-event
 * estimation when the strategy switches it on (mnee.h); rough boundaries
 * take light samples at the boundary vertex. In a scene lit by one delta
 * light the walk may be guided toward it (guided_walk.h). A translucent
 * material whose coefficients vary over its surface (textures) fills its
 * interior with those of the point where the path entered. Russian
 * roulette acts on the MIS-weighted throughput without the eta^2 radiance
 * scaling of refraction (pbrt-v4). */
#include "render/integrators/medium_walk.h"

#include "render/integrators/emission.h"
#include "render/integrators/medium_stack.h"
#include "render/integrators/roulette.h"
#include "render/integrators/shadow_tracking.h"
#include "render/integrators/surface_vertex.h"
#include "subsurf/volume.h"

#include <math.h>

typedef struct {
  ss_path_state k; /* beta, specular, eta_scale, prev_p (the last scattering vertex) */
  ss_spectral sp;
  /* A translucent material whose coefficients vary over its surface
   * (textures): the medium inside takes those of the point where
   * the path entered (an approximation: the interior is homogeneous along
   * each visit, docs/textures.md). */
  int entered; /* 1 when `entry_medium` holds them */
  ss_medium entry_medium;
  /* Manifold next-event estimation (mnee.h): the last vertex was a medium
   * vertex behind a smooth boundary (mnee_from), and the path has since
   * only refracted, out of it or (nested media) through a chain of true
   * interfaces (mnee_armed, the refractions in `mnee`), so an area light it
   * hits next is one MNEE samples too. */
  int mnee_from, mnee_armed;
  ss_mnee_refractions mnee;
  /* Nested media (medium_stack.h), when the scene's media overlap: the
   * regions the path is in, and those beyond the surface it is at. */
  int nested;
  ss_medium_stack media, beyond;
  /* The segment from the last medium vertex was sampled by the guided
   * mixture (guided_walk.h, the `guide` option). */
  int guiding;
  ss_guided_segment seg;
} path;

/* Nested media: the medium and the material of the region owning the path. */
static void region(const ss_scene *scene, const path *s, int *inside,
                   const ss_material **boundary) {
  int top = ss_medium_stack_top(scene, &s->media);
  *boundary = top >= 0 ? &scene->materials[top] : NULL;
  *inside = top >= 0 ? scene->materials[top].medium : -1;
}

/* Nested media: the regions a shadow ray along wi leaves into from a medium
 * vertex, or from a surface vertex (material m, normal n, reached along d):
 * those beyond it when the ray leaves through the surface. */
static const ss_medium_stack *shadow_media(const path *s, const ss_material *m, ss_vec3 d,
                                           ss_vec3 n, ss_vec3 wi) {
  int through = m && (ss_vec3_dot(wi, n) > 0.0) == (ss_vec3_dot(d, n) > 0.0);
  return through ? &s->beyond : &s->media;
}

/* Called when the path crosses `hit` of material m along d: entering a
 * spatially varying material records its entry-point coefficients. */
static void cross(const ss_scene *scene, path *s, const ss_material *m, const ss_hit *hit,
                  ss_vec3 d) {
  if (m->medium >= 0 && ss_vec3_dot(d, hit->ng) < 0.0) {
    s->entered =
        ss_material_optics_at(m, &scene->media[m->medium], ss_hit_texcoord(hit), &s->entry_medium);
  }
}

/* The coefficients of medium `medium` (the interior of material m) for this path. */
static const ss_medium *path_medium(const ss_scene *scene, const path *s, const ss_material *m,
                                    int medium) {
  return s->entered && ss_material_varies(m) ? &s->entry_medium : &scene->media[medium];
}

/* Next-event estimation from p. `f` is the scattering function (phase
 * function or BSDF x |cos|) toward the sampled direction and p_dir its
 * sampling density; evaluated through the callback-free pair below. */
typedef struct {
  const ss_medium *med; /* medium vertex (at point q), or NULL */
  ss_volume_point q;
  const ss_bsdf *bsdf; /* surface vertex */
  ss_frame frame;
  ss_vec3 wo_local;
  ss_vec3 d; /* propagation direction arriving at the vertex */
} vertex;

static void scattering(const vertex *v, ss_vec3 wi, ss_rgb *f, double *p_dir) {
  if (v->med) {
    double ph = ss_volume_phase_eval(v->med, &v->q, v->d, wi);
    *f = ss_rgb_gray(ph);
    *p_dir = ph;
    return;
  }
  ss_vec3 wi_local = ss_frame_to_local(v->frame, wi);
  *f = ss_rgb_scale(ss_rgb_from_vec3(ss_bsdf_eval(v->bsdf, v->wo_local, wi_local)),
                    fabs(wi_local.z));
  *p_dir = ss_bsdf_pdf(v->bsdf, v->wo_local, wi_local);
}

/* `med`: the coefficients of the medium around a medium vertex; for a
 * surface vertex (hit, material m) the medium is the one on the side the
 * shadow ray leaves toward, with the hit's coefficients when they vary. */
static ss_rgb next_event(const ss_scene *scene, const path *s, const vertex *v, ss_vec3 p,
                         ss_vec3 n, const ss_medium *med, const ss_material *m, const ss_hit *hit,
                         ss_rng *rng, ss_path_stats *stats) {
  double pmf;
  int li = ss_pick_light(scene, ss_rng_uniform(rng), &pmf);
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_light_sample ls;
  if (li < 0 || !ss_light_sample_li(&scene->lights[li], p, u1, u2, &ls)) {
    return ss_rgb_gray(0.0);
  }
  ss_rgb f;
  double p_dir;
  scattering(v, ls.wi, &f, &p_dir);
  if (ss_rgb_is_black(f) || ss_rgb_is_black(ls.li)) {
    return ss_rgb_gray(0.0);
  }
  ss_medium local;
  if (m) {
    /* Leaving a surface vertex: the shadow ray starts in the medium on the
     * side it leaves toward. */
    int inward = ss_vec3_dot(ls.wi, n) < 0.0 && m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0;
    med = inward ? &scene->media[m->medium] : NULL;
    if (inward && ss_material_optics_at(m, med, ss_hit_texcoord(hit), &local)) {
      med = &local;
    }
  }
  ss_rgb a_l = ss_rgb_gray(1.0);
  ss_tracking tk = {s->sp.hero, rng, &a_l};
  ss_rgb tr;
  if (s->nested) {
    ss_medium_stack st = *shadow_media(s, m, v->d, n, ls.wi);
    tr = ss_medium_stack_shadow(scene, p, n, &st, &ls, stats);
  } else if (ls.delta && !m && med && !ss_medium_is_volume(med)) {
    /* No MIS weight depends on the transmittance of a delta light's sample,
     * so an unbiased estimate of it may stand in (shadow_tracking.h). */
    tr = ss_shadow_transmittance_sampled(scene, p, med, &ls, SS_SHADOW_TRACKING_RATE, &tk, stats);
  } else {
    tr = ss_shadow_transmittance_tracked(scene, p, n, med, &ls, 1, &tk, stats);
  }
  if (ss_rgb_is_black(tr)) {
    return tr;
  }
  ss_rgb contrib = ss_rgb_mul(ss_rgb_mul(s->k.beta, f), ss_rgb_mul(tr, ls.li));
  if (ls.delta) {
    return ss_rgb_scale(contrib, 1.0 / (pmf * ss_rgb_average(ss_rgb_mul(s->sp.r_u, a_l))));
  }
  double p_light = pmf * ls.pdf;
  /* p_i^nee / p_h^nee = r_u[i] a_l[i]; p_i^uni / p_h^nee = r_u[i] p_dir T_i / p_light
   * (a_l = 1 unless ratio tracking crossed a grid, volume.h). */
  ss_rgb denom;
  for (int c = 0; c < 3; ++c) {
    denom.c[c] = s->sp.r_u.c[c] * (a_l.c[c] + p_dir * tr.c[c] / p_light);
  }
  return ss_rgb_scale(contrib, 1.0 / (p_light * ss_rgb_average(denom)));
}

/* Roulette on the MIS-weighted throughput without refraction's radiance
 * scaling. */
static int roulette(path *s, int depth, int rr_depth, ss_rng *rng) {
  double rr = ss_rgb_max(s->k.beta) * s->k.eta_scale / ss_rgb_average(s->sp.r_u);
  return ss_path_survives(&s->k.beta, rr, depth, rr_depth, rng);
}

/* The medium the segment ending at `hit` runs through (-1: none). */
static int segment_medium(const ss_material *m, ss_vec3 d, const ss_hit *hit) {
  if (m && m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0 && ss_vec3_dot(d, hit->ng) > 0.0) {
    return m->medium;
  }
  return -1;
}

/* The medium a ray leaving the surface of `hit` in direction w enters (-1:
 * none): the interface's medium when w points inside the closed mesh. */
static int side_medium(const ss_material *m, ss_vec3 w, const ss_hit *hit) {
  return m->kind == SS_MATERIAL_INTERFACE && ss_vec3_dot(w, hit->ng) < 0.0 ? m->medium : -1;
}

/* A walk: the path, its ray and where it is. */
typedef struct {
  const ss_scene *scene;
  const ss_walk_parts *parts;
  path s;
  ss_ray ray;
  int depth, crossings;
  /* The medium the ray starts in when known (-1: unknown or none), and the
   * material of the boundary that encloses it. */
  int inside;
  const ss_material *boundary;
  ss_rgb L;
  ss_rng *rng;
  ss_path_stats *stats;
} walk;

/* One segment of the walk. `crossing` is the distance-only record
 * (accel.h) and `hit` the one the surface needs (completed unless
 * distance_suffices). Index-matched crossings continue from `crossing`
 * whichever record was needed, so a walk does not depend on it (the hybrid
 * at infinite depth is volpath, bit for bit, and a spatially varying
 * material equals its homogeneous counterpart). */
typedef struct {
  ss_hit hit, crossing;
  int found;
  int medium; /* the medium the segment runs through (-1: none) */
  double t;   /* its sampled free flight */
  double tmax;
  const ss_material *m; /* the material of the surface that ends it */
} segment;

/* 1 when crossing the surface of `hit` (material m) needs only its
 * distance-only record (accel.h): an index-matched boundary of constant
 * coefficients that emits nothing, outside nested media and when no
 * strategy reacts to the entries into media. */
static int distance_suffices(const walk *w, const ss_material *m, const ss_hit *hit) {
  return !w->parts->reaction && !w->s.nested && m && ss_material_is_null(m) &&
         !ss_material_varies(m) && w->scene->shapes[hit->geom_id].light < 0;
}

/* The strategy's reaction to the path entering the medium `w->inside`
 * behind the surface of `hit` (material m); 1 when it ends the walk. */
static int react_entered(walk *w, const ss_material *m, const ss_hit *hit) {
  const ss_walk_reaction *r = w->parts->reaction;
  if (!r || !r->entered) {
    return 0;
  }
  ss_walk_view view = {&w->s.k, &w->s.sp, w->depth};
  const ss_medium *med = path_medium(w->scene, &w->s, m, w->inside);
  return r->entered(r->ctx, &view, m, med, hit, &w->L, w->rng, w->stats);
}

/* Traces the segment from the walk's ray: a segment known to run through a
 * medium samples its free flight first. Returns 0 when the path ends (a
 * leak out of a closed mesh). */
static int trace_segment(walk *w, segment *g) {
  const ss_scene *scene = w->scene;
  path *s = &w->s;
  ss_ray *ray = &w->ray;
  ss_rng *rng = w->rng;
  g->t = INFINITY;
  g->tmax = INFINITY;
  if (w->inside >= 0) {
    /* Distance first: a segment known to run through a medium samples its
     * free flight before tracing, and the query stops there, so that a
     * segment ending in a scattering event (most of them) finds no surface
     * and traverses only the part of the BVH its short span overlaps. */
    double dl = ss_vec3_length(ray->d);
    const ss_medium *med = path_medium(scene, s, w->boundary, w->inside);
    ss_spectral_choose_hero(&s->sp, med);
    g->t = s->guiding ? ss_guided_sample_distance(&s->seg, med->sigma_t, s->sp.hero, rng)
                      : ss_volume_sample_distance(med, ss_vec3_normalize(ray->d), s->sp.hero, rng);
    ss_ray span = *ray;
    span.tmax = fmin(ray->tmax, g->t / dl);
    g->found = ss_accel_intersect_distance(scene->accel, &span, &g->crossing);
    if (g->found) {
      g->hit = g->crossing;
    }
    g->m = g->found ? ss_scene_hit_material(scene, &g->hit) : w->boundary;
    if (g->found && !s->nested && segment_medium(g->m, ray->d, &g->hit) != w->inside) {
      return 0; /* a leak out of the closed mesh: the path ends */
    }
    if (g->found && !distance_suffices(w, g->m, &g->hit)) {
      ss_accel_hit_complete(scene->accel, &g->hit);
    }
    g->medium = w->inside;
    g->tmax = g->found ? g->hit.t * dl : INFINITY;
  } else {
    g->found = ss_accel_intersect_distance(scene->accel, ray, &g->crossing);
    if (g->found) {
      g->hit = g->crossing;
    }
    g->m = g->found ? ss_scene_hit_material(scene, &g->hit) : NULL;
    if (g->found && !distance_suffices(w, g->m, &g->hit)) {
      ss_accel_hit_complete(scene->accel, &g->hit);
    }
    g->medium = g->found && !s->nested ? segment_medium(g->m, ray->d, &g->crossing) : -1;
    if (g->medium >= 0) {
      g->tmax = g->hit.t * ss_vec3_length(ray->d);
      ss_spectral_choose_hero(&s->sp, path_medium(scene, s, g->m, g->medium));
      g->t = ss_volume_sample_distance(path_medium(scene, s, g->m, g->medium),
                                       ss_vec3_normalize(ray->d), s->sp.hero, rng);
    }
  }
  return 1;
}

/* The vertex of a scattering event at p in the medium `medium` of
 * coefficients med (behind material m), reached along dn: light sampled
 * through an index-matched boundary and by MNEE through a smooth one, the
 * next direction by phase sampling or the guided mixture, roulette.
 * Returns 0 when the path ends. */
static int medium_vertex(walk *w, const ss_material *m, int medium, const ss_medium *med, ss_vec3 p,
                         ss_vec3 dn) {
  const ss_scene *scene = w->scene;
  path *s = &w->s;
  ss_rng *rng = w->rng;
  ss_path_stats *stats = w->stats;
  const ss_mnee_options *mnee = w->parts->mnee;
  const ss_guide *guide = w->parts->guide;
  vertex v = {.med = med, .q = ss_volume_at(med, p), .d = dn};
  ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
  /* Light outside a refracting boundary cannot be reached by a straight
   * shadow ray: only index-matched media take light samples inside;
   * behind a smooth boundary MNEE connects through it (mnee.h). */
  if (s->nested ? m->eta == 1.0 : ss_material_is_null(m)) {
    w->L = ss_rgb_add(w->L, next_event(scene, s, &v, p, zero, med, NULL, NULL, rng, stats));
  }
  /* MNEE takes homogeneous media without flakes (its phase and
   * Beer-Lambert); oriented and gridded media keep phase sampling. In
   * nested media the straight line toward the light decides whether it
   * reaches the light through one or two refractions (mnee.h). A scene lit
   * by its environment alone has nothing to solve for. */
  s->mnee_from = mnee->enabled && (s->nested || ss_mnee_interface(m)) &&
                 !ss_medium_is_volume(med) && ss_mnee_light_count(scene) > 0;
  s->mnee_armed = 0;
  if (s->mnee_from) {
    ss_mnee_vertex mv = {s->k.beta, s->sp.r_u, p, v.d, med, s->nested ? &s->media : NULL};
    w->L = ss_rgb_add(w->L, ss_mnee_next_event(scene, mnee, &mv, rng, stats));
    s->mnee.x0 = p;
    s->mnee.media = s->media;
    s->mnee.k = 0;
  }
  /* Guided walks: homogeneous media of the scene's own coefficients (the
   * mixture's weights need sigma_t per channel and kappa). */
  s->guiding = guide && guide->q > 0.0 && !s->nested && !ss_medium_is_volume(med) &&
               med == &scene->media[medium];
  ss_vec3 wi;
  if (s->guiding) {
    /* The segment's weights carry the phase function over the mixture's
     * density of direction and distance, and r_l the unidirectional
     * density of both (guided_walk.h). */
    wi = ss_guided_sample_direction(guide, med, &v.q, v.d, ss_guide_direction(guide, p),
                                    guide->kappa[medium], s->sp.hero, rng, &s->seg);
    s->sp.r_l = s->sp.r_u;
  } else {
    wi = ss_volume_phase_sample(med, &v.q, v.d, rng);
    double p_dir = ss_volume_phase_eval(med, &v.q, v.d, wi);
    /* Exact phase sampling: f / p = 1, beta is unchanged. */
    s->sp.r_l = ss_rgb_scale(s->sp.r_u, 1.0 / p_dir);
  }
  s->k.specular = 0;
  s->k.prev_p = p;
  w->inside = medium;
  w->boundary = m;
  w->ray = (ss_ray){p, wi, 0.0, INFINITY};
  stats->extension_rays++;
  return roulette(s, w->depth, scene->integrator.rr_depth, rng);
}

/* The medium event that ends a segment g through a medium: a real
 * scattering event (volume.h; its vertex taken and the ray moved on: 1),
 * the surface reached (0), or the end of the path (-1, also when the
 * strategy's reaction to the scattering ends the walk). */
static int medium_event(walk *w, segment *g) {
  if (g->medium < 0) {
    return 0;
  }
  path *s = &w->s;
  const ss_guide *guide = w->parts->guide;
  const ss_medium *med = path_medium(w->scene, s, g->m, g->medium);
  ss_vec3 dn = ss_vec3_normalize(w->ray.d);
  ss_volume_weights wt = {&s->k.beta, &s->sp.r_u, &s->sp.r_l};
  int event = s->guiding
                  ? ss_guided_segment_weights(&s->seg, guide->q, med->sigma_t, med->optics.sigma_s,
                                              g->t, g->tmax, s->sp.hero, wt, &g->t)
                  : ss_volume_segment(med, w->ray.o, dn, g->t, g->tmax, s->sp.hero, w->rng, wt,
                                      &g->t, NULL);
  s->guiding = 0;
  if (event <= 0) {
    return event;
  }
  w->stats->scatter_events++;
  if (++w->depth >= w->scene->integrator.max_depth) {
    return -1;
  }
  ss_spectral_renormalise(&s->k.beta, &s->sp);
  ss_vec3 p = ss_vec3_madd(w->ray.o, dn, g->t);
  const ss_walk_reaction *r = w->parts->reaction;
  ss_walk_view view = {&s->k, &s->sp, w->depth};
  if (r && r->scattered && r->scattered(r->ctx, &view, p, &w->L, w->rng, w->stats)) {
    return -1;
  }
  return medium_vertex(w, g->m, g->medium, med, p, dn) ? 1 : -1;
}

/* The BSDF vertex at the surface that ends segment g (eta: n_inside /
 * n_outside across it, medium_stack.h): light sampling, BSDF sampling, the
 * MNEE chain's bookkeeping, the medium entered, roulette. Returns 0 when the
 * path ends. */
static int bsdf_vertex(walk *w, segment *g, double eta) {
  const ss_scene *scene = w->scene;
  path *s = &w->s;
  ss_ray *ray = &w->ray;
  ss_rng *rng = w->rng;
  ss_path_stats *stats = w->stats;
  if (w->depth++ >= scene->integrator.max_depth) {
    return 0;
  }
  vertex v;
  ss_bsdf local;
  v.med = NULL;
  v.bsdf = s->nested && g->m->kind == SS_MATERIAL_INTERFACE
               ? ss_interface_bsdf(g->m, ss_hit_texcoord(&g->hit), eta, &local)
               : ss_material_bsdf_at(g->m, ss_hit_texcoord(&g->hit), &local);
  v.frame = ss_hit_frame(g->m, &g->hit);
  v.d = ray->d;
  v.wo_local = ss_frame_to_local(v.frame, ss_vec3_neg(ss_vec3_normalize(ray->d)));
  if (!(v.bsdf->lobes & SS_BSDF_DELTA)) {
    ss_spectral_choose_hero(&s->sp, NULL); /* its shadow ray may track a medium */
    w->L = ss_rgb_add(
        w->L, next_event(scene, s, &v, g->hit.p, g->hit.ng, NULL, g->m, &g->hit, rng, stats));
  }
  ss_bsdf_sample bs;
  ss_vec3 wi;
  if (!ss_sample_surface(v.bsdf, v.frame, v.wo_local, ray->d, g->hit.ng, rng, &bs, &wi)) {
    return 0;
  }
  s->k.beta = ss_rgb_mul(s->k.beta, ss_rgb_scale(ss_rgb_from_vec3(bs.f), fabs(bs.wi.z) / bs.pdf));
  /* Refracted out of a smooth boundary straight from a medium vertex (in
   * nested media: through a true interface, the first or second since
   * it): the density stays that of the medium vertex's direction (MNEE's
   * MIS). */
  int refracted = bs.lobe == (SS_BSDF_TRANSMISSION | SS_BSDF_DELTA);
  int enters = ss_vec3_dot(ray->d, g->hit.ng) < 0.0;
  s->mnee_armed = s->nested ? refracted && (s->mnee_from ||
                                            (s->mnee_armed && s->mnee.k < SS_MANIFOLD_MAX_CHAIN))
                            : refracted && s->mnee_from && ss_vec3_dot(wi, g->hit.ng) > 0.0;
  s->mnee_from = 0;
  if (s->mnee_armed) {
    /* eta: n_inside / n_outside across the surface (medium_stack.h). */
    s->mnee.z[s->mnee.k] = g->hit;
    s->mnee.eta[s->mnee.k] = enters ? 1.0 / eta : eta;
    s->mnee.enters[s->mnee.k] = enters;
    s->mnee.k++;
  }
  s->sp.r_l = ss_rgb_scale(s->mnee_armed ? s->sp.r_l : s->sp.r_u, 1.0 / bs.pdf);
  s->k.specular = (bs.lobe & SS_BSDF_DELTA) != 0;
  if (bs.lobe & SS_BSDF_TRANSMISSION) {
    ss_path_refract(&s->k.eta_scale, bs.eta);
  }
  s->k.prev_p = g->hit.p;
  w->inside = side_medium(g->m, wi, &g->hit);
  w->boundary = g->m;
  if (s->nested) {
    s->media = bs.lobe & SS_BSDF_TRANSMISSION ? s->beyond : s->media;
    region(scene, s, &w->inside, &w->boundary);
  }
  if (bs.lobe & SS_BSDF_TRANSMISSION) {
    cross(scene, s, g->m, &g->hit, wi);
  }
  if (w->inside >= 0 && react_entered(w, g->m, &g->hit)) {
    return 0;
  }
  *ray = ss_ray_spawn(g->hit.p, g->hit.ng, wi);
  stats->extension_rays++;
  if (!roulette(s, w->depth, scene->integrator.rr_depth, rng)) {
    return 0;
  }
  return 1;
}

/* The surface that ends the segment g (or the escape): emission, crossings
 * of index-matched boundaries and of nested media's regions, else the BSDF
 * vertex. Returns 0 when the path ends. */
static int surface_event(walk *w, segment *g) {
  const ss_scene *scene = w->scene;
  path *s = &w->s;
  ss_ray *ray = &w->ray;
  ss_path_stats *stats = w->stats;
  const ss_mnee_options *mnee = w->parts->mnee;
  /* Emission found, MIS-weighted unless the last vertex sampled a delta
   * lobe; after a refraction chain from a medium vertex (mnee_armed) with
   * the density MNEE would have had. */
  double p_light = 0.0;
  ss_rgb le = ss_emission_found(scene, g->found ? &g->hit : NULL, ss_vec3_normalize(ray->d),
                                s->k.prev_p, &p_light);
  if (!ss_rgb_is_black(le)) {
    int armed = g->found && s->mnee_armed;
    if (armed) {
      const ss_light *l = &scene->lights[scene->shapes[g->hit.geom_id].light];
      p_light = ss_mnee_light_pdf(scene, mnee, l, &s->mnee, s->nested, &g->hit, stats);
    }
    w->L = ss_rgb_add(w->L,
                      ss_spectral_emitted(s->k.beta, &s->sp, le, p_light, armed || !s->k.specular));
  }
  if (!g->found) {
    return 0;
  }
  if (!g->m) {
    return 0;
  }
  double eta = g->m->eta;
  if (s->nested) {
    /* Schmidt & Budge 2002: only a change of the owning region is an event. */
    s->beyond = s->media;
    ss_crossing c = SS_CROSSING_TRUE;
    if (g->m->kind == SS_MATERIAL_INTERFACE) {
      c = ss_medium_stack_cross(scene, &s->beyond, scene->shapes[g->hit.geom_id].material,
                                ss_vec3_dot(ray->d, g->hit.ng) < 0.0, &eta);
    }
    if (c == SS_CROSSING_LOST) {
      return 0;
    }
    if (c != SS_CROSSING_TRUE) {
      s->media = s->beyond;
      if (!ss_cross_null_interface(&g->crossing, ray, &w->crossings, stats)) {
        return 0;
      }
      region(scene, s, &w->inside, &w->boundary);
      return 1;
    }
  }
  if (ss_material_is_null(g->m)) {
    cross(scene, s, g->m, &g->hit, ray->d);
    if (!ss_cross_null_interface(&g->crossing, ray, &w->crossings, stats)) {
      return 0;
    }
    w->inside = side_medium(g->m, ray->d, &g->crossing);
    w->boundary = g->m;
    if (w->inside >= 0 && react_entered(w, g->m, &g->hit)) {
      return 0;
    }
    return 1;
  }
  return bsdf_vertex(w, g, eta);
}

ss_rgb ss_medium_walk(const ss_scene *scene, const ss_walk_parts *parts, ss_ray ray, ss_rng *rng,
                      ss_path_stats *stats) {
  walk w;
  w.scene = scene;
  w.parts = parts;
  w.ray = ray;
  w.depth = w.crossings = 0;
  w.inside = -1;
  w.boundary = NULL;
  w.L = ss_rgb_gray(0.0);
  w.rng = rng;
  w.stats = stats;
  path *s = &w.s;
  s->k = ss_path_start(ray.o);
  s->sp = ss_spectral_start(ss_rng_uniform(rng));
  s->entered = 0;
  s->mnee_from = s->mnee_armed = 0;
  s->guiding = 0;
  s->nested = scene->nested_material >= 0;
  s->media = scene->camera_media;
  if (s->nested) {
    region(scene, s, &w.inside, &w.boundary);
  }
  for (;;) {
    segment g;
    if (!trace_segment(&w, &g)) {
      break;
    }
    int event = medium_event(&w, &g);
    if (event < 0) {
      break;
    }
    if (event == 0 && !surface_event(&w, &g)) {
      break;
    }
  }
  return w.L;
}
