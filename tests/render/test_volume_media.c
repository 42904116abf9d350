/* Micro-flake and gridded media in volpath (volume.h).
 *
 * An index-matched unit cube of a chromatic medium on the floor under a lamp
 * and a sky (light sampled from inside, so shadow rays cross the medium):
 * - uniform flakes are the isotropic medium (Jakob2010 eq. 14-15): the
 *   image means agree within the renders' standard errors;
 * - a grid of constant density covering the cube equals the homogeneous
 *   medium, isotropic and with fibre flakes whose voxel axes are the
 *   medium's: a denser voxel outside the cube triples the majorant, so delta
 *   and ratio tracking take null collisions with the spectral-MIS weights;
 * - the majorant bounds sigma_t(x, w) at random points and directions of the
 *   procedural yarn and wood grids;
 * - oriented renders (homogeneous and gridded) are bit-identical on 1 and 2
 *   threads;
 * - through the bssrdf integrator, a flake medium renders as the
 *   aniso-dipole named with the same flakes (bit for bit), uniform flakes
 *   as the dipole and a constant grid as the homogeneous medium (within the
 *   standard errors), and a gridded render is the same on 1 and 2 threads;
 * - only a render that uses BSSRDFs builds the aniso-dipole of the medium. */
#include "render/scene_builder.h"

#include <criterion/criterion.h>

#include "subsurf/grid.h"
#include "subsurf/render.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/scene.h"
#include "subsurf/subsurface.h"
#include "subsurf/volume.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Two tiles (120 pixels), so that 2 threads share them (test_render). */
enum { W = 20, H = 6 };

static const ss_rgb sigma_s = {{3.0, 2.0, 1.0}}, sigma_a = {{0.1, 0.3, 0.6}};

/* The medium: flakes of `type` about x (SS_FLAKE_NONE: isotropic), and a
 * grid (owned by the scene afterwards) or NULL; rendered by `integrator`,
 * the material naming `model` ("": none), with flakes of `model_flakes`
 * about x (p = 20) as the model's options unless SS_FLAKE_NONE. */
static ss_scene *build_as(ss_flake_type type, ss_grid *grid, const char *integrator,
                          const char *model, ss_flake_type model_flakes) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrator);
  s->camera.width = W;
  s->camera.height = H;
  s->camera.position = ss_vec3_make(0.4, 1.2, 2.6);
  s->camera.target = ss_vec3_make(0, 0, 0);
  s->camera.fov_deg = 40;
  ss_medium med = test_medium("m", sigma_s, sigma_a);
  if (type != SS_FLAKE_NONE) {
    med.optics.flakes = (ss_medium_flakes){type, 20.0, ss_vec3_make(1.0, 0.0, 0.0), 0.0, 1.0};
  }
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK, "%s", err.message);
  med.grid = grid;
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "cube");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = SS_BOUNDARY_INDEX_MATCHED;
  m.eta = 1.0;
  snprintf(m.bssrdf, sizeof m.bssrdf, "%s", model);
  if (model_flakes != SS_FLAKE_NONE) {
    const ss_bssrdf_ops *ops = ss_bssrdf_model_find(model);
    const char *keys[] = {"flake_distribution", "flake_exponent", "flake_axis"};
    const char *values[] = {ss_flake_type_name(model_flakes), "20", "1,0,0"};
    for (int k = 0; k < 3; ++k) {
      cr_assert_eq(ss_bssrdf_params_set_option(&m.bssrdf_options, ops, keys[k], values[k], &err),
                   SS_OK, "%s", err.message);
    }
  }
  cr_assert_eq(ss_scene_add_medium(s, &med, &m.medium, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_material_init(&m, &err), SS_OK, "%s", err.message);
  int mi;
  cr_assert_eq(ss_scene_add_material(s, &m, &mi, &err), SS_OK, "%s", err.message);
  ss_mesh *cube;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(1, 1, 1), 1, &cube, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "cube", cube, mi, NULL, &err), SS_OK, "%s", err.message);
  /* The floor below the cube, not touching it (coincident faces would make
   * leaks depend on which of them a ray finds). */
  test_add_floor_lamp_sky(s, -0.6);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_scene *build(ss_flake_type type, ss_grid *grid) {
  return build_as(type, grid, "volpath", "", SS_FLAKE_NONE);
}

