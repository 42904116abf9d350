/* Manifold next-event estimation for volpath (mnee.h).
 *
 * From a medium vertex x0 a light is picked as in ordinary next-event
 * estimation and a point y on it (area lights: uniform by area; delta
 * lights: their position or direction); the straight line x0 -> y seeds
 * the refraction point x1 on the boundary, Newton's method moves it until
 * Snell's law holds at the shading normal (render/manifold.h), and the
 * segment x1 -> y is tested for occlusion outside. The contribution carries
 * the phase function at x0, the transmittance of x0 -> x1 (and of any
 * index-matched media outside), the Fresnel transmittance at x1 and the
 * generalised geometry term (Hanika et al. 2015, eq. 4; Jakob & Marschner
 * 2012, eq. 10), written with J = |d omega_0 / d y| (manifold.h):
 *  - area light, radiance Le: L = f Ft eta^2 Le J / p_A(y), eta^2 being
 *    the radiance scaling of the refraction (bsdf.h);
 *  - point or spot light, intensity I: the irradiance at x0 normal to
 *    omega_0 is E = Ft I eta^2 J_perp (etendue: n_i^2 dA_0 d omega_0 =
 *    n_o^2 dA_y d omega_y, so d omega_y / dA_0 = eta^2 d omega_0 / dA_y,
 *    with J_perp over the plane normal to x1 -> y); 1 / r^2 when eta = 1;
 *  - directional or beam light, irradiance E_o: E = Ft E_o eta^2 J_dir
 *    (J_dir = d omega_0 / d omega_o); E_o when eta = 1.
 * An area light is also reached by the phase-sampled path x0 -> x1
 * (refraction chosen with probability 1 - Fr) -> y, whose solid-angle
 * density at x0 is p_phase (1 - Fr); MNEE's is p_A / J. The two are
 * combined by the balance heuristic (Veach 1997, eq. 9.10) inside
 * volpath's one-sample spectral MIS over the channels, as its ordinary
 * next-event estimation is. Approximations, documented in docs/render.md:
 * one solution per sample (the one Newton finds from the straight-line
 * seed; other stationary paths are missed), and phase-sampled paths
 * refract at the geometric normal while MNEE solves at the shading normal
 * (the same surface on a finely tessellated mesh). */
#include "render/integrators/mnee.h"

#include "render/manifold.h"
#include "subsurf/fresnel.h"

#include <math.h>

const char *const ss_mnee_option_names[] = {"mnee", "mnee_iterations", "mnee_tolerance", NULL};

const ss_mnee_options ss_mnee_defaults = {SS_MNEE_DEFAULT_ENABLED, SS_MNEE_DEFAULT_ITERATIONS,
                                          SS_MNEE_DEFAULT_TOLERANCE};

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
  o->enabled = (int)on;
  o->max_iterations = (int)it;
  o->tolerance = tol;
  return SS_OK;
}

