/* Manifold next-event estimation for volpath (mnee.h).
 *
 * From a medium vertex x0 a light is picked uniformly among those MNEE
 * solves for (all but the environment) and a point y on it (area lights:
 * uniform by area, and only with probability q = min(1, Omega_0 / Omega),
 * mnee.h; delta lights: their position or direction); the straight line
 * x0 -> y seeds the refraction points x_1 .. x_k (k = 1, or 2 through a
 * nested shell), Newton's method moves them until Snell's law holds at
 * every shading normal (render/manifold.h), and the segments are tested
 * for occlusion.
 * The contribution carries the phase function at x0, the transmittance of
 * every segment, the Fresnel transmittance at every vertex and the
 * generalised geometry term (Hanika et al. 2015, eq. 4; Jakob & Marschner
 * 2012, eq. 10), written with J = |d omega_0 / d y| (manifold.h) and
 * eta^2 = prod eta_i^2 = (n_0 / n_k)^2, the radiance scaling of the
 * refractions (bsdf.h):
 *  - area light, radiance Le: L = f Ft eta^2 Le J / p_A(y);
 *  - point or spot light, intensity I: the irradiance at x0 normal to
 *    omega_0 is E = Ft I eta^2 J_perp (etendue: n_0^2 dA_0 d omega_0 =
 *    n_k^2 dA_y d omega_y, so d omega_y / dA_0 = eta^2 d omega_0 / dA_y,
 *    with J_perp over the plane normal to x_k -> y); 1 / r^2 when eta = 1;
 *  - directional or beam light, irradiance E_o: E = Ft E_o eta^2 J_dir
 *    (J_dir = d omega_0 / d omega_o); E_o when eta = 1.
 * An area light is also reached by the phase-sampled path x0 -> x_1 ..
 * x_k (refraction chosen with probability 1 - Fr at each) -> y, whose
 * solid-angle density at x0 is p_phase prod (1 - Fr); MNEE's is
 * q p_A / J (a sample not taken is one MNEE does not produce: q is a
 * factor of its density, as a light-selection probability is; it depends
 * on x0 and the light only, so the phase-sampled path's query has it).
 * The two are combined by the balance heuristic (Veach 1997, eq. 9.10)
 * inside volpath's one-sample spectral MIS over the channels, as its
 * ordinary next-event estimation is; the phase-sampled path's MNEE
 * density is that of MNEE's deterministic solve for its light point (0
 * where the solve fails). Approximations, documented in docs/render.md:
 * one solution per sample (the one Newton finds from the straight-line
 * seed; other stationary paths are missed, and a converged solve is taken
 * to be the phase-sampled path), and phase-sampled paths refract at the
 * geometric normal while MNEE solves at the shading normal (the same
 * surface on a finely tessellated mesh). */
#include "render/integrators/mnee.h"

#include "render/integrators/medium_stack.h"
#include "subsurf/fresnel.h"

#include <math.h>

const char *const ss_mnee_option_names[] = {"mnee", "mnee_iterations", "mnee_tolerance",
                                            "mnee_solid_angle", NULL};

const ss_mnee_options ss_mnee_defaults = {SS_MNEE_DEFAULT_ENABLED, SS_MNEE_DEFAULT_ITERATIONS,
                                          SS_MNEE_DEFAULT_TOLERANCE, SS_MNEE_DEFAULT_SOLID_ANGLE};

ss_status ss_mnee_options_read(const ss_scene *scene, ss_mnee_options *o, ss_error *err) {
  double on = ss_scene_integrator_option(scene, "mnee", SS_MNEE_DEFAULT_ENABLED);
  if (!(on == 0.0 || on == 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "volpath: option mnee: expected 0 (off) or 1 (on), got %g", on);
  }
  double it = ss_scene_integrator_option(scene, "mnee_iterations", SS_MNEE_DEFAULT_ITERATIONS);
  if (!(it >= 1.0 && it <= SS_MNEE_MAX_ITERATIONS) || it != floor(it)) {
    return ss_error_set(
        err, SS_ERR_INVALID_ARGUMENT,
        "volpath: option mnee_iterations: expected a whole number in [1, %d], got %g",
        SS_MNEE_MAX_ITERATIONS, it);
  }
  double tol = ss_scene_integrator_option(scene, "mnee_tolerance", SS_MNEE_DEFAULT_TOLERANCE);
  if (!(tol > 0.0 && tol <= SS_MNEE_MAX_TOLERANCE)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "volpath: option mnee_tolerance: expected a number in (0, %g], got %g",
                        SS_MNEE_MAX_TOLERANCE, tol);
  }
  double omega = ss_scene_integrator_option(scene, "mnee_solid_angle", SS_MNEE_DEFAULT_SOLID_ANGLE);
  if (!(omega > 0.0) || !isfinite(omega)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "volpath: option mnee_solid_angle: expected a positive number of "
                        "steradians, got %g",
                        omega);
  }
  o->enabled = (int)on;
  o->max_iterations = (int)it;
  o->tolerance = tol;
  o->solid_angle = omega;
  return SS_OK;
}

