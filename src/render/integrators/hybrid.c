/* `hybrid`: the hybrid Monte Carlo method of Li2005. A camera
 * path is traced exactly as `volpath` traces
 * it (medium_walk.c: exact free flights, phase sampling, Fresnel events, spectral
 * MIS over the channels) until, inside a translucent object, a scattering
 * event x lies deeper than `depth` transport mean free paths l = 1 / min_c
 * sigma_t'_c below the tangent plane of the point x_e where the path entered
 * (depth 0: x = x_e itself, right after the refraction). There the path is
 * handed over to the material's radially symmetric diffusion model: the
 * rest of the path is estimated as the light that enters at points x_i of
 * the object's surface and reaches x, x_i every hit of one probe chord of
 * the `bssrdf` integrator (probe.h, all hits) around x's projection onto
 * the entry plane, the direct light sampled at each, and the path continued
 * from one of them (a cosine-sampled direction, MIS with light sampling) as
 * `bssrdf` continues it (bssrdf_path.h). The hand-over is the hybrid's
 * reaction to two events of the medium walk (medium_walk.h): the path
 * entering a translucent object (recorded; at depth 0 the hand-over
 * itself) and a scattering event (the hand-over when it lies deep enough).
 *
 * After a scattering event (Li et al.: the dipole's real source at the
 * event), x is an isotropic point source of the power the path carries.
 * beta (the walk's throughput, refraction's radiance scaling undone, so
 * that it multiplies L / eta^2 inside, the invariant of refraction) holds
 * the Fresnel transmission at x_e, the transmittances and the albedo
 * sigma_s / sigma_t of every event up to x, and the in-scattered radiance
 * the path needs at x is L_s(x) = int p(w, w') L(x, w') / eta^2 dw'. The
 * diffusion's scattered light at x is isotropic, so by the reciprocity of
 * transport L_s(x) is what the surface's light would give through an
 * isotropic source of unit power at x:
 *     L_s(x) = int_A int_H K(x -> x_i, w_i) L_i(x_i, w_i) cos_i dw_i dA(x_i),
 *     K = M(r_i; z_i) Ft(cos_i) / (pi (1 - 2 C1(1/eta)))
 * (bssrdf.h, point_source_exitance and ss_bssrdf_point_source_radiance: the
 * model's exitance M of a source at depth z_i below x_i's tangent plane at
 * lateral distance r_i, leaving with the model's exit lobe). Check: a
 * non-absorbing object under a uniform L_i = 1 has L = eta^2 inside, so
 * L_s = 1, and the right side is int M dA = 1 (every source's power
 * leaves, test_point_source.c) times the lobe's int Ft cos dw / (pi (1 - 2
 * C1)) = 1. So the estimate is
 *     beta sum_j K(x -> x_j, w) L_i(x_j, w) cos / D(x_j)
 * (D: the probe's density of the all-hits chord), with light sampling and
 * the continuation at x_j as `bssrdf` has them, and no further albedo:
 * the source's power is the beta that scattered at x. The depth z_i is
 * measured below each x_i's own tangent plane (on a flat boundary: below
 * the entry plane, as Li et al. place it): so the distance to the real
 * source is |x_i - x| and the far side of a thin part is near. Models
 * without a point source (burley, table-radial, multipole, ...) keep the
 * earlier hand-over: S(x_i, w_i; x, n_e) / Ft(1) at the 3-D distance
 * |x_i - x| divided by the reduced albedo alpha' its source carries
 * (Jensen et al. 2001, eq. 4), which drops the profile inside that
 * distance: biased low where light travels far (high albedo,
 * docs/results.md).
 *
 * At depth 0 the model's own BSSRDF is evaluated with x_e as the exit
 * point: S(x_i, w_i; x_e, n_e) / Ft(1), dividing by Ft(1) = 1 - Fr(1)
 * removes the model's exit-side Fresnel factor (the walk took the
 * refraction at x_e); exact for the models whose S depends on w_o only
 * through Ft (the hierarchical kernel's convention, hierarchical.h). That
 * is the `bssrdf` integrator's estimate of the same model; at an infinite
 * depth the path is never handed over and the image is volpath's, bit for
 * bit.
 *
 * The continuation keeps the walk's hero channel and starts from the
 * walk's channel density ratios r_u (spectral_mis.h), so that a medium it
 * traces volumetrically (level of detail "volpath") multiplies them on and
 * the channels stay combined by the balance heuristic over whole paths,
 * f / sum_i pmf_i p_i(prefix) p_i(suffix): with fresh ratios the weights
 * of prefix and suffix, each summing to one over the channels, would be
 * multiplied under one hero, which does not sum to one (a bias). */
#include "render/integrators/hybrid.h"
#include "render/integrators/bssrdf_path.h"
#include "render/integrators/hierarchical.h"
#include "render/integrators/medium_walk.h"

