/* Tracked shadow rays (src/render/integrators/shadow_tracking.h): from
 * points inside an index-matched sphere toward a point light and a
 * directional light, the estimate's mean equals the exact Beer-Lambert
 * transmittance of ss_shadow_transmittance_tracked within K_SIGMA standard
 * errors for rates 0.5 and 1, and rate 0 returns it (up to the float
 * position of the distance-only hit); a blocker outside still blocks. */
#include "render/integrators/shadow_tracking.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/scene_io.h"
#include "subsurf/stats.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define K_SIGMA 4.5
#define N 20000

/* An index-matched unit icosphere of an RGB medium, the light `light` and
 * the extra shapes `shapes` (JSON). */
static ss_scene *matched_scene(const char *light, const char *shapes) {
  char text[4096];
  snprintf(
      text, sizeof text,
      "{\"camera\": {\"position\": [0, 0, 5], \"resolution\": [2, 2]},\n"
      " \"media\": [{\"name\": \"m\", \"sigma_s\": [2, 3, 4], \"sigma_a\": [0.1, 0.3, 0.6]}],\n"
      " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\",\n"
      "   \"boundary\": \"index-matched\", \"medium\": \"m\"},\n"
      "  {\"name\": \"wall\", \"type\": \"diffuse\", \"albedo\": 0.5}],\n"
      " \"shapes\": [{\"name\": \"ball\", \"type\": \"sphere\", \"subdivisions\": 4,\n"
      "   \"material\": \"t\"}%s],\n"
      " \"lights\": [%s],\n"
      " \"integrator\": {\"type\": \"volpath\"}}\n",
      shapes, light);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(text, "test", NULL, &s, &err), SS_OK, "%s", err.message);
  return s;
}

/* For random points inside the sphere: the mean of N tracked estimates at
 * each rate against the exact transmittance. Returns the number of points
 * whose exact transmittance is not 0. */
static int check_means(const ss_scene *s) {
  const ss_medium *med = &s->media[0];
  ss_rng rng;
  ss_rng_seed(&rng, 5, 3);
  ss_path_stats stats;
  memset(&stats, 0, sizeof stats);
  ss_rgb a_l = ss_rgb_gray(1.0);
  ss_tracking tk = {0, &rng, &a_l};
  ss_vec3 zero = ss_vec3_make(0.0, 0.0, 0.0);
  int lit = 0;
  for (int i = 0; i < 12; ++i) {
    ss_vec3 p = ss_vec3_scale(ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng)),
                              0.95 * cbrt(ss_rng_uniform(&rng)));
    ss_light_sample ls;
    cr_assert(ss_light_sample_li(&s->lights[0], p, 0.5, 0.5, &ls));
    ss_rgb exact = ss_shadow_transmittance_tracked(s, p, zero, med, &ls, 1, &tk, &stats);
    lit += exact.c[0] > 0.0;
    ss_rgb at0 = ss_shadow_transmittance_sampled(s, p, med, &ls, 0.0, &tk, &stats);
    for (int c = 0; c < 3; ++c) {
      cr_assert_float_eq(at0.c[c], exact.c[c], 1e-5 * exact.c[c] + 1e-300, "point %d", i);
    }
    const double rates[2] = {0.5, 1.0};
    for (int r = 0; r < 2; ++r) {
      ss_running_stats st[3];
      for (int c = 0; c < 3; ++c) {
        ss_running_stats_init(&st[c]);
      }
      for (int k = 0; k < N; ++k) {
        ss_rgb e = ss_shadow_transmittance_sampled(s, p, med, &ls, rates[r], &tk, &stats);
        for (int c = 0; c < 3; ++c) {
          ss_running_stats_add(&st[c], e.c[c]);
        }
      }
      for (int c = 0; c < 3; ++c) {
        double tol = K_SIGMA * ss_running_stats_stderr(&st[c]) + 1e-5 * exact.c[c];
        cr_assert(fabs(st[c].mean - exact.c[c]) <= tol,
                  "point %d, rate %g, channel %d: mean %g, exact %g (+- %g)", i, rates[r], c,
                  st[c].mean, exact.c[c], tol);
      }
    }
  }
  return lit;
}

Test(shadow_tracking, tracked_transmittance_to_a_point_light_is_unbiased) {
  ss_scene *s = matched_scene("{\"name\": \"lamp\", \"type\": \"point\", \"position\": [3, 1, -1],"
                              " \"intensity\": 10}",
                              "");
  cr_assert_gt(check_means(s), 8);
  ss_scene_destroy(s);
}

Test(shadow_tracking, tracked_transmittance_to_a_directional_light_is_unbiased) {
  ss_scene *s = matched_scene("{\"name\": \"sun\", \"type\": \"directional\","
                              " \"direction\": [-1, -0.5, 0.3], \"irradiance\": 1}",
                              "");
  cr_assert_gt(check_means(s), 8);
  ss_scene_destroy(s);
}

Test(shadow_tracking, a_blocker_beyond_the_boundary_blocks_the_tracked_ray) {
  ss_scene *s =
      matched_scene("{\"name\": \"lamp\", \"type\": \"point\", \"position\": [3, 0, 0],"
                    " \"intensity\": 10}",
                    ", {\"name\": \"block\", \"type\": \"cube\", \"size\": 0.5,"
                    " \"transform\": {\"translate\": [2, 0, 0]}, \"material\": \"wall\"}");
  check_means(s);
  ss_rng rng;
  ss_rng_seed(&rng, 9, 1);
  ss_path_stats stats;
  memset(&stats, 0, sizeof stats);
  ss_rgb a_l = ss_rgb_gray(1.0);
  ss_tracking tk = {1, &rng, &a_l};
  ss_light_sample ls;
  ss_vec3 p = ss_vec3_make(0.9, 0.0, 0.0);
  cr_assert(ss_light_sample_li(&s->lights[0], p, 0.5, 0.5, &ls));
  for (int k = 0; k < 1000; ++k) {
    ss_rgb e = ss_shadow_transmittance_sampled(s, p, &s->media[0], &ls, 0.5, &tk, &stats);
    cr_assert(ss_rgb_is_black(e), "sample %d", k);
  }
  ss_scene_destroy(s);
}
