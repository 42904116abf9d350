/* Spatially varying subsurface scattering: a translucent
 * material given by a textured albedo and mfp. The `bssrdf` integrator
 * builds the model for the exit point's coefficients and samples the entry
 * point with that same model; volpath takes the coefficients of the point
 * where a path entered. Both are checked bit for bit against a homogeneous
 * material of those coefficients: a texture that is constant but differs
 * from the material's own medium renders exactly like the homogeneous
 * material of the texture's value, so no step (sampling, pdf, evaluation,
 * free flights, shadow rays) uses the medium's coefficients instead. */
#include "render/scene_builder.h"

#include <criterion/criterion.h>

#include "subsurf/albedo_inversion.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double g = 0.3, eta = 1.33;

/* A medium converted from albedo and mfp (exact inversion) behind a
 * boundary of index ratio e. */
static int add_medium(ss_scene *s, const char *name, ss_rgb albedo, ss_rgb mfp, double e) {
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "%s", name);
  med.optics.phase = SS_PHASE_HG;
  med.optics.g = ss_rgb_gray(g);
  ss_error err;
  for (int c = 0; c < 3; ++c) {
    cr_assert_eq(ss_albedo_to_coefficients(SS_ALBEDO_INVERSION_EXACT, albedo.c[c], mfp.c[c], g, e,
                                           &med.optics.sigma_s.c[c], &med.optics.sigma_a.c[c],
                                           &err),
                 SS_OK, "%s", err.message);
  }
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK, "%s", err.message);
  int mi;
  cr_assert_eq(ss_scene_add_medium(s, &med, &mi, &err), SS_OK, "%s", err.message);
  return mi;
}

/* A unit sphere of a translucent material given by albedo and mfp, on the
 * floor under a lamp and a sky. `tex_albedo` (may be NULL) replaces the
 * albedo; the medium is always converted from `albedo`, `mfp`. */