size_t ss_mnee_light_count(const ss_scene *scene) {
  return scene->num_lights - (scene->environment >= 0);
}

/* The probability of a sample from x0 toward area light l: min(1, Omega_0 /
 * Omega), Omega = 2 pi (1 - cos theta) the solid angle of the light's
 * bounding sphere (sin theta = R / d; 1 - cos = sin^2 / (1 + cos), free of
 * cancellation), 4 pi from inside it. */
static double area_rate(const ss_mnee_options *o, const ss_light *l, ss_vec3 x0) {
  double d2 = ss_vec3_length2(ss_vec3_sub(l->bound_centre, x0));
  double sin2 = l->bound_radius * l->bound_radius / d2;
  double omega = 4.0 * SS_PI;
  if (sin2 < 1.0) {
    omega = 2.0 * SS_PI * sin2 / (1.0 + sqrt(1.0 - sin2));
  }
  return fmin(1.0, o->solid_angle / omega);
}

/* A light picked uniformly among those MNEE samples (the environment is
 * skipped), with its probability *pmf; -1 when there is none. */
static int pick_light(const ss_scene *scene, double u, double *pmf) {
  size_t n = ss_mnee_light_count(scene);
  if (n == 0) {
    *pmf = 0.0;
    return -1;
  }
  size_t i = (size_t)(u * (double)n);
  i = i < n ? i : n - 1;
  if (scene->environment >= 0 && i >= (size_t)scene->environment) {
    ++i;
  }
  *pmf = 1.0 / (double)n;
  return (int)i;
}

/* A smooth refracting surface MNEE solves on, whatever its index ratio
 * (nested media take it from the regions on both sides). */
static int smooth_interface(const ss_material *m) {
  return m && m->kind == SS_MATERIAL_INTERFACE && (m->bsdf.lobes & SS_BSDF_DELTA) &&
         !m->textures[SS_PARAM_ALPHA];
}

int ss_mnee_interface(const ss_material *m) {
  return smooth_interface(m) && m->boundary != SS_BOUNDARY_INDEX_MATCHED && m->eta != 1.0;
}

/* The target of a light: a point on it (area: *yn its normal) or, for
 * lights at infinity, the direction toward them. 0 for the environment. */
static int light_target(const ss_light *l, double u1, double u2, ss_manifold_target *y,
                        ss_vec3 *yn) {
  y->at_infinity = 0;
  *yn = ss_vec3_make(0.0, 0.0, 0.0);
  switch (l->type) {
  case SS_LIGHT_AREA:
    return ss_light_sample_point(l, u1, u2, &y->p, yn);
  case SS_LIGHT_POINT:
  case SS_LIGHT_SPOT:
    y->p = l->position;
    return 1;
  case SS_LIGHT_DIRECTIONAL:
  case SS_LIGHT_BEAM:
    y->w = ss_vec3_neg(l->direction);
    y->at_infinity = 1;
    return 1;
  case SS_LIGHT_ENVIRONMENT:
    break;
  }
  return 0;
}

/* The straight line from x0 toward the target: to the point y (area
 * light: normal yn), or along y.w. */
static ss_ray seed_ray(ss_vec3 x0, const ss_manifold_target *y, ss_vec3 yn) {
  ss_ray ray = {x0, y->w, 0.0, INFINITY};
  return y->at_infinity ? ray : ss_ray_spawn_to(x0, ss_vec3_make(0.0, 0.0, 0.0), y->p, yn);
}

/* Nested media: the seed of the chain, the true interfaces (medium_stack.h)
 * the straight line from x0 (in the regions st) toward the target crosses,
 * in order; false and index-matching ones and surfaces that bound no region
 * are passed (the solved path's segments are tested). 0 when the line
 * crosses none, more than SS_MANIFOLD_MAX_CHAIN, or one that is not smooth,
 * or is lost (medium_stack.h). */