/* 8^3 voxels over [-1, 1]^3 of density 1 and axis x, but voxel (7, 7, 7)
 * of density 3: its trilinear reach (x, y, z > 0.625) lies outside the
 * unit cube, which sees density 1 exactly; the majorant triples. */
static ss_grid *constant_grid(void) {
  ss_grid *g;
  ss_error err;
  const int n[3] = {8, 8, 8};
  cr_assert_eq(ss_grid_create(n, ss_vec3_make(-1, -1, -1), ss_vec3_make(1, 1, 1), 1, &g, &err),
               SS_OK);
  for (int64_t v = 0; v < ss_grid_voxels(g); ++v) {
    g->density[v] = 1.0f;
    ss_grid_set_axis(g, v, ss_vec3_make(1.0, 0.0, 0.0));
  }
  g->density[ss_grid_index(g, 7, 7, 7)] = 3.0f;
  cr_assert_eq(ss_grid_finish(g, &err), SS_OK);
  return g;
}

/* The image mean per channel over `runs` renders of independent seeds, and
 * its standard error from their spread. */
static void image_mean(const ss_scene *s, int runs, int spp, double mean[3], double se[3]) {
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int r = 0; r < runs; ++r) {
    ss_film *f = test_render(s, spp, 1000u + (uint64_t)r, 1, NULL);
    double m[3] = {0, 0, 0};
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        ss_rgb p = ss_film_pixel_mean(f, x, y);
        cr_assert(ss_rgb_is_finite(p));
        for (int c = 0; c < 3; ++c) {
          m[c] += p.c[c] / (W * H);
        }
      }
    }
    for (int c = 0; c < 3; ++c) {
      sum[c] += m[c];
      sum2[c] += m[c] * m[c];
    }
    ss_film_destroy(f);
  }
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum[c] / runs;
    se[c] = sqrt(fmax(sum2[c] / runs - mean[c] * mean[c], 0.0) / (runs - 1));
  }
}

/* Both scenes' image means agree within 4.5 combined standard errors. */
static void expect_same_image(ss_scene *a, ss_scene *b) {
  double ma[3], sa[3], mb[3], sb[3];
  image_mean(a, 16, 4, ma, sa);
  image_mean(b, 16, 4, mb, sb);
  for (int c = 0; c < 3; ++c) {
    double tol = 4.5 * sqrt(sa[c] * sa[c] + sb[c] * sb[c]);
    cr_assert(ma[c] > 0.0);
    cr_assert(fabs(ma[c] - mb[c]) <= tol, "channel %d: %g vs %g (tolerance %g)", c, ma[c], mb[c],
              tol);
  }
  ss_scene_destroy(a);
  ss_scene_destroy(b);
}

Test(volume_media, uniform_flakes_render_as_the_isotropic_medium) {
  expect_same_image(build(SS_FLAKE_UNIFORM, NULL), build(SS_FLAKE_NONE, NULL));
}

Test(volume_media, a_constant_grid_renders_as_the_homogeneous_medium) {
  expect_same_image(build(SS_FLAKE_NONE, constant_grid()), build(SS_FLAKE_NONE, NULL));
}

Test(volume_media, a_constant_grid_of_fibre_flakes_renders_as_the_homogeneous_fibres) {
  expect_same_image(build(SS_FLAKE_FIBER, constant_grid()), build(SS_FLAKE_FIBER, NULL));
}

/* sigma_t(x, w) <= majorant sigma_t per channel at random points of the
 * grid's box and random directions. */
static void expect_majorant_bounds(ss_grid *g, ss_flake_type type) {
  ss_scene *s = build(type, g);
  const ss_medium *m = &s->media[0];
  ss_rng rng;
  ss_rng_seed(&rng, 7u, 1u);
  ss_vec3 size = ss_vec3_sub(m->grid->hi, m->grid->lo);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    ss_vec3 p = ss_vec3_add(
        m->grid->lo, ss_vec3_mul(size, ss_vec3_make(ss_rng_uniform(&rng), ss_rng_uniform(&rng),
                                                    ss_rng_uniform(&rng))));
    ss_vec3 w = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    ss_volume_point q = ss_volume_at(m, p);
    ss_rgb st = ss_volume_sigma_t(m, &q, w);
    for (int c = 0; c < 3; ++c) {
      double ratio = st.c[c] / (m->majorant * m->sigma_t.c[c]);
      cr_assert(ratio <= 1.0, "sigma_t %g above the majorant at (%g, %g, %g)", st.c[c], p.x, p.y,
                p.z);
      worst = fmax(worst, ratio);
    }
  }
  cr_assert_gt(worst, 0.5, "the majorant is needlessly loose (largest ratio %g)", worst);
  ss_scene_destroy(s);
}

