/* Single scattering in grids and micro-flakes
 * (src/render/integrators/volume_single_scatter.c): the term equals volpath's
 * paths of exactly one scattering event in the medium.
 *
 * A 10 x 8 x 10 slab (top face y = 1) is seen from above along a slightly
 * oblique direction through its central 0.5 x 0.5. volpath, restricted to
 * one scattering event by max_depth (index matched: the event is the first
 * vertex, max_depth 2; eta 1.3: refraction in, event, refraction out,
 * max_depth 3), and the `fem` integrator's path (diffusion_path.h: the
 * boundary's reflection and the single scattering term) with its diffusion
 * term left out trace the same camera rays. Index matched, the slab is lit
 * by a point light and a constant sky; behind the smooth boundary of eta
 * 1.3 by the sky only (volpath reaches it by phase sampling, and Jensen et
 * al.'s refraction at the straight line's exit is exact for a flat boundary
 * under light from infinity; the sky's reflection at the entry, Fr(cos_o)
 * Le in both, is subtracted). The slab is 8 deep and 10 wide: light
 * crossing it unscattered, or entering through its sides, is below 1e-3 of
 * the term. Each channel's mean must agree within 4 combined standard
 * errors of at most 2.5 % (measured with 10^6 rays: within 0.1-0.3 %), for
 *  - a heterogeneous grid of densities 0.6-2 over an isotropic medium, and
 *  - homogeneous fibre flakes (p = 20, axis oblique, albedo falling to 0.7
 *    of its normal value at grazing incidence).
 * In a homogeneous isotropic sphere behind eta 1.3 under a point light,
 * where both use Jensen et al.'s approximation, the tracked term equals the
 * homogeneous one (ss_single_scatter). Under a sun at 30-80 degrees behind
 * eta 1.3, which volpath reaches only by MNEE, volpath's homogeneous term
 * equals Jensen et al.'s. The `fem` and `bssrdf` integrators'
 * checks accept single_scattering on such media. */
#include "render/integrators/bssrdf_vertex.h"
#include "render/integrators/diffusion_path.h"
#include "render/integrators/medium_walk.h"
#include "render/integrators/mnee.h"
#include "render/integrators/single_scatter.h"
#include "subsurf/fresnel.h"
#include "subsurf/grid.h"
#include "subsurf/volume.h"

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const ss_rgb sigma_s = {{3.0, 2.0, 1.5}}, sigma_a = {{0.2, 0.4, 0.6}};
static const ss_rgb sky = {{0.6, 0.8, 1.0}};

/* 8^3 voxels over the slab of densities uniform in [0.6, 2] (fixed seed). */
static ss_grid *random_grid(void) {
  ss_grid *g;
  ss_error err;
  const int n[3] = {8, 8, 8};
  cr_assert_eq(ss_grid_create(n, ss_vec3_make(-5, -7, -5), ss_vec3_make(5, 1, 5), 0, &g, &err),
               SS_OK);
  ss_rng rng;
  ss_rng_seed(&rng, 7, 0);
  for (int64_t v = 0; v < ss_grid_voxels(g); ++v) {
    g->density[v] = (float)(0.6 + 1.4 * ss_rng_uniform(&rng));
  }
  cr_assert_eq(ss_grid_finish(g, &err), SS_OK, "%s", err.message);
  return g;
}

/* The slab of the medium (flakes of `type` or none, the grid or NULL; the
 * scene owns it) behind an index-matched boundary (eta 1) or a smooth one,
 * under the sky and, for sun_deg >= 0, a sun of irradiance 10 (most of the
 * term) at sun_deg degrees from the normal in the x-y plane. */
static ss_scene *slab_sun(ss_flake_type type, ss_grid *grid, double eta, double sun_deg) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  ss_medium med = test_medium("m", sigma_s, sigma_a);
  if (type != SS_FLAKE_NONE) {
    med.optics.flakes =
        (ss_medium_flakes){type, 20.0, ss_vec3_normalize(ss_vec3_make(1, 1, 0.5)), 0.3, 2.0};
  }
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK, "%s", err.message);
  med.grid = grid;
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "slab");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = eta == 1.0 ? SS_BOUNDARY_INDEX_MATCHED : SS_BOUNDARY_SMOOTH;
  m.eta = eta;
  m.bssrdf_single = 1;
  m.lod = SS_LOD_BSSRDF;
  cr_assert_eq(ss_scene_add_medium(s, &med, &m.medium, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_material_init(&m, &err), SS_OK, "%s", err.message);
  int mi;
  cr_assert_eq(ss_scene_add_material(s, &m, &mi, &err), SS_OK, "%s", err.message);
  ss_mesh *box;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(10, 8, 10), 1, &box, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(box, ss_mat4_translate(ss_vec3_make(0, -3, 0)), &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "slab", box, mi, NULL, &err), SS_OK, "%s", err.message);
  if (eta == 1.0) {
    test_add_point_light(s, "lamp", ss_vec3_make(2, 4, 1), 20.0);
  }
  test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, sky);
  if (sun_deg >= 0.0) {
    double t = sun_deg * SS_PI / 180.0;
    test_add_sun(s, ss_vec3_make(sin(t), -cos(t), 0.0));
    s->lights[s->num_lights - 1].value = ss_rgb_gray(10.0);
  }
  s->integrator.max_depth = eta == 1.0 ? 2 : 3;
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_scene *slab(ss_flake_type type, ss_grid *grid, double eta) {
  return slab_sun(type, grid, eta, -1.0);
}

