/* The per-pixel trimmed mean of render passes (trimmed_render.h): with no
 * trimming it is the plain render's mean (the passes split the same sample
 * streams), an outlier injected into one pass is removed by trimming but not
 * by the plain mean, and bad splits are refused. */
#include "subsurf/render.h"
#include "subsurf/scene.h"
#include "subsurf/trimmed_render.h"

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <math.h>

/* A diffuse icosphere over the floor, under the lamp and the sky. */
static ss_scene *scene(void) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  test_sphere_view(s, 12, 8);
  snprintf(s->integrator.name, sizeof s->integrator.name, "path");
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "white");
  m.kind = SS_MATERIAL_DIFFUSE;
  m.albedo = ss_rgb_gray(0.8);
  m.medium = -1;
  int mi;
  cr_assert_eq(ss_scene_add_material(s, &m, &mi, &err), SS_OK, "%s", err.message);
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(0.3, 2, &sphere, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", sphere, mi, NULL, &err), SS_OK, "%s", err.message);
  test_add_floor_lamp_sky(s, -0.3);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_render_options options(const ss_scene *s, int spp) {
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  o.seed = 11;
  o.threads = 2;
  return o;
}

Test(trimmed_render, fraction_zero_equals_the_plain_render) {
  ss_scene *s = scene();
  ss_render_options o = options(s, 12);
  ss_film *plain, *trimmed;
  ss_render_stats stats, tstats;
  ss_error err;
  cr_assert_eq(ss_render(s, &o, &plain, &stats, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_render_trimmed(s, &o, 4, 0.0, &trimmed, &tstats, &err), SS_OK, "%s", err.message);
  cr_assert_eq(tstats.samples, stats.samples);
  cr_assert_eq(ss_film_sample_count(trimmed), ss_film_sample_count(plain));
  int lit = 0;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 12; ++x) {
      ss_rgb a = ss_film_pixel_mean(plain, x, y), b = ss_film_pixel_mean(trimmed, x, y);
      for (int c = 0; c < 3; ++c) {
        cr_assert(fabs(a.c[c] - b.c[c]) <= 1e-12 * fabs(a.c[c]) + 1e-300,
                  "pixel %d,%d channel %d: %.17g plain, %.17g over 4 passes", x, y, c, a.c[c],
                  b.c[c]);
      }
      lit += a.c[0] > 0.0;
    }
  }
  cr_assert_gt(lit, 48);
  ss_film_destroy(plain);
  ss_film_destroy(trimmed);
  ss_scene_destroy(s);
}

Test(trimmed_render, an_outlier_in_one_pass_is_trimmed_away) {
  ss_scene *s = scene();
  ss_render_options o = options(s, 16);
  enum { K = 8 };
  ss_film *pass[K];
  ss_error err;
  for (int k = 0; k < K; ++k) {
    ss_render_stats stats;
    cr_assert_eq(ss_render_pass(s, &o, k, K, &pass[k], &stats, &err), SS_OK, "%s", err.message);
    cr_assert_eq(ss_film_min_samples(pass[k]), 2);
  }
  /* The range of the clean pass means at pixel (6, 4), then pass 3 made an
   * outlier there. */
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < K; ++k) {
    double v = ss_film_pixel_mean(pass[k], 6, 4).c[0];
    lo = fmin(lo, v);
    hi = fmax(hi, v);
  }
  cr_assert_gt(hi, 0.0);
  ss_film_pixel_state st;
  ss_film_get_pixel_state(pass[3], 6, 4, &st);
  st.mean[0] = 1e6;
  ss_film_set_pixel_state(pass[3], 6, 4, &st);
  ss_film *mean, *trimmed;
  cr_assert_eq(ss_film_trimmed_combine(pass, K, 0.0, &mean, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_film_trimmed_combine(pass, K, 0.125, &trimmed, &err), SS_OK, "%s", err.message);
  double m = ss_film_pixel_mean(mean, 6, 4).c[0], t = ss_film_pixel_mean(trimmed, 6, 4).c[0];
  cr_assert_geq(m, 1e6 / K, "the plain mean %g should carry the outlier", m);
  cr_assert(t >= lo && t <= hi, "trimmed %g outside the clean passes' range [%g, %g]", t, lo, hi);
  ss_film_destroy(mean);
  ss_film_destroy(trimmed);
  for (int k = 0; k < K; ++k) {
    ss_film_destroy(pass[k]);
  }
  ss_scene_destroy(s);
}

Test(trimmed_render, splits_that_do_not_divide_the_spp_or_drop_every_pass_are_refused) {
  ss_scene *s = scene();
  ss_render_options o = options(s, 12);
  ss_film *film;
  ss_render_stats stats;
  ss_error err;
  cr_assert_eq(ss_render_trimmed(s, &o, 5, 0.0, &film, &stats, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_null(film);
  cr_assert_eq(ss_render_trimmed(s, &o, 4, 0.5, &film, &stats, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_eq(ss_render_pass(s, &o, 4, 4, &film, &stats, &err), SS_ERR_INVALID_ARGUMENT);
  o.time_limit = 1.0;
  cr_assert_eq(ss_render_trimmed(s, &o, 4, 0.0, &film, &stats, &err), SS_ERR_INVALID_ARGUMENT);
  ss_scene_destroy(s);
}
