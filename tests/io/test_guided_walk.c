/* Guided walks of volpath (src/render/integrators/guided_walk.h): kappa is
 * the root of a atanh(kappa) = kappa, Dwivedi's direction density
 * integrates to 1 and its sampler draws it, and on an index-matched
 * chromatic sphere lit by a point light or a directional light the guided
 * walk's mean equals the unguided walk's within K_SIGMA standard errors
 * per channel (the mixture's weights keep it unbiased); a scene lit by an
 * environment is not guided (the same paths bit for bit). */
#include "render/integrators/guided_walk.h"
#include "subsurf/integrator.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/scene_io.h"
#include "subsurf/stats.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define K_SIGMA 4.5

Test(guided_walk, kappa_is_the_root_of_the_transport_eigenvalue_equation) {
  const double albedo[] = {0.2, 0.5, 0.678, 0.838, 0.9585, 0.99, 0.999};
  double previous = 1.0;
  for (size_t i = 0; i < sizeof albedo / sizeof albedo[0]; ++i) {
    double k = ss_dwivedi_kappa(albedo[i]);
    cr_assert(k > 0.0 && k < previous, "albedo %g: kappa %g", albedo[i], k);
    if (k < SS_GUIDE_MAX_KAPPA) {
      cr_assert_float_eq(albedo[i] * atanh(k), k, 1e-9, "albedo %g: kappa %g", albedo[i], k);
    }
    previous = k;
  }
  /* Diffusion's limit for albedo near 1: kappa ~ sqrt(3 (1 - a)). */
  cr_assert_float_eq(ss_dwivedi_kappa(0.999), sqrt(3.0 * 0.001), 2e-3);
  cr_assert_eq(ss_dwivedi_kappa(1.0), 0.0);
  cr_assert_eq(ss_dwivedi_kappa(0.01), SS_GUIDE_MAX_KAPPA);
}

Test(guided_walk, dwivedi_density_is_normalised_and_sampled) {
  const double kappas[] = {0.0, 0.3, 0.8, SS_GUIDE_MAX_KAPPA};
  ss_rng rng;
  ss_rng_seed(&rng, 3, 5);
  for (int i = 0; i < 4; ++i) {
    double k = kappas[i];
    /* 2 pi int D(mu) dmu by the midpoint rule. */
    const int cells = 200000;
    double integral = 0.0;
    for (int j = 0; j < cells; ++j) {
      integral += ss_dwivedi_pdf(k, -1.0 + (j + 0.5) * 2.0 / cells) * 2.0 / cells;
    }
    cr_assert_float_eq(2.0 * SS_PI * integral, 1.0, 1e-6, "kappa %g: %g", k, integral);
    /* The sampler against the density, in 20 bins of mu. */
    enum { BINS = 20, N = 200000 };
    int count[BINS] = {0};
    for (int n = 0; n < N; ++n) {
      double mu = ss_dwivedi_sample_mu(k, ss_rng_uniform(&rng));
      cr_assert(mu >= -1.0 && mu <= 1.0);
      int b = (int)((mu + 1.0) * 0.5 * BINS);
      count[b < BINS ? b : BINS - 1]++;
    }
    for (int b = 0; b < BINS; ++b) {
      double p = 0.0;
      for (int j = 0; j < 1000; ++j) {
        double mu = -1.0 + (b + (j + 0.5) / 1000.0) * 2.0 / BINS;
        p += 2.0 * SS_PI * ss_dwivedi_pdf(k, mu) * (2.0 / BINS) / 1000.0;
      }
      double expected = N * p, sd = sqrt(N * p * (1.0 - p));
      cr_assert(fabs(count[b] - expected) <= 5.0 * sd, "kappa %g, bin %d: %d against %g", k, b,
                count[b], expected);
    }
  }
}

/* An index-matched unit icosphere of an RGB medium lit by `light` (JSON),
 * volpath with option guide = q. */
