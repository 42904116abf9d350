/* The test of the albedo parameterisation: a large thick slab whose
 * translucent material gives `albedo` A and `mfp` (scene file, exact
 * inversion) under a uniform environment of radiance 1 renders with volpath
 * to radiance A on its face seen head-on, for A from 0.05 to 0.95 and several
 * g; behind a smooth dielectric, to A plus the environment's Fresnel
 * reflection F(0). The slab is 1000 x 1000 x 500 mean free paths, tens of
 * diffusion lengths in every direction even at A = 0.95 (1/sigma_tr = 33 mean
 * free paths index matched), so light entering its sides and bottom does not
 * reach the centre of its face. Tolerance: 4.5 standard errors of the Monte
 * Carlo estimate and of the table value combined. */
#include <criterion/criterion.h>

#include "subsurf/albedo_inversion.h"
#include "subsurf/albedo_table.h"
#include "subsurf/integrator.h"
#include "subsurf/scene_io.h"
#include "subsurf/stats.h"

#include <math.h>
#include <stdio.h>

#define K_SIGMA 4.5

static ss_scene *slab_scene(double albedo, double g, const char *boundary) {
  char text[2048];
  snprintf(text, sizeof text,
           "{\"materials\": [{\"name\": \"slab\", \"type\": \"translucent\", %s"
           "\"albedo\": %.17g, \"mfp\": 1, \"g\": %.17g}],"
           " \"shapes\": [{\"type\": \"cube\", \"size\": [1000, 1000, 500], \"material\": "
           "\"slab\"}],"
           " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}]}",
           boundary, albedo, g);
  ss_scene *s = NULL;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(text, "slab.json", ".", &s, &err), SS_OK, "%s", err.message);
  return s;
}

/* Radiance toward +z from the slab's face (z = 250) near its centre. */
static void face_radiance(const ss_scene *s, int n, uint64_t seed, ss_running_stats *st) {
  const ss_integrator_ops *ops = ss_integrator_find("volpath");
  cr_assert_not_null(ops);
  ss_path_stats ps = {0};
  ss_running_stats_init(st);
  ss_rng rng;
  ss_rng_seed(&rng, seed, 5);
  for (int i = 0; i < n; ++i) {
    ss_vec3 o = ss_vec3_make(ss_rng_uniform(&rng) - 0.5, ss_rng_uniform(&rng) - 0.5, 300.0);
    ss_ray ray = {o, ss_vec3_make(0, 0, -1), 0, INFINITY};
    ss_rgb L = ops->li(s, NULL, ray, &rng, &ps);
    ss_running_stats_add(st, L.c[1]);
  }
}

static void expect_face(double albedo, double g, const char *boundary, double eta, int n,
                        uint64_t seed) {
  ss_scene *s = slab_scene(albedo, g, boundary);
  ss_running_stats st;
  face_radiance(s, n, seed, &st);
  ss_scene_destroy(s);
  const ss_albedo_table *t;
  ss_error err;
  cr_assert_eq(ss_albedo_table_builtin(&t, &err), SS_OK, "%s", err.message);
  /* the table's own standard error at this point */
  double table_se;
  double ar = ss_albedo_table_invert(t, albedo, g, eta);
  ss_albedo_table_albedo(t, ar, g, eta, &table_se);
  double f0 = 1.0 - ss_albedo_max(eta), expected = albedo + f0;
  double se = sqrt(pow(ss_running_stats_stderr(&st), 2) + table_se * table_se);
  cr_expect(fabs(st.mean - expected) <= K_SIGMA * se,
            "albedo %g g %g eta %g: face radiance %.5f +- %.5f (table +- %.5f), expected %.5f",
            albedo, g, eta, st.mean, ss_running_stats_stderr(&st), table_se, expected);
}

Test(albedo_slab, index_matched_face_has_the_albedo) {
  const double albedos[] = {0.05, 0.2, 0.5, 0.8, 0.95};
  const double gs[] = {0.0, 0.6, 0.9};
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 5; ++i) {
      expect_face(albedos[i], gs[j], "\"boundary\": \"index-matched\", ", 1.0, 3000,
                  (uint64_t)(10 * j + i));
    }
  }
}

Test(albedo_slab, dielectric_face_has_the_albedo_plus_fresnel_reflection) {
  const double albedos[] = {0.05, 0.5, 0.9};
  for (int i = 0; i < 3; ++i) {
    expect_face(albedos[i], 0.3, "\"boundary\": \"smooth\", \"eta\": 1.4, ", 1.4, 3000,
                (uint64_t)(100 + i));
  }
}
