/* The translucent sphere the hierarchical integrator's tests render: an
 * icosphere of radius 1 (smooth boundary, sigma_s (10, 8, 6), sigma_a
 * (0.5, 1, 2): mean free path 0.095, profile width 1/sigma_tr = 0.25) with
 * the given kernel model, lit by a directional light from the upper left
 * and a dim sky, seen by an 8 x 8 camera of `fov` degrees (below 10 every
 * pixel sees the sphere), integrator `hierarchical`; not yet committed, so
 * that a test can set options first. */
#ifndef SUBSURF_TESTS_HIER_SPHERE_H
#define SUBSURF_TESTS_HIER_SPHERE_H

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

static inline ss_scene *hier_sphere_uncommitted(const char *model, double fov) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  s->camera.width = 8;
  s->camera.height = 8;
  s->camera.position = ss_vec3_make(0, 0, 5);
  s->camera.target = ss_vec3_make(0, 0, 0);
  s->camera.up = ss_vec3_make(0, 1, 0);
  s->camera.fov_deg = fov;
  snprintf(s->integrator.name, sizeof s->integrator.name, "hierarchical");
  test_add_translucent(s, ss_rgb_make(10.0, 8.0, 6.0), ss_rgb_make(0.5, 1.0, 2.0),
                       SS_BOUNDARY_SMOOTH, model);
  ss_mesh *sphere;
  cr_assert_eq(ss_shape_icosphere(1.0, 4, &sphere, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", sphere, 0, NULL, &err), SS_OK, "%s", err.message);
  ss_light l;
  memset(&l, 0, sizeof l);
  snprintf(l.name, sizeof l.name, "sun");
  l.type = SS_LIGHT_DIRECTIONAL;
  l.direction = ss_vec3_normalize(ss_vec3_make(1, -1, -0.5));
  l.value = ss_rgb_gray(2.0);
  l.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
  test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_make(0.1, 0.2, 0.3));
  return s;
}

#endif