static ss_scene *build(const char *integrator, ss_boundary_type boundary, ss_rgb albedo, ss_rgb mfp,
                       ss_texture *tex_albedo, ss_texture *tex_mfp) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrator);
  test_sphere_view(s, 24, 8); /* two tiles: test_expect_tiles_for_threads */
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "skin");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = boundary;
  m.eta = boundary == SS_BOUNDARY_INDEX_MATCHED ? 1.0 : eta;
  m.medium = add_medium(s, "skin", albedo, mfp, m.eta);
  snprintf(m.bssrdf, sizeof m.bssrdf, "dipole");
  m.lod = SS_LOD_BSSRDF;
  m.by_albedo = 1;
  m.albedo = albedo;
  m.mfp = mfp;
  m.albedo_inversion = SS_ALBEDO_INVERSION_EXACT;
  m.textures[SS_PARAM_ALBEDO] = tex_albedo;
  m.textures[SS_PARAM_MFP] = tex_mfp;
  if (tex_albedo) {
    cr_assert_eq(ss_scene_add_texture(s, tex_albedo, &err), SS_OK);
  }
  if (tex_mfp) {
    cr_assert_eq(ss_scene_add_texture(s, tex_mfp, &err), SS_OK);
  }
  cr_assert_eq(ss_material_init(&m, &err), SS_OK, "%s", err.message);
  int mi;
  cr_assert_eq(ss_scene_add_material(s, &m, &mi, &err), SS_OK, "%s", err.message);
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(0.8, 3, &sphere, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", sphere, mi, NULL, &err), SS_OK, "%s", err.message);
  test_add_floor_lamp_sky(s, -0.8);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_texture *constant(ss_rgb v) {
  ss_texture *t;
  ss_error err;
  cr_assert_eq(ss_texture_create_checker(v, v, &t, &err), SS_OK);
  return t;
}

static ss_texture *freckles(void) {
  ss_noise_params q = {
      .octaves = 4, .lacunarity = 2.0, .gain = 0.5, .lo = 0.45, .hi = 0.6, .seed = 3u, .world = 1};
  ss_texture *t;
  ss_error err;
  cr_assert_eq(
      ss_texture_create_noise(ss_rgb_make(0.8, 0.6, 0.5), ss_rgb_make(0.4, 0.2, 0.1), &q, &t, &err),
      SS_OK);
  const double scale[2] = {4.0, 4.0}, offset[2] = {0.0, 0.0};
  ss_texture_set_transform(t, scale, offset);
  return t;
}

static ss_film *render(const ss_scene *s, int threads) {
  return test_render(s, 2, 11, threads, NULL);
}

static void expect_texture_rules(const char *integrator, ss_boundary_type boundary) {
  ss_rgb base = ss_rgb_make(0.5, 0.5, 0.5), mfp = ss_rgb_make(0.2, 0.1, 0.05);
  ss_rgb value = ss_rgb_make(0.85, 0.6, 0.3), mfp2 = ss_rgb_make(0.05, 0.1, 0.3);
  ss_scene *textured = build(integrator, boundary, base, mfp, constant(value), constant(mfp2));
  ss_scene *plain = build(integrator, boundary, value, mfp2, NULL, NULL);
  ss_film *a = render(textured, 1), *b = render(plain, 1);
  if (strcmp(integrator, "bssrdf") == 0) {
    /* a model built per path vertex samples from its exponential mixture
     * (params.single_use), the material's own from its fitted table: the
     * same image needs the same per-vertex model with the material's base
     * coefficients set to the texture's (which then no longer matter) */
    ss_scene_destroy(plain);
    ss_film_destroy(b);
    plain = build(integrator, boundary, value, mfp2, constant(value), constant(mfp2));
    b = render(plain, 1);
  }
  cr_assert_gt(test_expect_identical_films(a, b), 0.0);
  ss_film_destroy(a);
  ss_film_destroy(b);
  ss_scene_destroy(textured);
  ss_scene_destroy(plain);
}

Test(varying_sss, bssrdf_samples_and_evaluates_with_the_exit_points_model) {
  expect_texture_rules("bssrdf", SS_BOUNDARY_SMOOTH);
}

Test(varying_sss, volpath_traces_the_entry_points_coefficients) {
  /* index matched: light is sampled from inside, through shadow rays */
  expect_texture_rules("volpath", SS_BOUNDARY_INDEX_MATCHED);
  expect_texture_rules("volpath", SS_BOUNDARY_SMOOTH);
}

Test(varying_sss, textured_renders_are_finite_and_the_same_for_1_and_2_threads) {
  const char *const integrators[] = {"bssrdf", "volpath"};
  for (int k = 0; k < 2; ++k) {
    ss_scene *s = build(integrators[k], SS_BOUNDARY_SMOOTH, ss_rgb_gray(0.6),
                        ss_rgb_make(0.2, 0.1, 0.05), freckles(), NULL);
    test_expect_thread_independent(s, 2, 11);
    ss_scene_destroy(s);
  }
}

Test(varying_sss, a_tabulating_model_is_refused_for_varying_coefficients) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "wax");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = SS_BOUNDARY_SMOOTH;
  m.eta = eta;
  m.medium = add_medium(s, "wax", ss_rgb_gray(0.5), ss_rgb_gray(0.1), eta);
  snprintf(m.bssrdf, sizeof m.bssrdf, "pbd");
  m.lod = SS_LOD_BSSRDF;
  m.by_albedo = 1;
  m.albedo = ss_rgb_gray(0.5);
  m.mfp = ss_rgb_gray(0.1);
  ss_texture *t = freckles();
  cr_assert_eq(ss_scene_add_texture(s, t, &err), SS_OK);
  m.textures[SS_PARAM_ALBEDO] = t;
  cr_assert_eq(ss_material_init(&m, &err), SS_OK, "%s", err.message);
  int mi;
  cr_assert_eq(ss_scene_add_material(s, &m, &mi, &err), SS_OK);
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(1.0, 2, &sphere, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", sphere, mi, NULL, &err), SS_OK);
  cr_assert_eq(ss_scene_commit(s, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "'pbd' tabulates"), "%s", err.message);
  ss_scene_destroy(s);
}

Test(varying_sss, texture_values_outside_the_parameters_range_are_refused) {
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "wax");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = SS_BOUNDARY_SMOOTH;
  m.eta = eta;
  m.by_albedo = 1;
  ss_error err;
  ss_texture *t = constant(ss_rgb_make(0.5, 1.0, 0.5)); /* albedo 1 is not in (0, 1) */
  m.textures[SS_PARAM_ALBEDO] = t;
  cr_assert_eq(ss_material_init(&m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "(0, 1)"), "%s", err.message);
  m.textures[SS_PARAM_ALBEDO] = NULL;
  ss_texture *z = constant(ss_rgb_make(0.1, 0.0, 0.1)); /* mfp 0 */
  m.textures[SS_PARAM_MFP] = z;
  cr_assert_eq(ss_material_init(&m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "'mfp'"), "%s", err.message);
  m.by_albedo = 0; /* a medium-given material has no mfp */
  cr_assert_eq(ss_material_init(&m, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "no parameter 'mfp'"), "%s", err.message);
  ss_texture_destroy(t);
  ss_texture_destroy(z);
}
