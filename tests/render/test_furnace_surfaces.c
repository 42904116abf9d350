/* Furnace tests of the surface materials in the integrators: a sphere of a
 * lossless conductor (F = 1, rough with energy compensation, anisotropic),
 * mirror, thin dielectric, diffuse transmission (R + T = 1), white plastic,
 * two-sided and
 * mix under a sky of radiance 1 looks exactly like the sky in path,
 * volpath and bssrdf, which see the materials only through their BSDFs.
 * Tolerances are 4.5 standard errors. */
#include <criterion/criterion.h>

#include "render/furnace.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static ss_material surface(const char *name, ss_material_kind kind) {
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "%s", name);
  m.kind = kind;
  m.medium = -1;
  return m;
}

static ss_material lossless_metal(const char *name, int rough) {
  ss_material m = surface(name, SS_MATERIAL_CONDUCTOR);
  m.conductor_eta = ss_rgb_gray(1.0);
  m.conductor_k = ss_rgb_gray(1e4);
  m.boundary = rough ? SS_BOUNDARY_ROUGH : SS_BOUNDARY_SMOOTH;
  m.mf.type = SS_MICROFACET_BECKMANN;
  m.mf.alpha = 0.25;
  m.mf.alpha_v = 0.8;
  m.energy_compensation = 1;
  return m;
}

/* The scene of furnace.h with the materials mats[0..n) and the sphere made
 * of the last. */
static ss_scene *scene_of(ss_material *mats, int n) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  int mi = -1;
  for (int i = 0; i < n; ++i) {
    cr_assert_eq(ss_scene_add_material(s, &mats[i], &mi, &err), SS_OK, "%s", err.message);
  }
  furnace_finish(s, mi);
  return s;
}

static void expect_sky(ss_material *mats, int n, const char *what) {
  static const char *const integrators[] = {"path", "volpath", "bssrdf"};
  ss_scene *s = scene_of(mats, n);
  for (int k = 0; k < 3; ++k) {
    ss_running_stats st[3];
    estimate(s, integrators[k], 8000, st);
    for (int c = 0; c < 3; ++c) {
      double se = ss_running_stats_stderr(&st[c]);
      cr_expect(fabs(st[c].mean - 1.0) <= 4.5 * se + 2e-3,
                "%s (%s) channel %d: %.5f +- %.5f, expected 1", what, integrators[k], c, st[c].mean,
                se);
    }
  }
  ss_scene_destroy(s);
}

Test(furnace_surfaces, lossless_conductors_return_the_sky) {
  ss_material smooth = lossless_metal("smooth", 0), rough = lossless_metal("rough", 1);
  expect_sky(&smooth, 1, "smooth conductor");
  expect_sky(&rough, 1, "rough anisotropic conductor");
}

Test(furnace_surfaces, mirror_sheet_and_diffuse_transmission_return_the_sky) {
  ss_material mirror = surface("mirror", SS_MATERIAL_MIRROR);
  mirror.albedo = ss_rgb_gray(1.0);
  expect_sky(&mirror, 1, "mirror");
  ss_material thin = surface("thin", SS_MATERIAL_THIN_DIELECTRIC);
  thin.eta = 1.5;
  expect_sky(&thin, 1, "thin dielectric");
  ss_material dt = surface("dt", SS_MATERIAL_DIFFUSE_TRANSMISSION);
  dt.albedo = ss_rgb_make(0.2, 0.5, 0.9);
  dt.transmittance = ss_rgb_make(0.8, 0.5, 0.1);
  expect_sky(&dt, 1, "diffuse transmission");
  ss_material plastic = surface("plastic", SS_MATERIAL_COATED_DIFFUSE);
  plastic.albedo = ss_rgb_gray(1.0);
  plastic.eta = 1.5;
  expect_sky(&plastic, 1, "white plastic");
}

/* A mix of diffuse transmission and a metal: light transmitted into the
 * sphere meets the metal's back, black when one-sided (the mix loses
 * energy) and a mirror image of its front when two-sided (lossless). */
Test(furnace_surfaces, two_sided_and_mix_return_the_sky) {
  ss_material mats[4] = {lossless_metal("metal", 1), surface("both", SS_MATERIAL_TWO_SIDED),
                         surface("dt", SS_MATERIAL_DIFFUSE_TRANSMISSION),
                         surface("mix", SS_MATERIAL_MIX)};
  mats[1].parts[0] = 0;
  mats[2].albedo = ss_rgb_gray(0.3);
  mats[2].transmittance = ss_rgb_gray(0.7);
  mats[3].parts[0] = 1;
  mats[3].parts[1] = 2;
  mats[3].mix_weight = 0.4;
  expect_sky(mats, 4, "mix of a two-sided metal and diffuse transmission");
  mats[3].parts[0] = 0;
  ss_scene *s = scene_of(mats, 4);
  ss_running_stats st[3];
  estimate(s, "volpath", 4000, st);
  cr_expect_lt(st[0].mean, 0.9, "a one-sided metal's back absorbs: %g", st[0].mean);
  ss_scene_destroy(s);
}
