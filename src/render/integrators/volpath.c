/* `volpath`: the ground-truth volumetric path tracer.
 *
 * Homogeneous media bounded by closed meshes (no nesting): the medium a ray
 * segment travels through is known after a scattering event or a surface
 * event (the side of the interface the ray leaves into), and otherwise read
 * from the surface that ends it (a ray that hits an interface from the inside
 * was inside its medium). A known medium's segment samples its distance first
 * and traces only that far; a surface found there must agree with the medium
 * (else the path ends as a leak), so tracking cannot drift out of sync with
 * the geometry and needs no medium stack.
 *
 * Chromatic media: free-flight distances are sampled with the extinction of
 * one "hero" channel chosen per path (hero_pmf: in proportion to the
 * channels' diffusion lengths, uniform for gray media), and the three channels are
 * combined by the one-sample balance heuristic over the channels' sampling
 * techniques (spectral MIS: Wilkie et al. 2014, "Hero Wavelength Spectral
 * Sampling"; the r_u / r_l bookkeeping of pbrt-v4's VolPathIntegrator). For a
 * path x with hero h, the estimate of channel k is
 *     f_k(x) / (sum_i pmf_i (p_i^uni(x) + p_i^nee(x)))
 * where p_i are the densities with which channel i's technique (distance
 * sampling with sigma_t[i]) would produce x by unidirectional sampling or by
 * next-event estimation. beta = f / p_h^uni, r_u[i] = 3 pmf_i p_i^uni / p_h^uni
 * and r_l[i] = 3 pmf_i p_i^nee / p_h^uni are tracked along the path and renormalised to
 * mean(r_u) = 1 at every vertex (the ratios are invariant to that). Free
 * flights have no absorption events: a scattering vertex weighs the path by
 * sigma_s T / (sigma_t[h] T[h]), so every channel stays unbiased.
 *
 * Next-event estimation from medium and surface vertices goes through
 * index-matched interfaces with the exact Beer-Lambert transmittance of the
 * media crossed (a straight shadow ray cannot pass a refracting interface:
 * lights sit outside the closed meshes); behind a smooth dielectric
 * boundary medium vertices connect to lights by manifold next-event
 * estimation (mnee.h, the `mnee` option); rough boundaries take light
 * samples at the boundary vertex. In a scene lit by one delta light the
 * walk may be guided toward it (guided_walk.h, the `guide` option). Russian
 * roulette acts on the MIS-weighted throughput without the eta^2 radiance
 * scaling of refraction (pbrt-v4). */
#include "render/integrators/emission.h"
#include "render/integrators/guided_walk.h"
#include "render/integrators/hybrid.h"
#include "render/integrators/medium_stack.h"
#include "render/integrators/mnee.h"
#include "render/integrators/roulette.h"
#include "render/integrators/shadow_tracking.h"
#include "render/integrators/spectral_mis.h"
#include "render/integrators/surface_vertex.h"
#include "subsurf/volume.h"

#include <math.h>
#include <stdlib.h>

/* The `guide` option's default: the probability of the guided technique
 * (0: the classical walk); 0.3-0.5 measured best on the index-matched skin
 * sphere (bench/RESULTS.md). */
#define SS_VOLPATH_DEFAULT_GUIDE 0.5

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

/* 1 when crossing the surface of `hit` (material m) needs only its
 * distance-only record (accel.h): an index-matched boundary of constant
 * coefficients that emits nothing, outside nested media and the hybrid. */
static int distance_suffices(const ss_scene *scene, const ss_hybrid_state *h, const path *s,
                             const ss_material *m, const ss_hit *hit) {
  return !h && !s->nested && m && ss_material_is_null(m) && !ss_material_varies(m) &&
         scene->shapes[hit->geom_id].light < 0;
}

/* The hybrid's record of an entry into the medium `medium` of m at hit. */
static void enter(const ss_scene *scene, const path *s, const ss_material *m, int medium,
                  const ss_hit *hit, ss_hybrid_entry *e) {
  const ss_medium *med = path_medium(scene, s, m, medium);
  double sigma = INFINITY;
  for (int c = 0; c < 3; ++c) {
    sigma = fmin(sigma,
                 med->optics.sigma_s.c[c] * (1.0 - med->optics.g.c[c]) + med->optics.sigma_a.c[c]);
  }
  e->valid = 1;
  e->hit = *hit;
  e->m = m;
  e->mfp = 1.0 / sigma;
}