static int nested_seed(const ss_scene *scene, ss_vec3 x0, const ss_manifold_target *y, ss_vec3 yn,
                       ss_medium_stack st, ss_manifold_chain *c, ss_path_stats *stats) {
  ss_ray ray = seed_ray(x0, y, yn);
  c->k = 0;
  c->pass_others = 1;
  for (int crossing = 0; crossing < SS_MAX_NULL_CROSSINGS; ++crossing) {
    ss_hit hit;
    stats->shadow_rays++;
    if (!ss_accel_intersect(scene->accel, &ray, &hit)) {
      return c->k > 0;
    }
    int mat = scene->shapes[hit.geom_id].material;
    if (mat >= 0 && scene->materials[mat].kind == SS_MATERIAL_INTERFACE) {
      int enters = ss_vec3_dot(ray.d, hit.ng) < 0.0;
      double n_before = ss_region_index(scene, ss_medium_stack_top(scene, &st)), eta;
      ss_crossing cr = ss_medium_stack_cross(scene, &st, mat, enters, &eta);
      if (cr == SS_CROSSING_LOST) {
        return 0;
      }
      if (cr == SS_CROSSING_TRUE) {
        if (c->k == SS_MANIFOLD_MAX_CHAIN || !smooth_interface(&scene->materials[mat])) {
          return 0;
        }
        c->enters[c->k] = enters;
        c->eta[c->k] = n_before / ss_region_index(scene, ss_medium_stack_top(scene, &st));
        if (!ss_manifold_chain_vertex(scene, c, c->k, hit.geom_id, hit.prim_id, hit.b1, hit.b2)) {
          return 0;
        }
        c->k++;
      }
    }
    ss_ray next = ss_ray_spawn(hit.p, hit.ng, ray.d);
    if (!y->at_infinity) {
      next = ss_ray_spawn_to(hit.p, hit.ng, y->p, yn);
    }
    ray = next;
  }
  return 0;
}

/* Apart media: the seed is where the straight line toward the light leaves
 * the medium (a light inside it, which no straight segment leaves it for,
 * is not one MNEE reaches), one vertex on an ss_mnee_interface. */
static int apart_seed(const ss_scene *scene, ss_vec3 x0, const ss_manifold_target *y,
                      ss_manifold_chain *c, ss_path_stats *stats) {
  ss_ray ray = {x0, y->at_infinity ? y->w : ss_vec3_sub(y->p, x0), 0.0,
                y->at_infinity ? INFINITY : 1.0};
  ss_hit seed;
  stats->shadow_rays++;
  if (!ss_accel_intersect(scene->accel, &ray, &seed) || !(ss_vec3_dot(ray.d, seed.ng) > 0.0)) {
    return 0;
  }
  const ss_material *m = ss_scene_hit_material(scene, &seed);
  if (!ss_mnee_interface(m)) {
    return 0;
  }
  c->k = 1;
  c->eta[0] = m->eta;
  c->enters[0] = 0;
  c->pass_others = 0;
  return ss_manifold_chain_vertex(scene, c, 0, seed.geom_id, seed.prim_id, seed.b1, seed.b2);
}

/* The outward (mesh) normal of a chain vertex. */
static ss_vec3 mesh_normal(const ss_manifold_chain *c, int i) {
  return c->enters[i] ? ss_vec3_neg(c->x[i].ng) : c->x[i].ng;
}

/* Nested media: the transmittance of the solved chain from x0 (in the
 * regions of v) to the light sample `out`, segment by segment through the
 * stack of regions (Beer-Lambert in each medium crossed): every segment
 * must reach its end past false and index-matching interfaces only, and
 * every vertex must be a true interface of its index ratio in the chain
 * (the regions carried along the segments). Black otherwise (an occluder,
 * or a solution on another crossing). */
