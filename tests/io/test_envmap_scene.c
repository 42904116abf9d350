/* The bundled environment-lit scene: its map is read relative to the
 * scene file, oriented as the scene format says (the forest's sun lies 36
 * degrees right of the map's centre, which faces -z, and 19 degrees up),
 * and light sampling finds the sun. */
#include "subsurf/light.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/scene.h"
#include "subsurf/scene_io.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

Test(envmap_scene, the_forest_scene_reads_its_map_and_samples_the_sun) {
  char path[1024];
  snprintf(path, sizeof path, "%s/scenes/skin_sphere_forest.json", getenv("SUBSURF_SOURCE_DIR"));
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_read_json(path, &s, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  cr_assert_geq(s->environment, 0);
  const ss_light *env = &s->lights[s->environment];
  cr_assert_not_null(env->map);
  /* 36 degrees from -z toward the viewer's right (+x), 19 degrees up. */
  double az = 36.0 * SS_PI / 180.0, el = 19.0 * SS_PI / 180.0;
  ss_vec3 sun = ss_vec3_make(cos(el) * sin(az), sin(el), -cos(el) * cos(az));
  ss_rng rng;
  ss_rng_seed(&rng, 9, 1);
  int near_sun = 0, n = 4000;
  double brightest = 0.0;
  for (int i = 0; i < n; ++i) {
    ss_light_sample ls;
    if (ss_light_sample_li(env, ss_vec3_make(0, 0, 0), ss_rng_uniform(&rng), ss_rng_uniform(&rng),
                           &ls) &&
        ss_vec3_dot(ls.wi, sun) > cos(3.0 * SS_PI / 180.0)) {
      near_sun++;
      brightest = fmax(brightest, ls.li.c[0]);
    }
  }
  /* The 3 degree cap is 7e-4 of the sphere but holds about 8 % of the
   * map's power (the sun's few pixels reach 400, the sky about 0.5). */
  cr_expect_gt(brightest, 100.0, "the brightest sample near the sun: %g", brightest);
  cr_expect_gt(near_sun, 3 * n / 100, "%d of %d light samples within 3 degrees of the sun",
               near_sun, n);
  ss_scene_destroy(s);
}