/* The hybrid's hand-over at x, with the path's throughput and channel
 * ratios r_u normalised to mean(r_u) = 1 (no light sampling could have
 * produced the prefix) and refraction's radiance scaling undone. The
 * continuation keeps the path's hero (uniform when none was chosen yet)
 * and multiplies r_u on in media traced at level of detail "volpath"
 * (hybrid.c). */
static ss_rgb handover(const ss_scene *scene, const ss_hybrid_state *h, const path *s,
                       const ss_hybrid_entry *e, ss_vec3 x, int scattered, int depth, ss_rng *rng,
                       ss_path_stats *stats) {
  double k = ss_rgb_average(s->sp.r_u);
  ss_rgb beta = ss_rgb_scale(s->k.beta, s->k.eta_scale / k);
  int hero = ss_spectral_hero(&s->sp);
  return ss_hybrid_handover(scene, h, e, x, scattered, beta, ss_rgb_scale(s->sp.r_u, 1.0 / k), hero,
                            depth, rng, stats);
}

/* The walk; `guide` is NULL or off (q = 0) for the unguided walk. */
static ss_rgb walk(const ss_scene *scene, const ss_hybrid_state *h, const ss_mnee_options *mnee,
                   const ss_guide *guide, ss_ray ray, ss_rng *rng, ss_path_stats *stats) {
  ss_hybrid_entry entry = {.valid = 0};
  ss_rgb L = ss_rgb_gray(0.0);
  path s;
  s.k = ss_path_start(ray.o);
  s.sp = ss_spectral_start(ss_rng_uniform(rng));
  s.entered = 0;
  s.mnee_from = s.mnee_armed = 0;
  s.guiding = 0;
  s.nested = scene->nested_material >= 0;
  s.media = scene->camera_media;
  int depth = 0, crossings = 0;
  /* The medium the ray starts in when known (-1: unknown or none), and the
   * material of the boundary that encloses it. */
  int inside = -1;
  const ss_material *boundary = NULL;
  if (s.nested) {
    region(scene, &s, &inside, &boundary);
  }
  const int max_depth = scene->integrator.max_depth, rr_depth = scene->integrator.rr_depth;
  for (;;) {
    /* `crossing` is the distance-only record (accel.h) and `hit` the one the
     * surface needs (completed unless distance_suffices). Index-matched
     * crossings continue from `crossing` whichever record was needed, so a
     * walk does not depend on it (the hybrid at infinite depth is volpath,
     * bit for bit, and a spatially varying material equals its homogeneous
     * counterpart). */
    ss_hit hit, crossing;
    int found, medium;
    double t = INFINITY, tmax = INFINITY;
    const ss_material *m;
    if (inside >= 0) {
      /* Distance first: a segment known to run through a medium samples its
       * free flight before tracing, and the query stops there, so that a
       * segment ending in a scattering event (most of them) finds no surface
       * and traverses only the part of the BVH its short span overlaps. */
      double dl = ss_vec3_length(ray.d);
      const ss_medium *med = path_medium(scene, &s, boundary, inside);
      ss_spectral_choose_hero(&s.sp, med);
      t = s.guiding ? ss_guided_sample_distance(&s.seg, med->sigma_t, s.sp.hero, rng)
                    : ss_volume_sample_distance(med, ss_vec3_normalize(ray.d), s.sp.hero, rng);
      ss_ray span = ray;
      span.tmax = fmin(ray.tmax, t / dl);
      found = ss_accel_intersect_distance(scene->accel, &span, &crossing);
      if (found) {
        hit = crossing;
      }
      m = found ? ss_scene_hit_material(scene, &hit) : boundary;
      if (found && !s.nested && segment_medium(m, ray.d, &hit) != inside) {
        break; /* a leak out of the closed mesh: the path ends */
      }
      if (found && !distance_suffices(scene, h, &s, m, &hit)) {
        ss_accel_hit_complete(scene->accel, &hit);
      }
      medium = inside;
      tmax = found ? hit.t * dl : INFINITY;
    } else {
      found = ss_accel_intersect_distance(scene->accel, &ray, &crossing);
      if (found) {
        hit = crossing;
      }
      m = found ? ss_scene_hit_material(scene, &hit) : NULL;
      if (found && !distance_suffices(scene, h, &s, m, &hit)) {
        ss_accel_hit_complete(scene->accel, &hit);
      }
      medium = found && !s.nested ? segment_medium(m, ray.d, &crossing) : -1;
      if (medium >= 0) {
        tmax = hit.t * ss_vec3_length(ray.d);
        ss_spectral_choose_hero(&s.sp, path_medium(scene, &s, m, medium));
        t = ss_volume_sample_distance(path_medium(scene, &s, m, medium), ss_vec3_normalize(ray.d),
                                      s.sp.hero, rng);
      }
    }
    if (medium >= 0) {
      const ss_medium *med = path_medium(scene, &s, m, medium);
      ss_vec3 dn = ss_vec3_normalize(ray.d);
      ss_volume_weights w = {&s.k.beta, &s.sp.r_u, &s.sp.r_l};
      /* A real scattering event at distance t, or the segment's end (volume.h). */
      int event = s.guiding
                      ? ss_guided_segment_weights(&s.seg, guide->q, med->sigma_t,
                                                  med->optics.sigma_s, t, tmax, s.sp.hero, w, &t)
                      : ss_volume_segment(med, ray.o, dn, t, tmax, s.sp.hero, rng, w, &t, NULL);
      s.guiding = 0;
      if (event < 0) {
        break;
      }
      if (event > 0) {
        stats->scatter_events++;
        if (++depth >= max_depth) {
          break;
        }
        ss_spectral_renormalise(&s.k.beta, &s.sp);
        ss_vec3 p = ss_vec3_madd(ray.o, dn, t);
        if (h && entry.valid && ss_hybrid_depth_below(&entry, p) >= h->depth * entry.mfp) {
          L = ss_rgb_add(L, handover(scene, h, &s, &entry, p, 1, depth, rng, stats));
          break;
        }
        vertex v = {.med = med, .q = ss_volume_at(med, p), .d = dn};
        ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
        /* Light outside a refracting boundary cannot be reached by a straight
         * shadow ray: only index-matched media take light samples inside;
         * behind a smooth boundary MNEE connects through it (mnee.h). */
        if (s.nested ? m->eta == 1.0 : ss_material_is_null(m)) {
          L = ss_rgb_add(L, next_event(scene, &s, &v, p, zero, med, NULL, NULL, rng, stats));
        }
        /* MNEE takes homogeneous media without flakes (its phase and
         * Beer-Lambert); oriented and gridded media keep phase sampling. In
         * nested media the straight line toward the light decides whether
         * it reaches the light through one or two refractions (mnee.h). A
         * scene lit by its environment alone has nothing to solve for. */
        s.mnee_from = mnee->enabled && (s.nested || ss_mnee_interface(m)) &&
                      !ss_medium_is_volume(med) && ss_mnee_light_count(scene) > 0;
        s.mnee_armed = 0;
        if (s.mnee_from) {
          ss_mnee_vertex mv = {s.k.beta, s.sp.r_u, p, v.d, med, s.nested ? &s.media : NULL};
          L = ss_rgb_add(L, ss_mnee_next_event(scene, mnee, &mv, rng, stats));
          s.mnee.x0 = p;
          s.mnee.media = s.media;
          s.mnee.k = 0;
        }
        /* Guided walks: homogeneous media of the scene's own coefficients
         * (the mixture's weights need sigma_t per channel and kappa). */
        s.guiding = guide && guide->q > 0.0 && !s.nested && !ss_medium_is_volume(med) &&
                    med == &scene->media[medium];
        ss_vec3 wi;
        if (s.guiding) {
          /* The segment's weights carry the phase function over the
           * mixture's density of direction and distance, and r_l the
           * unidirectional density of both (guided_walk.h). */
          wi = ss_guided_sample_direction(guide, med, &v.q, v.d, ss_guide_direction(guide, p),
                                          guide->kappa[medium], s.sp.hero, rng, &s.seg);
          s.sp.r_l = s.sp.r_u;
        } else {
          wi = ss_volume_phase_sample(med, &v.q, v.d, rng);
          double p_dir = ss_volume_phase_eval(med, &v.q, v.d, wi);
          /* Exact phase sampling: f / p = 1, beta is unchanged. */
          s.sp.r_l = ss_rgb_scale(s.sp.r_u, 1.0 / p_dir);
        }
        s.k.specular = 0;
        s.k.prev_p = p;
        inside = medium;
        boundary = m;
        ray.o = p;
        ray.d = wi;
        ray.tmin = 0.0;
        ray.tmax = INFINITY;
        stats->extension_rays++;
        if (!roulette(&s, depth, rr_depth, rng)) {
          break;
        }
        continue;
      }
    }
    /* Emission found, MIS-weighted unless the last vertex sampled a delta
     * lobe; after a refraction chain from a medium vertex (mnee_armed) with
     * the density MNEE would have had. */
    double p_light = 0.0;
    ss_rgb le = ss_emission_found(scene, found ? &hit : NULL, ss_vec3_normalize(ray.d), s.k.prev_p,
                                  &p_light);
    if (!ss_rgb_is_black(le)) {
      int armed = found && s.mnee_armed;
      if (armed) {
        const ss_light *l = &scene->lights[scene->shapes[hit.geom_id].light];
        p_light = ss_mnee_light_pdf(scene, mnee, l, &s.mnee, s.nested, &hit, stats);
      }
      L = ss_rgb_add(L, ss_spectral_emitted(s.k.beta, &s.sp, le, p_light, armed || !s.k.specular));
    }
    if (!found) {
      break;
    }
    if (!m) {
      break;
    }
    double eta = m->eta;
    if (s.nested) {
      /* Schmidt & Budge 2002: only a change of the owning region is an event. */
      s.beyond = s.media;
      ss_crossing c = SS_CROSSING_TRUE;
      if (m->kind == SS_MATERIAL_INTERFACE) {
        c = ss_medium_stack_cross(scene, &s.beyond, scene->shapes[hit.geom_id].material,
                                  ss_vec3_dot(ray.d, hit.ng) < 0.0, &eta);
      }
      if (c == SS_CROSSING_LOST) {
        break;
      }
      if (c != SS_CROSSING_TRUE) {
        s.media = s.beyond;
        if (!ss_cross_null_interface(&crossing, &ray, &crossings, stats)) {
          break;
        }
        region(scene, &s, &inside, &boundary);
        continue;
      }
    }
    if (ss_material_is_null(m)) {
      cross(scene, &s, m, &hit, ray.d);
      if (!ss_cross_null_interface(&crossing, &ray, &crossings, stats)) {
        break;
      }
      inside = side_medium(m, ray.d, &crossing);
      boundary = m;
      if (h && inside >= 0) {
        enter(scene, &s, m, inside, &hit, &entry);
        if (!(h->depth > 0.0)) {
          L = ss_rgb_add(L, handover(scene, h, &s, &entry, hit.p, 0, depth, rng, stats));
          break;
        }
      }
      continue;
    }
    if (depth++ >= max_depth) {
      break;
    }
    vertex v;
    ss_bsdf local;
    v.med = NULL;
    v.bsdf = s.nested && m->kind == SS_MATERIAL_INTERFACE
                 ? ss_interface_bsdf(m, ss_hit_texcoord(&hit), eta, &local)
                 : ss_material_bsdf_at(m, ss_hit_texcoord(&hit), &local);
    v.frame = ss_hit_frame(m, &hit);
    v.d = ray.d;
    v.wo_local = ss_frame_to_local(v.frame, ss_vec3_neg(ss_vec3_normalize(ray.d)));
    if (!(v.bsdf->lobes & SS_BSDF_DELTA)) {
      ss_spectral_choose_hero(&s.sp, NULL); /* its shadow ray may track a medium */
      L = ss_rgb_add(L, next_event(scene, &s, &v, hit.p, hit.ng, NULL, m, &hit, rng, stats));
    }
    ss_bsdf_sample bs;
    ss_vec3 wi;
    if (!ss_sample_surface(v.bsdf, v.frame, v.wo_local, ray.d, hit.ng, rng, &bs, &wi)) {
      break;
    }
    s.k.beta = ss_rgb_mul(s.k.beta, ss_rgb_scale(ss_rgb_from_vec3(bs.f), fabs(bs.wi.z) / bs.pdf));
    /* Refracted out of a smooth boundary straight from a medium vertex (in
     * nested media: through a true interface, the first or second since
     * it): the density stays that of the medium vertex's direction (MNEE's
     * MIS). */
    int refracted = bs.lobe == (SS_BSDF_TRANSMISSION | SS_BSDF_DELTA);
    int enters = ss_vec3_dot(ray.d, hit.ng) < 0.0;
    s.mnee_armed =
        s.nested ? refracted && (s.mnee_from || (s.mnee_armed && s.mnee.k < SS_MANIFOLD_MAX_CHAIN))
                 : refracted && s.mnee_from && ss_vec3_dot(wi, hit.ng) > 0.0;
    s.mnee_from = 0;
    if (s.mnee_armed) {
      /* eta: n_inside / n_outside across the surface (medium_stack.h). */
      s.mnee.z[s.mnee.k] = hit;
      s.mnee.eta[s.mnee.k] = enters ? 1.0 / eta : eta;
      s.mnee.enters[s.mnee.k] = enters;
      s.mnee.k++;
    }
    s.sp.r_l = ss_rgb_scale(s.mnee_armed ? s.sp.r_l : s.sp.r_u, 1.0 / bs.pdf);
    s.k.specular = (bs.lobe & SS_BSDF_DELTA) != 0;
    if (bs.lobe & SS_BSDF_TRANSMISSION) {
      ss_path_refract(&s.k.eta_scale, bs.eta);
    }
    s.k.prev_p = hit.p;
    inside = side_medium(m, wi, &hit);
    boundary = m;
    if (s.nested) {
      s.media = bs.lobe & SS_BSDF_TRANSMISSION ? s.beyond : s.media;
      region(scene, &s, &inside, &boundary);
    }
    if (bs.lobe & SS_BSDF_TRANSMISSION) {
      cross(scene, &s, m, &hit, wi);
    }
    if (h && inside >= 0) {
      enter(scene, &s, m, inside, &hit, &entry);
      if (!(h->depth > 0.0)) {
        L = ss_rgb_add(L, handover(scene, h, &s, &entry, hit.p, 0, depth, rng, stats));
        break;
      }
    }
    ray = ss_ray_spawn(hit.p, hit.ng, wi);
    stats->extension_rays++;
    if (!roulette(&s, depth, rr_depth, rng)) {
      break;
    }
  }
  return L;
}

