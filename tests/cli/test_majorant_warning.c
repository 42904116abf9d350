/* subsurf render's warning when tracking found sigma_t above a medium's
 * majorant. From the command line it cannot be provoked with
 * valid input: the majorant is the largest flake-table entry times the
 * largest voxel density, and the lookups interpolate linearly between
 * entries and voxels, so they never exceed it (test_volume_media checks
 * that no collision is counted then). So the warning is tested here on the
 * scene the render command would report on, the bundled yarn, after ratio
 * tracking with a tenth of the majorant has met collisions above it. */
#include <criterion/criterion.h>

#include "cli/majorant_warning.h"
#include "subsurf/rng.h"
#include "subsurf/scene_io.h"
#include "subsurf/volume.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What ss_cli_warn_majorant prints for `scene`, in a buffer to free. */
static char *warnings(const ss_scene *scene, int *media) {
  char *text = NULL;
  size_t size = 0;
  FILE *out = open_memstream(&text, &size);
  cr_assert_not_null(out);
  *media = ss_cli_warn_majorant(out, "render", scene);
  cr_assert_eq(fclose(out), 0);
  return text;
}

Test(majorant_warning, names_the_medium_and_its_count_only_once_exceeded) {
  const char *dir = getenv("SUBSURF_SOURCE_DIR");
  cr_assert_not_null(dir, "SUBSURF_SOURCE_DIR is not set");
  char path[4096];
  snprintf(path, sizeof path, "%s/scenes/yarn.json", dir);
  ss_scene *scene;
  ss_error err;
  cr_assert_eq(ss_scene_read_json(path, &scene, &err), SS_OK, "%s", err.message);
  const ss_medium *wool = &scene->media[0];
  int media;
  char *text = warnings(scene, &media);
  cr_assert_eq(media, 0);
  cr_assert_str_empty(text, "warned before any tracking: %s", text);
  free(text);
  /* Shadow rays through the yarn along its axis and across it; `low`
   * shares the medium's count. */
  ss_medium low = *wool;
  low.majorant = 0.1 * wool->majorant;
  ss_rng rng;
  ss_rng_seed(&rng, 5u, 6u);
  for (int i = 0; i < 200; ++i) {
    ss_vec3 o = i % 2 ? ss_vec3_make(-3.0, 0.0, 0.01 * (i % 7)) : ss_vec3_make(0.0, -3.0, 0.0);
    ss_vec3 d = i % 2 ? ss_vec3_make(1.0, 0.0, 0.0) : ss_vec3_make(0.0, 1.0, 0.0);
    ss_volume_transmittance(&low, o, d, 6.0, i % 3, &rng, NULL);
  }
  uint64_t above = ss_medium_majorant_exceeded(wool);
  cr_assert_gt(above, 0, "no collision above a tenth of the majorant");
  text = warnings(scene, &media);
  char expected[256];
  snprintf(expected, sizeof expected,
           "subsurf render: warning: medium 'wool': %llu tracking collisions found sigma_t above "
           "the majorant (the image is biased)\n",
           (unsigned long long)above);
  cr_assert_eq(media, 1);
  cr_assert_str_eq(text, expected);
  free(text);
  ss_scene_destroy(scene);
}