static ss_rgb nested_transmittance(const ss_scene *scene, const ss_mnee_vertex *v,
                                   const ss_manifold_chain *c, const ss_light_sample *out,
                                   ss_path_stats *stats) {
  const ss_rgb black = ss_rgb_gray(0.0);
  ss_medium_stack st = *v->media;
  ss_rgb tr = ss_rgb_gray(1.0);
  ss_vec3 p = v->x0, n = ss_vec3_make(0.0, 0.0, 0.0);
  for (int i = 0; i < c->k; ++i) {
    ss_vec3 ng = mesh_normal(c, i), d = ss_vec3_sub(c->x[i].p, p);
    ss_light_sample to = {
        .wi = ss_vec3_normalize(d), .dist = ss_vec3_length(d), .p = c->x[i].p, .n = ng};
    tr = ss_rgb_mul(tr, ss_medium_stack_shadow(scene, p, n, &st, &to, stats));
    double n_before = ss_region_index(scene, ss_medium_stack_top(scene, &st)), eta;
    int mat = scene->shapes[c->x[i].geom_id].material;
    if (ss_rgb_is_black(tr) ||
        ss_medium_stack_cross(scene, &st, mat, c->enters[i], &eta) != SS_CROSSING_TRUE ||
        n_before / ss_region_index(scene, ss_medium_stack_top(scene, &st)) != c->eta[i]) {
      return black;
    }
    p = c->x[i].p;
    n = ng;
  }
  return ss_rgb_mul(tr, ss_medium_stack_shadow(scene, p, n, &st, out, stats));
}

/* Fresnel transmittance through every vertex of the chain at its shading
 * (or, `geometric`, its geometric) normal, and the radiance scaling
 * prod eta_i^2 = (n_0 / n_k)^2 of the refractions. */
static double chain_transmission(ss_vec3 x0, const ss_manifold_chain *c, int geometric,
                                 double *eta2) {
  double ft = 1.0;
  *eta2 = 1.0;
  for (int i = 0; i < c->k; ++i) {
    ss_vec3 wi = ss_vec3_normalize(ss_vec3_sub(i ? c->x[i - 1].p : x0, c->x[i].p));
    ft *=
        1.0 - ss_fresnel_dielectric(ss_vec3_dot(wi, geometric ? c->x[i].ng : c->x[i].n), c->eta[i]);
    *eta2 *= c->eta[i] * c->eta[i];
  }
  return ft;
}

ss_rgb ss_mnee_next_event(const ss_scene *scene, const ss_mnee_options *o, const ss_mnee_vertex *v,
                          ss_rng *rng, ss_path_stats *stats) {
  const ss_rgb black = ss_rgb_gray(0.0);
  double pmf;
  int li = pick_light(scene, ss_rng_uniform(rng), &pmf);
  if (li < 0) {
    return black;
  }
  const ss_light *l = &scene->lights[li];
  /* Area lights: a sample with probability q, decided before any ray is
   * traced (its cost is the seed, the solve and the shadow rays). */
  double q = l->type == SS_LIGHT_AREA ? area_rate(o, l, v->x0) : 1.0;
  if (q < 1.0 && !(ss_rng_uniform(rng) < q)) {
    return black;
  }
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_manifold_target y;
  ss_vec3 yn;
  if (!light_target(l, u1, u2, &y, &yn)) {
    return black;
  }
  ss_manifold_chain c;
  if (!(v->media ? nested_seed(scene, v->x0, &y, yn, *v->media, &c, stats)
                 : apart_seed(scene, v->x0, &y, &c, stats)) ||
      !ss_manifold_chain_solve(scene, v->x0, &c, &y, o->max_iterations, o->tolerance,
                               &stats->shadow_rays)) {
    return black;
  }
  const ss_manifold_vertex *x1 = &c.x[0], *xk = &c.x[c.k - 1];
  ss_vec3 w0 = ss_vec3_sub(x1->p, v->x0);
  double d0 = ss_vec3_length(w0), d2;
  w0 = ss_vec3_scale(w0, 1.0 / d0);
  ss_vec3 wo = ss_manifold_target_dir(&y, xk->p, &d2);
  /* The light's value along x_k -> y and the Jacobian in its measure. */
  ss_light_sample ls;
  double J;
  if (l->type == SS_LIGHT_AREA) {
    if (!(ss_vec3_dot(wo, yn) < 0.0)) {
      return black; /* one-sided emitter seen from behind */
    }
    ls.li = l->value;
    ss_frame f = ss_frame_from_normal(yn);
    J = ss_manifold_chain_jacobian(v->x0, &c, &y, f.s, f.t);
  } else {
    if (!ss_light_sample_li(l, xk->p, u1, u2, &ls)) {
      return black; /* outside a spot's cone or a beam's cylinder */
    }
    if (!y.at_infinity) {
      ls.li = ss_rgb_scale(ls.li, ls.dist * ls.dist); /* the intensity toward x_k */
    }
    ss_frame f = ss_frame_from_normal(wo);
    J = ss_manifold_chain_jacobian(v->x0, &c, &y, f.s, f.t);
  }
  if (!(J > 0.0) || !isfinite(J)) {
    return black;
  }
  /* Occlusion (and media) outside, from x_k to the light. */
  ss_light_sample out = {.wi = wo, .dist = d2, .p = y.at_infinity ? xk->p : y.p, .n = yn};
  if (l->type == SS_LIGHT_BEAM) {
    out.dist = ls.dist; /* to the beam's source disk */
    out.p = ls.p;
  }
  ss_rgb tr;
  if (v->media) {
    tr = nested_transmittance(scene, v, &c, &out, stats);
  } else {
    tr = ss_shadow_transmittance_in(scene, x1->p, x1->ng, NULL, &out, 1, stats);
    for (int ch = 0; ch < 3; ++ch) {
      tr.c[ch] *= exp(-v->medium->sigma_t.c[ch] * d0);
    }
  }
  if (ss_rgb_is_black(tr)) {
    return black;
  }
  double eta2;
  double ft = chain_transmission(v->x0, &c, 0, &eta2);
  double ph = ss_phase_eval(&v->medium->phase, ss_vec3_dot(v->d, w0));
  /* f: phase x Fresnel transmittance x eta^2 x J (see the top of the file). */
  double f = ph * ft * eta2 * J;
  ss_rgb contrib = ss_rgb_mul(ss_rgb_mul(v->beta, tr), ss_rgb_scale(ls.li, f));
  if (l->type != SS_LIGHT_AREA) {
    return ss_rgb_scale(contrib, 1.0 / (pmf * ss_rgb_average(v->r_u)));
  }
  /* In solid angle at x0: MNEE's density p_A / J against phase sampling's
   * p_phase prod (1 - Fr) at the geometric normals, each channel's with
   * the transmittance of its own distance sampling (as volpath's
   * next_event). */
  double p_light = q * pmf / l->area;
  double p_uni = ph * chain_transmission(v->x0, &c, 1, &eta2) * J;
  ss_rgb denom;
  for (int ch = 0; ch < 3; ++ch) {
    denom.c[ch] = v->r_u.c[ch] * (1.0 + p_uni * tr.c[ch] / p_light);
  }
  return ss_rgb_scale(contrib, 1.0 / (p_light * ss_rgb_average(denom)));
}