ss_rgb ss_volpath_walk(const ss_scene *scene, const ss_hybrid_state *h, const ss_mnee_options *mnee,
                       ss_ray ray, ss_rng *rng, ss_path_stats *stats) {
  return walk(scene, h, mnee, NULL, ray, rng, stats);
}

/* volpath's options: MNEE's (mnee.h) and `guide`, the probability of the
 * guided technique at a medium vertex (guided_walk.h). */
static const char *const volpath_option_names[] = {
    "mnee", "mnee_iterations", "mnee_tolerance", "mnee_solid_angle", "guide", NULL};

typedef struct {
  ss_mnee_options mnee;
  ss_guide guide;
} volpath_state;

static ss_status guide_option_read(const ss_scene *scene, double *q, ss_error *err) {
  *q = ss_scene_integrator_option(scene, "guide", SS_VOLPATH_DEFAULT_GUIDE);
  if (!(*q >= 0.0 && *q < 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "volpath: option guide: expected a probability in [0, 1), got %g", *q);
  }
  return SS_OK;
}

static ss_status volpath_check(const ss_scene *scene, ss_error *err) {
  /* The medium stack's shadow rays and free flights are homogeneous and
   * isotropic in direction. */
  for (size_t i = 0; scene->nested_material >= 0 && i < scene->num_media; ++i) {
    if (ss_medium_is_volume(&scene->media[i])) {
      return ss_error_set(err, SS_ERR_UNSUPPORTED,
                          "volpath: medium '%s': micro-flake and gridded media cannot be nested "
                          "or touch other media",
                          scene->media[i].name);
    }
  }
  ss_mnee_options o;
  double q;
  ss_status st = ss_mnee_options_read(scene, &o, err);
  return st != SS_OK ? st : guide_option_read(scene, &q, err);
}