Test(volume_media, the_majorant_never_underestimates_sigma_t) {
  ss_error err;
  ss_grid *yarn, *wood;
  ss_yarn_params yp = {16, 1.0, 3, 0.2, 0.6};
  ss_wood_params wp = {16, ss_vec3_make(2.0, 1.0, 0.5), 0.2, 2.5, 0.4};
  cr_assert_eq(ss_grid_yarn(&yp, &yarn, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_grid_wood(&wp, &wood, &err), SS_OK, "%s", err.message);
  expect_majorant_bounds(yarn, SS_FLAKE_FIBER);
  expect_majorant_bounds(wood, SS_FLAKE_SURFACE);
}

/* Tracks n rays through m from random points of the cube [-0.5, 0.5]^3
 * in random directions: delta tracking over 1.5 and ratio tracking over 1. */
static void track_rays(const ss_medium *m, int n) {
  ss_rng rng;
  ss_rng_seed(&rng, 11u, 2u);
  for (int i = 0; i < n; ++i) {
    ss_vec3 o = ss_vec3_make(ss_rng_uniform(&rng) - 0.5, ss_rng_uniform(&rng) - 0.5,
                             ss_rng_uniform(&rng) - 0.5);
    ss_vec3 d = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    ss_rgb beta = ss_rgb_gray(1.0), r_u = beta, r_l = beta, a_l = beta;
    ss_volume_weights w = {&beta, &r_u, &r_l};
    double t;
    uint64_t tentative = 0;
    ss_volume_segment(m, o, d, INFINITY, 1.5, i % 3, &rng, w, &t, &tentative);
    ss_volume_transmittance(m, o, d, 1.0, i % 3, &rng, &a_l);
  }
}

/* The tracking checks the majorant at every tentative collision: none is
 * counted with the medium's own majorant, and with a tenth of it (below
 * the cube's sigma_t in every direction) delta and ratio tracking each
 * count their collisions in the medium. */
Test(volume_media, tracking_counts_collisions_above_the_majorant) {
  ss_scene *s = build(SS_FLAKE_FIBER, constant_grid());
  const ss_medium *m = &s->media[0];
  track_rays(m, 2000);
  cr_assert_eq(ss_medium_majorant_exceeded(m), 0);
  ss_medium wrong = *m; /* shares the count */
  wrong.majorant = 0.1 * m->majorant;
  track_rays(&wrong, 2000);
  uint64_t both = ss_medium_majorant_exceeded(m);
  cr_assert_gt(both, 2000, "%llu collisions counted", (unsigned long long)both);
  /* Ratio tracking alone (shadow rays across the fibres, where sigma_t is
   * largest; a collision above the majorant ends one at transmittance 0). */
  ss_rng rng;
  ss_rng_seed(&rng, 3u, 4u);
  for (int i = 0; i < 100; ++i) {
    ss_rgb a_l = ss_rgb_gray(1.0);
    ss_volume_transmittance(&wrong, ss_vec3_make(0, -0.5, 0), ss_vec3_make(0, 1, 0), 1.0, 0, &rng,
                            &a_l);
  }
  uint64_t after = ss_medium_majorant_exceeded(m);
  cr_assert_gt(after, both + 20, "%llu then %llu", (unsigned long long)both,
               (unsigned long long)after);
  ss_scene_destroy(s);
}

/* Both films bit-identical and not black; destroys them. */
static void expect_identical_films(ss_film *a, ss_film *b) {
  cr_assert_gt(test_expect_identical_films(a, b), 0.0);
  ss_film_destroy(a);
  ss_film_destroy(b);
}

static void expect_thread_independent(ss_scene *s) {
  test_expect_thread_independent(s, 2, 5u);
  ss_scene_destroy(s);
}

Test(volume_media, oriented_renders_are_the_same_on_1_and_2_threads) {
  ss_error err;
  ss_grid *yarn;
  ss_yarn_params yp = {12, 0.5, 3, 0.4, 1.0};
  cr_assert_eq(ss_grid_yarn(&yp, &yarn, &err), SS_OK, "%s", err.message);
  expect_thread_independent(build(SS_FLAKE_FIBER, NULL));
  expect_thread_independent(build(SS_FLAKE_FIBER, yarn));
}

/* The bssrdf integrator: a micro-flake medium takes the
 * aniso-dipole with its flakes; the same model named with the flakes as its
 * options gives the very same image. */
Test(volume_media, a_flake_medium_renders_through_bssrdf_as_the_aniso_dipole_named) {
  ss_scene *a = build_as(SS_FLAKE_FIBER, NULL, "bssrdf", "", SS_FLAKE_NONE);
  ss_scene *b = build_as(SS_FLAKE_NONE, NULL, "bssrdf", "aniso-dipole", SS_FLAKE_FIBER);
  expect_identical_films(test_render(a, 2, 3u, 1, NULL), test_render(b, 2, 3u, 1, NULL));
  ss_scene_destroy(a);
  ss_scene_destroy(b);
}

Test(volume_media, uniform_flakes_render_through_bssrdf_as_the_dipole) {
  expect_same_image(build_as(SS_FLAKE_UNIFORM, NULL, "bssrdf", "", SS_FLAKE_NONE),
                    build_as(SS_FLAKE_NONE, NULL, "bssrdf", "dipole", SS_FLAKE_NONE));
}

/* The exit point's model from the grid's density and voxel axis there. */
Test(volume_media, a_constant_grid_renders_through_bssrdf_as_the_homogeneous_fibres) {
  expect_same_image(build_as(SS_FLAKE_FIBER, constant_grid(), "bssrdf", "", SS_FLAKE_NONE),
                    build_as(SS_FLAKE_FIBER, NULL, "bssrdf", "", SS_FLAKE_NONE));
}

Test(volume_media, gridded_bssrdf_renders_are_the_same_on_1_and_2_threads) {
  ss_error err;
  ss_grid *yarn;
  ss_yarn_params yp = {12, 0.5, 3, 0.4, 1.0};
  cr_assert_eq(ss_grid_yarn(&yp, &yarn, &err), SS_OK, "%s", err.message);
  expect_thread_independent(build_as(SS_FLAKE_FIBER, yarn, "bssrdf", "", SS_FLAKE_NONE));
}

Test(volume_media, bssrdf_refuses_oriented_media_at_lod_volpath) {
  ss_error err;
  ss_scene *s = build_as(SS_FLAKE_SURFACE, NULL, "bssrdf", "", SS_FLAKE_NONE);
  s->materials[0].lod = SS_LOD_VOLPATH; /* as a scene's "lod": "volpath" */
  ss_subsurface_destroy(s->subsurface);
  cr_assert_eq(ss_subsurface_create(s, &s->subsurface, &err), SS_OK, "%s", err.message);
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  ss_film *film = NULL;
  ss_render_stats stats;
  cr_assert_neq(ss_render(s, &o, &film, &stats, &err), SS_OK);
  cr_assert(strstr(err.message, "not lod \"volpath\""), "%s", err.message);
  ss_scene_destroy(s);
}

/* The aniso-dipole of a flake medium (its flake tables take tens of ms) is
 * planned at commit but built only by an integrator that uses BSSRDFs. */
Test(volume_media, only_bssrdf_renders_build_the_aniso_dipole_of_a_flake_medium) {
  ss_scene *s = build(SS_FLAKE_FIBER, NULL);
  cr_assert_eq(ss_subsurface_count(s->subsurface), 1, "the model is planned");
  ss_film_destroy(test_render(s, 1, 1, 1, NULL));
  cr_expect_not(ss_subsurface_built(s->subsurface, 0), "a volpath render built the aniso-dipole");
  cr_expect_null(ss_subsurface_bssrdf(s->subsurface, 0));
  snprintf(s->integrator.name, sizeof s->integrator.name, "bssrdf");
  ss_film_destroy(test_render(s, 1, 1, 1, NULL));
  cr_assert(ss_subsurface_built(s->subsurface, 0), "a bssrdf render did not build it");
  cr_expect_str_eq(ss_bssrdf_name(ss_subsurface_bssrdf(s->subsurface, 0)), "aniso-dipole");
  ss_scene_destroy(s);
}
