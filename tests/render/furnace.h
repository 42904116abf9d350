/* The furnace scenes shared by the furnace tests: a unit icosphere with one
 * material (and medium) under a uniform sky of radiance 1, and the estimate
 * of volpath's (or another integrator's) radiance along rays toward it. */
#ifndef SUBSURF_TESTS_RENDER_FURNACE_H
#define SUBSURF_TESTS_RENDER_FURNACE_H

#include <criterion/criterion.h>

#include "subsurf/integrator.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"
#include "subsurf/stats.h"
#include "subsurf/texture.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Adds the unit icosphere of material mi and the sky of radiance 1, and
 * commits the scene. */
static inline void furnace_finish(ss_scene *s, int mi) {
  ss_error err;
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(1.0, 5, &sphere, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_add_shape(s, "ball", sphere, mi, NULL, &err), SS_OK, "%s", err.message);
  ss_light env;
  memset(&env, 0, sizeof env);
  env.type = SS_LIGHT_ENVIRONMENT;
  snprintf(env.name, sizeof env.name, "sky");
  env.value = ss_rgb_gray(1.0);
  env.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &env, NULL, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
}

/* With `alpha` (owned by the scene from then on) on the material's alpha
 * when not NULL. */
static ss_scene *furnace_scene_alpha(ss_material *mat, const ss_medium *med, ss_texture *alpha) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  if (alpha) {
    cr_assert_eq(ss_scene_add_texture(s, alpha, &err), SS_OK, "%s", err.message);
    mat->textures[SS_PARAM_ALPHA] = alpha;
  }
  if (med) {
    cr_assert_eq(ss_scene_add_medium(s, med, &mat->medium, &err), SS_OK, "%s", err.message);
  }
  int mi;
  cr_assert_eq(ss_scene_add_material(s, mat, &mi, &err), SS_OK, "%s", err.message);
  furnace_finish(s, mi);
  return s;
}

static inline ss_scene *furnace_scene(ss_material *mat, const ss_medium *med) {
  return furnace_scene_alpha(mat, med, NULL);
}

static ss_material interface_material(ss_boundary_type b, double eta) {
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "interface");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = b;
  m.eta = eta;
  m.medium = -1;
  return m;
}

static ss_medium gray_medium(double sigma_s, double sigma_a, ss_phase_type type, double g) {
  ss_medium m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "medium");
  m.optics.sigma_s = ss_rgb_gray(sigma_s);
  m.optics.sigma_a = ss_rgb_gray(sigma_a);
  ss_error err;
  m.optics.phase = type;
  m.optics.g = ss_rgb_gray(g);
  cr_assert_eq(ss_medium_init(&m, &err), SS_OK, "%s", err.message);
  return m;
}

/* Runs `n` paths of the integrator along rays from (0, 0, 4) toward points
 * spread over the sphere's disk; per-channel statistics. */
static void estimate(const ss_scene *s, const char *integrator, int n, ss_running_stats st[3]) {
  const ss_integrator_ops *ops = ss_integrator_find(integrator);
  cr_assert_not_null(ops);
  ss_path_stats ps;
  memset(&ps, 0, sizeof ps);
  for (int c = 0; c < 3; ++c) {
    ss_running_stats_init(&st[c]);
  }
  ss_rng rng;
  ss_rng_seed(&rng, 7, 11);
  for (int i = 0; i < n; ++i) {
    double x = 1.6 * ss_rng_uniform(&rng) - 0.8, y = 1.6 * ss_rng_uniform(&rng) - 0.8;
    ss_ray ray = {ss_vec3_make(0, 0, 4), ss_vec3_normalize(ss_vec3_make(x, y, -4)), 0, INFINITY};
    ss_rgb L = ops->li(s, NULL, ray, &rng, &ps);
    for (int c = 0; c < 3; ++c) {
      ss_running_stats_add(&st[c], L.c[c]);
    }
  }
}

/* A lossless sphere with a rough boundary (clear, or a non-absorbing
 * isotropic medium) under the sky, its roughness the texture `tex` (owned
 * by the scene) or, when NULL, the constant alpha: the statistics of n
 * volpath paths. */
static void rough_furnace_alpha(ss_microfacet_type type, double alpha, ss_texture *tex, double eta,
                                int compensated, int with_medium, int n, ss_running_stats *st) {
  ss_medium med = gray_medium(2.0, 0.0, SS_PHASE_ISOTROPIC, 0.0);
  ss_material mat = interface_material(SS_BOUNDARY_ROUGH, eta);
  mat.mf.type = type;
  mat.mf.alpha = alpha;
  mat.energy_compensation = compensated;
  ss_scene *s = furnace_scene_alpha(&mat, with_medium ? &med : NULL, tex);
  ss_running_stats ch[3];
  estimate(s, "volpath", n, ch);
  *st = ch[0]; /* grey: the channels are the same path */
  ss_scene_destroy(s);
}

/* A roughness texture with values in [0.1, 0.7]: 0, a checker of 8 x 8
 * squares per unit of uv; 1, world-space fBm noise (4 octaves, features
 * about a third of the sphere's radius). */
static inline ss_texture *alpha_texture(int which) {
  ss_texture *t;
  ss_error err;
  ss_rgb a = ss_rgb_gray(0.1), b = ss_rgb_gray(0.7);
  if (which == 0) {
    cr_assert_eq(ss_texture_create_checker(a, b, &t, &err), SS_OK, "%s", err.message);
    ss_texture_set_transform(t, (const double[2]){8.0, 8.0}, (const double[2]){0.0, 0.0});
  } else {
    ss_noise_params p = {.octaves = 4,
                         .lacunarity = 2.0,
                         .gain = 0.5,
                         .lo = 0.35,
                         .hi = 0.65,
                         .seed = 3,
                         .world = 1};
    cr_assert_eq(ss_texture_create_noise(a, b, &p, &t, &err), SS_OK, "%s", err.message);
    ss_texture_set_transform(t, (const double[2]){3.0, 3.0}, (const double[2]){0.0, 0.0});
  }
  return t;
}

static inline void rough_furnace(ss_microfacet_type type, double alpha, double eta, int compensated,
                                 int with_medium, int n, ss_running_stats *st) {
  rough_furnace_alpha(type, alpha, NULL, eta, compensated, with_medium, n, st);
}

#endif