typedef struct {
  double sum[3], sum2[3];
  int n;
} tally;

static void tally_add(tally *t, ss_rgb v) {
  for (int c = 0; c < 3; ++c) {
    cr_assert(isfinite(v.c[c]));
    t->sum[c] += v.c[c];
    t->sum2[c] += v.c[c] * v.c[c];
  }
  t->n++;
}

/* Two estimates over the same rays (a, the reference, and b), the rays'
 * random choice and the path statistics. */
typedef struct {
  tally a, b;
  ss_rng pick;
  ss_path_stats stats;
} comparison;

static void comparison_init(comparison *k, uint64_t seed) {
  memset(k, 0, sizeof *k);
  ss_rng_seed(&k->pick, seed, 0);
}

static double tally_mean(const tally *t, int c) { return t->sum[c] / t->n; }

static double tally_se(const tally *t, int c) {
  double m = tally_mean(t, c);
  return sqrt(fmax(t->sum2[c] / t->n - m * m, 0.0) / t->n);
}

/* Estimate b (`what`) is positive, its standard error combined with a's
 * below `max_se` of it, and a and b agree within 4 combined standard errors. */
static void expect_equal(const tally *a, const tally *b, const char *what, double max_se) {
  for (int c = 0; c < 3; ++c) {
    double ma = tally_mean(a, c), mb = tally_mean(b, c);
    double se = sqrt(tally_se(a, c) * tally_se(a, c) + tally_se(b, c) * tally_se(b, c));
    cr_log_info("channel %d: %.5f +- %.5f, %s %.5f +- %.5f\n", c, ma, tally_se(a, c), what, mb,
                tally_se(b, c));
    cr_assert(mb > 0.0 && se < max_se * mb, "channel %d: %s %g, standard error %g", c, what, mb,
              se);
    cr_assert(fabs(ma - mb) <= 4.0 * se, "channel %d: %g against %s %g (se %g)", c, ma, what, mb,
              se);
  }
}

/* The diffusion-path integrators' radiance without their diffusion term:
 * the boundary's reflection and the single scattering term. */
static ss_rgb no_diffusion(const void *ctx, const ss_hit *hit, ss_vec3 d, ss_path_stats *stats) {
  (void)ctx, (void)hit, (void)d, (void)stats;
  return ss_rgb_gray(0.0);
}

/* n camera rays from above into the slab's central 0.5 x 0.5, traced by
 * volpath and by the `fem` integrator's path (diffusion_path.h) without its
 * diffusion term, on independent random streams; behind a smooth boundary
 * the sky's reflection at the entry, Fr(cos_o) Le in both, is subtracted. */
static void compare_slab(ss_scene *s, int n) {
  const ss_material *m = &s->materials[0];
  ss_vec3 dir = ss_vec3_normalize(ss_vec3_make(0.25, -1.0, 0.15));
  comparison k;
  comparison_init(&k, 11);
  ss_rng rng;
  double fr = 0.0;
  for (int i = 0; i < n; ++i) {
    ss_vec3 o = ss_vec3_make(-0.25 + 0.5 * ss_rng_uniform(&k.pick), 3.0,
                             -0.25 + 0.5 * ss_rng_uniform(&k.pick));
    o = ss_vec3_madd(o, dir, -2.0 / fabs(dir.y));
    ss_ray ray = {o, dir, 0.0, INFINITY};
    if (m->eta != 1.0 && i == 0) {
      ss_hit hit;
      cr_assert(ss_accel_intersect(s->accel, &ray, &hit));
      fr = ss_fresnel_dielectric(-ss_vec3_dot(dir, hit.ng), m->eta);
    }
    ss_rng_seed(&rng, 1, 2 * (uint64_t)i);
    ss_walk_parts parts = {&ss_mnee_defaults, NULL, NULL};
    ss_rgb v = ss_medium_walk(s, &parts, ray, &rng, &k.stats);
    tally_add(&k.a, ss_rgb_sub(v, ss_rgb_scale(sky, fr)));
    ss_rng_seed(&rng, 1, 2 * (uint64_t)i + 1);
    v = ss_diffusion_path_li(s, no_diffusion, NULL, ray, &rng, &k.stats);
    tally_add(&k.b, ss_rgb_sub(v, ss_rgb_scale(sky, fr)));
  }
  expect_equal(&k.a, &k.b, "the term", 0.025);
  ss_scene_destroy(s);
}