/* The state is the MNEE options (mnee.h) and the guide (guided_walk.h),
 * checked before the first sample. */
static ss_status volpath_prepare(const ss_scene *scene, void **state, ss_error *err) {
  double q;
  ss_status st = volpath_check(scene, err);
  if (st != SS_OK || (st = guide_option_read(scene, &q, err)) != SS_OK) {
    return st;
  }
  volpath_state *v = malloc(sizeof *v);
  if (!v) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "volpath: out of memory");
  }
  if ((st = ss_mnee_options_read(scene, &v->mnee, err)) != SS_OK ||
      (st = ss_guide_init(&v->guide, scene, q, err)) != SS_OK) {
    free(v);
    return st;
  }
  *state = v;
  return SS_OK;
}

static void volpath_release(void *state) {
  volpath_state *v = state;
  if (v) {
    ss_guide_free(&v->guide);
  }
  free(v);
}

static ss_rgb volpath_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                         ss_path_stats *stats) {
  const volpath_state *v = state;
  return v ? walk(scene, NULL, &v->mnee, &v->guide, ray, rng, stats)
           : walk(scene, NULL, &ss_mnee_defaults, NULL, ray, rng, stats);
}

const ss_integrator_ops ss_integrator_volpath = {
    .name = "volpath",
    .summary = "volumetric path tracing with spectral MIS over RGB and manifold next-event "
               "estimation through smooth boundaries (ground truth)",
    .options = volpath_option_names,
    .check = volpath_check,
    .prepare = volpath_prepare,
    .release = volpath_release,
    .li = volpath_li,
};