#include "subsurf/irradiance_points.h"
#include "subsurf/probe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  double depth; /* switch depth in transport mean free paths, >= 0, may be inf */
  size_t num_materials;
  const ss_bssrdf **kernel; /* per material: its radially symmetric model, or NULL */
} hybrid_state;

/* Where the path last entered a translucent object: the surface hit, its
 * material and the transport mean free path of its most translucent channel. */
typedef struct {
  int valid;
  ss_hit hit; /* hit.ng: outward normal */
  const ss_material *m;
  double mfp;
} entry;

/* The walk's reactions' context, one per camera path. */
typedef struct {
  const ss_scene *scene;
  const hybrid_state *h;
  entry e;
} path_ctx;

/* The depth of x below the tangent plane of the entry point. */
static double depth_below(const entry *e, ss_vec3 x) {
  return ss_vec3_dot(ss_vec3_sub(e->hit.p, x), e->hit.ng);
}

/* The model of every translucent material; an error names a material whose
 * model cannot be handed over to. */
static ss_status kernels(const ss_scene *scene, const ss_bssrdf **kernel, ss_error *err) {
  for (size_t i = 0; i < scene->num_materials; ++i) {
    const ss_material *m = &scene->materials[i];
    if (!ss_material_is_translucent(m)) {
      continue;
    }
    const ss_bssrdf *b = ss_subsurface_bssrdf(scene->subsurface, (int)i);
    if (!b || !ss_hier_kernel_ok(b)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "hybrid: material '%s': key bssrdf: model '%s' is not a radially "
                          "symmetric diffusion model (use dipole, better-dipole, pbd, "
                          "table-radial, multipole, ...)",
                          m->name, b ? ss_bssrdf_name(b) : "none");
    }
    kernel[i] = b;
  }
  return SS_OK;
}

static ss_status hybrid_check(const ss_scene *scene, ss_error *err) {
  if (ss_refuse_nested_media(scene, "hybrid", err) != SS_OK ||
      ss_refuse_varying_media(scene, "hybrid", "use volpath or bssrdf", err) != SS_OK) {
    return SS_ERR_INVALID_ARGUMENT;
  }
  double depth = ss_scene_integrator_option(scene, "depth", SS_HYBRID_DEFAULT_DEPTH);
  if (!(depth >= 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "hybrid: option depth: expected a number >= 0 (mean free paths; inf: "
                        "never hand over), got %g",
                        depth);
  }
  return SS_OK;
}

static ss_status hybrid_prepare(const ss_scene *scene, void **state, ss_error *err) {
  if (hybrid_check(scene, err) != SS_OK) {
    return SS_ERR_INVALID_ARGUMENT;
  }
  ss_status built = ss_subsurface_build(scene->subsurface, err);
  if (built != SS_OK) {
    return built;
  }
  double depth = ss_scene_integrator_option(scene, "depth", SS_HYBRID_DEFAULT_DEPTH);
  const ss_bssrdf **kernel = calloc(scene->num_materials + 1, sizeof *kernel);
  if (!kernel) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "hybrid: out of memory");
  }
  ss_status st = kernels(scene, kernel, err);
  hybrid_state *h = st == SS_OK ? calloc(1, sizeof *h) : NULL;
  if (!h) {
    free(kernel);
    return st != SS_OK ? st : ss_error_set(err, SS_ERR_NO_MEMORY, "hybrid: out of memory");
  }
  h->depth = depth;
  h->num_materials = scene->num_materials;
  h->kernel = kernel;
  *state = h;
  return SS_OK;
}

static void hybrid_release(void *state) {
  hybrid_state *h = state;
  if (h) {
    free((void *)h->kernel);
    free(h);
  }
}

/* The hand-over at x (the entry point itself at depth 0, else a scattering
 * event, `scattered`): the diffusion model's estimate of all the light the
 * path would have gathered from x on, beta included (the path's
 * MIS-collapsed throughput times the radiance scaling of its refractions);
 * r: the path's channel density ratios (mean 1) and hero its hero channel,
 * for the media the continuation traces volumetrically. */