Test(volume_single_scatter, grid_index_matched_equals_volpath_single_scattering) {
  compare_slab(slab(SS_FLAKE_NONE, random_grid(), 1.0), 100000);
}

Test(volume_single_scatter, grid_behind_eta_1_3_equals_volpath_single_scattering) {
  compare_slab(slab(SS_FLAKE_NONE, random_grid(), 1.3), 100000);
}

Test(volume_single_scatter, flakes_index_matched_equal_volpath_single_scattering) {
  compare_slab(slab(SS_FLAKE_FIBER, NULL, 1.0), 100000);
}

Test(volume_single_scatter, flakes_behind_eta_1_3_equal_volpath_single_scattering) {
  compare_slab(slab(SS_FLAKE_FIBER, NULL, 1.3), 200000);
}

/* Behind eta 1.3 under a sun, which volpath reaches only by MNEE (a delta
 * light), at 30 degrees and past the critical angle of 50.3 degrees, where
 * the straight line toward the sun meets the face in total internal
 * reflection (MNEE's seed) and Jensen et al.'s refraction is exact: a
 * homogeneous medium. Before manifold.c continued w_t below the surface,
 * volpath's term was 0 from 52 degrees on. */
Test(volume_single_scatter, a_sun_past_the_critical_angle_reaches_volpath_by_mnee) {
  const double suns[] = {30.0, 52.0, 69.0, 80.0};
  for (size_t k = 0; k < sizeof suns / sizeof *suns; ++k) {
    cr_log_info("sun at %g degrees", suns[k]);
    compare_slab(slab_sun(SS_FLAKE_NONE, NULL, 1.3, suns[k]), 50000);
  }
}

/* A homogeneous isotropic sphere of radius 1 behind eta 1.3 under a point
 * light beside the camera: the tracked term and Jensen et al.'s estimate
 * of ss_single_scatter (the same approximation for a delta light behind a
 * refracting boundary) over rays toward the sphere's lit side. */
Test(volume_single_scatter, homogeneous_medium_equals_the_jensen_estimate) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  int mi = test_add_translucent(s, sigma_s, sigma_a, SS_BOUNDARY_SMOOTH, "");
  s->materials[mi].bssrdf_single = 1;
  ss_mesh *ball;
  cr_assert_eq(ss_shape_sphere_uv(1.0, 64, 128, &ball, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "ball", ball, mi, NULL, &err), SS_OK, "%s", err.message);
  test_add_point_light(s, "lamp", ss_vec3_make(1.5, 2, 3), 10.0);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  const ss_material *m = &s->materials[mi];
  comparison k;
  comparison_init(&k, 13);
  ss_rng rng;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    ss_vec3 target = ss_vec3_make(-0.3 + 0.6 * ss_rng_uniform(&k.pick),
                                  -0.3 + 0.6 * ss_rng_uniform(&k.pick), 0.0);
    ss_vec3 o = ss_vec3_make(0, 0.5, 4);
    ss_ray ray = {o, ss_vec3_normalize(ss_vec3_sub(target, o)), 0.0, INFINITY};
    ss_hit hit;
    cr_assert(ss_accel_intersect(s->accel, &ray, &hit));
    ss_rng_seed(&rng, 3, 2 * (uint64_t)i);
    tally_add(&k.b, ss_volume_single_scatter(s, m, &hit, ray.d, &rng, &k.stats));
    ss_rng_seed(&rng, 3, 2 * (uint64_t)i + 1);
    tally_add(&k.a, ss_single_scatter(s, m, &hit, ray.d, &rng, &k.stats));
  }
  expect_equal(&k.a, &k.b, "the tracked term", 0.02);
  ss_scene_destroy(s);
}

/* The `fem` and `bssrdf` integrators' checks take single_scattering on
 * flakes and grids (the slab's material at the level of detail "bssrdf",
 * whose model is then aniso-dipole). */
Test(volume_single_scatter, fem_and_bssrdf_accept_it_on_flakes_and_grids) {
  ss_scene *scenes[2] = {slab(SS_FLAKE_FIBER, NULL, 1.3), slab(SS_FLAKE_NONE, random_grid(), 1.0)};
  const char *integrators[2] = {"fem", "bssrdf"};
  for (int i = 0; i < 2; ++i) {
    for (int k = 0; k < 2; ++k) {
      const ss_integrator_ops *ops = ss_integrator_find(integrators[k]);
      ss_error err;
      cr_assert(ops);
      cr_assert_eq(ops->check(scenes[i], &err), SS_OK, "%s: %s", integrators[k], err.message);
    }
    ss_scene_destroy(scenes[i]);
  }
}
