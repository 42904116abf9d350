/* The scene of the `subsurf compare` CLI tests: a 12 x 12 view of a
 * translucent Skin1-like sphere lit by a spherical area light. */
#ifndef SUBSURF_TESTS_COMPARE_SCENE_FIXTURE_H
#define SUBSURF_TESTS_COMPARE_SCENE_FIXTURE_H

#include "cli_files.h"

static const char *const compare_fixture_scene =
    "{\n"
    "  \"camera\": {\"position\": [0, 0, 5], \"fov\": "
    "30, \"resolution\": [12, 12]},\n"
    "  \"media\": [{\"name\": \"m\", \"sigma_s\": [3.7, "
    "4.4, 5.05], \"sigma_a\": [0.16, 0.85, "
    "2.4]}],\n"
    "  \"materials\": [{\"name\": \"skin\", \"type\": "
    "\"translucent\", \"boundary\": \"smooth\",\n"
    "                  \"eta\": 1.33, \"medium\": "
    "\"m\", \"bssrdf\": \"dipole\"}],\n"
    "  \"shapes\": [{\"name\": \"s\", \"type\": "
    "\"sphere\", \"subdivisions\": 2, \"material\": "
    "\"skin\"},\n"
    "             {\"name\": \"lamp\", \"type\": "
    "\"sphere\", \"radius\": 2, \"center\": [6, 2, "
    "-2], \"subdivisions\": 1}],\n"
    "  \"lights\": [{\"name\": \"lamp\", \"type\": "
    "\"area\", \"shape\": \"lamp\", \"radiance\": "
    "10}]\n"
    "}\n";

/* Writes it as dir/scene.json. */
static inline void compare_fixture_write(const char *dir) {
  cli_write_text(dir, "scene.json", compare_fixture_scene);
}

#endif