int ss_mnee_interface(const ss_material *m) {
  return m && m->kind == SS_MATERIAL_INTERFACE && m->boundary != SS_BOUNDARY_INDEX_MATCHED &&
         (m->bsdf.lobes & SS_BSDF_DELTA) && !m->textures[SS_PARAM_ALPHA] && m->eta != 1.0;
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

ss_rgb ss_mnee_next_event(const ss_scene *scene, const ss_mnee_options *o, const ss_mnee_vertex *v,
                          ss_rng *rng, ss_path_stats *stats) {
  const ss_rgb black = ss_rgb_gray(0.0);
  double pmf;
  int li = ss_pick_light(scene, ss_rng_uniform(rng), &pmf);
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  ss_manifold_target y;
  ss_vec3 yn;
  if (li < 0 || !light_target(&scene->lights[li], u1, u2, &y, &yn)) {
    return black;
  }
  const ss_light *l = &scene->lights[li];
  /* Seed: where the straight line toward the light leaves the medium (a
   * light inside it, which no straight segment leaves it for, is not one
   * MNEE reaches). */
  ss_ray ray = {v->x0, y.at_infinity ? y.w : ss_vec3_sub(y.p, v->x0), 0.0,
                y.at_infinity ? INFINITY : 1.0};
  ss_hit seed;
  stats->shadow_rays++;
  if (!ss_accel_intersect(scene->accel, &ray, &seed) || !(ss_vec3_dot(ray.d, seed.ng) > 0.0)) {
    return black;
  }
  const ss_material *m = ss_scene_hit_material(scene, &seed);
  if (!ss_mnee_interface(m)) {
    return black;
  }
  const double eta = m->eta;
  ss_manifold_vertex x1;
  if (!ss_manifold_solve(scene, v->x0, &seed, &y, eta, o->max_iterations, o->tolerance, &x1,
                         &stats->shadow_rays)) {
    return black;
  }
  ss_vec3 w0 = ss_vec3_sub(x1.p, v->x0);
  double d0 = ss_vec3_length(w0), d2;
  w0 = ss_vec3_scale(w0, 1.0 / d0);
  ss_vec3 wo = ss_manifold_target_dir(&y, x1.p, &d2);
  /* The light's value along x1 -> y and the Jacobian in its measure. */
  ss_light_sample ls;
  double J;
  if (l->type == SS_LIGHT_AREA) {
    if (!(ss_vec3_dot(wo, yn) < 0.0)) {
      return black; /* one-sided emitter seen from behind */
    }
    ls.li = l->value;
    ss_frame f = ss_frame_from_normal(yn);
    J = ss_manifold_jacobian(v->x0, &x1, &y, eta, f.s, f.t);
  } else {
    if (!ss_light_sample_li(l, x1.p, u1, u2, &ls)) {
      return black; /* outside a spot's cone or a beam's cylinder */
    }
    if (!y.at_infinity) {
      ls.li = ss_rgb_scale(ls.li, ls.dist * ls.dist); /* the intensity toward x1 */
    }
    ss_frame f = ss_frame_from_normal(wo);
    J = ss_manifold_jacobian(v->x0, &x1, &y, eta, f.s, f.t);
  }
  if (!(J > 0.0) || !isfinite(J)) {
    return black;
  }
  /* Occlusion (and index-matched media) outside, from x1 to the light. */
  ss_light_sample out = {.wi = wo, .dist = d2, .p = y.at_infinity ? x1.p : y.p, .n = yn};
  if (l->type == SS_LIGHT_BEAM) {
    out.dist = ls.dist; /* to the beam's source disk */
    out.p = ls.p;
  }
  ss_rgb tr = ss_shadow_transmittance_in(scene, x1.p, x1.ng, NULL, &out, 1, stats);
  if (ss_rgb_is_black(tr)) {
    return black;
  }
  for (int c = 0; c < 3; ++c) {
    tr.c[c] *= exp(-v->medium->sigma_t.c[c] * d0);
  }
  ss_vec3 wi = ss_vec3_neg(w0);
  double ft = 1.0 - ss_fresnel_dielectric(ss_vec3_dot(wi, x1.n), eta);
  double ph = ss_phase_eval(&v->medium->phase, ss_vec3_dot(v->d, w0));
  /* f: phase x Fresnel transmittance x eta^2 x J (see the top of the file). */
  double f = ph * ft * eta * eta * J;
  ss_rgb contrib = ss_rgb_mul(ss_rgb_mul(v->beta, tr), ss_rgb_scale(ls.li, f));
  if (l->type != SS_LIGHT_AREA) {
    return ss_rgb_scale(contrib, 1.0 / (pmf * ss_rgb_average(v->r_u)));
  }
  /* In solid angle at x0: MNEE's density p_A / J against phase sampling's
   * p_phase (1 - Fr) at the geometric normal, each channel's with the
   * transmittance of its own distance sampling (as volpath's next_event). */
  double p_light = pmf / l->area;
  double p_uni = ph * (1.0 - ss_fresnel_dielectric(ss_vec3_dot(wi, x1.ng), eta)) * J;
  ss_rgb denom;
  for (int c = 0; c < 3; ++c) {
    denom.c[c] = v->r_u.c[c] * (1.0 + p_uni * tr.c[c] / p_light);
  }
  return ss_rgb_scale(contrib, 1.0 / (p_light * ss_rgb_average(denom)));
}

double ss_mnee_light_pdf(const ss_scene *scene, const ss_light *l, ss_vec3 x0, const ss_hit *z,
                         const ss_hit *y, double eta) {
  ss_manifold_vertex x1;
  if (l->type != SS_LIGHT_AREA ||
      !ss_manifold_vertex_at(scene, z->geom_id, z->prim_id, z->b1, z->b2, &x1)) {
    return 0.0;
  }
  ss_manifold_target t = {.p = y->p, .at_infinity = 0};
  ss_frame f = ss_frame_from_normal(y->ng);
  double J = ss_manifold_jacobian(x0, &x1, &t, eta, f.s, f.t);
  return J > 0.0 && isfinite(J) ? ss_light_pmf(scene) / (l->area * J) : 0.0;
}