static ss_scene *matched_scene(const char *light, double q) {
  char text[4096];
  snprintf(
      text, sizeof text,
      "{\"camera\": {\"position\": [0, 0, 4], \"resolution\": [2, 2]},\n"
      " \"media\": [{\"name\": \"m\", \"sigma_s\": [2, 3, 4], \"sigma_a\": [0.1, 0.3, 0.6]}],\n"
      " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\",\n"
      "   \"boundary\": \"index-matched\", \"medium\": \"m\"}],\n"
      " \"shapes\": [{\"name\": \"ball\", \"type\": \"sphere\", \"subdivisions\": 4,\n"
      "   \"material\": \"t\"}],\n"
      " \"lights\": [%s],\n"
      " \"integrator\": {\"type\": \"volpath\", \"guide\": %g}}\n",
      light, q);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(text, "test", NULL, &s, &err), SS_OK, "%s", err.message);
  return s;
}

/* n volpath paths along rays from (0, 0, 4) toward points spread over the
 * sphere's disk, with the integrator's prepared state; per-channel stats. */
static void estimate(const ss_scene *s, int n, uint64_t seed, ss_running_stats st[3]) {
  const ss_integrator_ops *ops = ss_integrator_find("volpath");
  cr_assert_not_null(ops);
  void *state = NULL;
  ss_error err;
  cr_assert_eq(ops->prepare(s, &state, &err), SS_OK, "%s", err.message);
  ss_path_stats ps;
  memset(&ps, 0, sizeof ps);
  for (int c = 0; c < 3; ++c) {
    ss_running_stats_init(&st[c]);
  }
  ss_rng rng;
  ss_rng_seed(&rng, seed, 11);
  for (int i = 0; i < n; ++i) {
    double x = 1.6 * ss_rng_uniform(&rng) - 0.8, y = 1.6 * ss_rng_uniform(&rng) - 0.8;
    ss_ray ray = {ss_vec3_make(0, 0, 4), ss_vec3_normalize(ss_vec3_make(x, y, -4)), 0, INFINITY};
    ss_rgb L = ops->li(s, state, ray, &rng, &ps);
    for (int c = 0; c < 3; ++c) {
      ss_running_stats_add(&st[c], L.c[c]);
    }
  }
  ops->release(state);
}

static void guided_equals_unguided(const char *light) {
  ss_scene *plain = matched_scene(light, 0.0), *guided = matched_scene(light, 0.5);
  ss_running_stats a[3], b[3];
  estimate(plain, 60000, 7, a);
  estimate(guided, 60000, 8, b);
  for (int c = 0; c < 3; ++c) {
    double se = hypot(ss_running_stats_stderr(&a[c]), ss_running_stats_stderr(&b[c]));
    cr_assert(a[c].mean > 10.0 * se, "channel %d: mean %g +- %g", c, a[c].mean, se);
    cr_assert(fabs(a[c].mean - b[c].mean) <= K_SIGMA * se,
              "channel %d: unguided %g, guided %g (+- %g)", c, a[c].mean, b[c].mean, se);
  }
  ss_scene_destroy(plain);
  ss_scene_destroy(guided);
}

Test(guided_walk, guided_mean_equals_unguided_under_a_point_light) {
  guided_equals_unguided(
      "{\"name\": \"lamp\", \"type\": \"point\", \"position\": [3, 1, -1], \"intensity\": 10}");
}

Test(guided_walk, guided_mean_equals_unguided_under_a_directional_light) {
  guided_equals_unguided("{\"name\": \"sun\", \"type\": \"directional\","
                         " \"direction\": [-1, -0.5, 0.3], \"irradiance\": 1}");
}

/* Light sampling weighs paths by the density of their directions (MIS), so
 * only a scene lit by one delta light is guided. */
Test(guided_walk, an_environment_light_is_not_guided) {
  const char *sky = "{\"name\": \"sky\", \"type\": \"environment\", \"radiance\": 1}";
  ss_scene *plain = matched_scene(sky, 0.0), *guided = matched_scene(sky, 0.5);
  ss_running_stats a[3], b[3];
  estimate(plain, 2000, 7, a);
  estimate(guided, 2000, 7, b);
  for (int c = 0; c < 3; ++c) {
    cr_assert_eq(a[c].mean, b[c].mean, "channel %d", c);
    cr_assert_eq(a[c].m2, b[c].m2, "channel %d", c);
  }
  ss_scene_destroy(plain);
  ss_scene_destroy(guided);
}