static ss_rgb handover(const ss_scene *scene, const hybrid_state *h, const entry *e, ss_vec3 x,
                       int scattered, ss_rgb beta, ss_rgb r, int hero, int depth, ss_rng *rng,
                       ss_path_stats *stats) {
  size_t mi = (size_t)(e->m - scene->materials);
  const ss_bssrdf *b = mi < h->num_materials ? h->kernel[mi] : NULL;
  if (!b || !ss_rgb_is_finite(beta) || ss_rgb_is_black(beta)) {
    return ss_rgb_gray(0.0);
  }
  int point_source = scattered && ss_bssrdf_has_point_source(b);
  if (scattered && !point_source) {
    /* The scattering event has weighed the path by its albedo already; the
     * model's source carries the reduced albedo alpha' again (Jensen et al.
     * 2001, eq. 4: R_d is alpha' / (4 pi) times the dipole's terms). */
    const ss_medium_optics *o = &ss_bssrdf_get_params(b)->medium;
    for (int c = 0; c < 3; ++c) {
      double s_prime = o->sigma_s.c[c] * (1.0 - o->g.c[c]);
      beta.c[c] *= s_prime > 0.0 ? (s_prime + o->sigma_a.c[c]) / s_prime : 0.0;
    }
  }
  ss_vec3 n = e->hit.ng;
  /* x_p, the probe's centre: x's projection onto the entry point's tangent plane. */
  ss_vec3 x_p = ss_vec3_madd(x, n, depth_below(e, x));
  ss_probe probe;
  ss_probe_init(&probe, scene->accel, e->hit.geom_id, b, x_p, ss_frame_from_normal(n), n);
  ss_vertex v;
  memset(&v, 0, sizeof v);
  v.kind = point_source ? SS_VERTEX_SOURCE : SS_VERTEX_ENTRY;
  v.source_depth = depth_below(e, x);
  v.d = ss_vec3_neg(n);
  v.bssrdf = b;
  v.query.x_o = x;
  v.query.n_o = n;
  v.query.w_o = n;
  double eta = ss_bssrdf_get_params(b)->eta;
  v.scale = point_source ? 1.0 : 1.0 / ss_irradiance_fresnel_weight(1.0, eta);
  /* Every hit of one probe chord is an entry point, its direct light
   * estimated there (one all-hits query, as the `bssrdf` integrator's
   * default all_hits); the path continues from one of them. */
  ss_rgb L = ss_rgb_gray(0.0);
  if (!ss_vertex_sample_entries(scene, &probe, &e->hit, beta, rng, &v, &L, stats)) {
    return L;
  }
  return ss_rgb_add(L, ss_bssrdf_path_continue(scene, &v, beta, r, hero, depth, 1.0, rng, stats));
}

/* The hand-over at x, with the walk's throughput and channel ratios r_u
 * normalised to mean(r_u) = 1 (no light sampling could have produced the
 * prefix) and refraction's radiance scaling undone. The continuation keeps
 * the path's hero (uniform when none was chosen yet) and multiplies r_u on
 * in media traced at level of detail "volpath". */
static ss_rgb hand_over_walk(const path_ctx *c, const ss_walk_view *w, ss_vec3 x, int scattered,
                             ss_rng *rng, ss_path_stats *stats) {
  double k = ss_rgb_average(w->sp->r_u);
  ss_rgb beta = ss_rgb_scale(w->k->beta, w->k->eta_scale / k);
  int hero = ss_spectral_hero(w->sp);
  return handover(c->scene, c->h, &c->e, x, scattered, beta, ss_rgb_scale(w->sp->r_u, 1.0 / k),
                  hero, w->depth, rng, stats);
}

/* The walk entered a translucent object: its entry is recorded, and at
 * depth 0 the path is handed over there. */
static int entered(void *ctx, const ss_walk_view *w, const ss_material *m, const ss_medium *med,
                   const ss_hit *hit, ss_rgb *L, ss_rng *rng, ss_path_stats *stats) {
  path_ctx *c = ctx;
  double sigma = INFINITY;
  for (int k = 0; k < 3; ++k) {
    sigma = fmin(sigma,
                 med->optics.sigma_s.c[k] * (1.0 - med->optics.g.c[k]) + med->optics.sigma_a.c[k]);
  }
  c->e.valid = 1;
  c->e.hit = *hit;
  c->e.m = m;
  c->e.mfp = 1.0 / sigma;
  if (c->h->depth > 0.0) {
    return 0;
  }
  *L = ss_rgb_add(*L, hand_over_walk(c, w, hit->p, 0, rng, stats));
  return 1;
}

/* A scattering event deeper than `depth` mean free paths below the entry
 * plane: the path is handed over there. */
static int scattered(void *ctx, const ss_walk_view *w, ss_vec3 p, ss_rgb *L, ss_rng *rng,
                     ss_path_stats *stats) {
  path_ctx *c = ctx;
  if (!c->e.valid || !(depth_below(&c->e, p) >= c->h->depth * c->e.mfp)) {
    return 0;
  }
  *L = ss_rgb_add(*L, hand_over_walk(c, w, p, 1, rng, stats));
  return 1;
}

static ss_rgb hybrid_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                        ss_path_stats *stats) {
  path_ctx c = {scene, state, {.valid = 0}};
  ss_walk_reaction r = {entered, scattered, &c};
  ss_walk_parts parts = {&ss_mnee_defaults, NULL, state ? &r : NULL};
  return ss_medium_walk(scene, &parts, ray, rng, stats);
}

static const char *const hybrid_options[] = {"depth", NULL};

const ss_integrator_ops ss_integrator_hybrid = {
    .name = "hybrid",
    .summary = "volumetric random walk near the surface, the material's diffusion model below "
               "`depth` mean free paths (Li, Pellacini & Torrance 2005)",
    .options = hybrid_options,
    .check = hybrid_check,
    .prepare = hybrid_prepare,
    .release = hybrid_release,
    .li = hybrid_li,
};