double ss_mnee_light_pdf(const ss_scene *scene, const ss_mnee_options *o, const ss_light *l,
                         const ss_mnee_refractions *r, int nested, const ss_hit *y,
                         ss_path_stats *stats) {
  ss_manifold_chain c = {.k = r->k}, seed;
  ss_manifold_target t = {.p = y->p, .at_infinity = 0};
  if (l->type != SS_LIGHT_AREA || !(r->k >= 1 && r->k <= SS_MANIFOLD_MAX_CHAIN)) {
    return 0.0;
  }
  /* MNEE's sample for the light point y is a deterministic function of y:
   * the straight line x0 -> y must cross the same interfaces in the same
   * order, and Newton's method from there must converge, or MNEE never
   * samples this path and phase sampling keeps its full weight (failed
   * solves would otherwise bias the combination, Hanika et al. 2015,
   * sec. 5). A converged solve is taken to be this path. */
  if (!(nested ? nested_seed(scene, r->x0, &t, y->ng, r->media, &seed, stats)
               : apart_seed(scene, r->x0, &t, &seed, stats)) ||
      seed.k != r->k) {
    return 0.0;
  }
  for (int i = 0; i < r->k; ++i) {
    if (seed.x[i].geom_id != r->z[i].geom_id || seed.enters[i] != r->enters[i]) {
      return 0.0;
    }
  }
  if (!ss_manifold_chain_solve(scene, r->x0, &seed, &t, o->max_iterations, o->tolerance,
                               &stats->shadow_rays)) {
    return 0.0;
  }
  for (int i = 0; i < r->k; ++i) {
    c.eta[i] = r->eta[i];
    c.enters[i] = r->enters[i];
    if (!ss_manifold_chain_vertex(scene, &c, i, r->z[i].geom_id, r->z[i].prim_id, r->z[i].b1,
                                  r->z[i].b2)) {
      return 0.0;
    }
  }
  ss_frame f = ss_frame_from_normal(y->ng);
  double J = ss_manifold_chain_jacobian(r->x0, &c, &t, f.s, f.t);
  double pmf = 1.0 / (double)ss_mnee_light_count(scene);
  return J > 0.0 && isfinite(J) ? area_rate(o, l, r->x0) * pmf / (l->area * J) : 0.0;
}
