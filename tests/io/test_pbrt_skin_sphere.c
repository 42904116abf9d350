/* The acceptance test of the pbrt-v3 importer: the bundled
 * scenes/skin_sphere.pbrt, written from scenes/skin_sphere.json, becomes the
 * same scene, so that both render to the same image bit for bit at the same
 * seed (the strongest property: every pixel of a 24 x 24 window through the
 * sphere's edge, 2 samples per pixel, volpath). */
#include <criterion/criterion.h>

#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static ss_scene *load(const char *name) {
  const char *root = getenv("SUBSURF_SOURCE_DIR");
  cr_assert_not_null(root, "SUBSURF_SOURCE_DIR is not set");
  char path[4096];
  snprintf(path, sizeof path, "%s/scenes/%s", root, name);
  ss_scene *s = NULL;
  ss_error err;
  cr_assert_eq(ss_scene_read(path, &s, NULL, NULL, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_film *render(const ss_scene *s) {
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = 2;
  o.threads = 1;
  const int crop[4] = {148, 112, 172, 136}; /* the lit edge of the sphere */
  memcpy(o.crop, crop, sizeof crop);
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_error err;
  cr_assert_eq(ss_render(s, &o, &film, &stats, &err), SS_OK, "%s", err.message);
  return film;
}

Test(pbrt_skin_sphere, pbrt_copy_is_the_json_scene) {
  ss_scene *j = load("skin_sphere.json"), *p = load("skin_sphere.pbrt");
  const ss_camera *cj = &j->camera, *cp = &p->camera;
  const ss_vec3 vj[] = {cj->position, cj->forward, cj->right, cj->up_cam};
  const ss_vec3 vp[] = {cp->position, cp->forward, cp->right, cp->up_cam};
  for (int i = 0; i < 4; ++i) {
    cr_expect(vj[i].x == vp[i].x && vj[i].y == vp[i].y && vj[i].z == vp[i].z,
              "camera vector %d: (%g %g %g) against (%g %g %g)", i, vj[i].x, vj[i].y, vj[i].z,
              vp[i].x, vp[i].y, vp[i].z);
  }
  cr_expect_eq(cj->tan_half_fov, cp->tan_half_fov);
  cr_expect_eq(cj->width, cp->width);
  cr_expect_eq(cj->height, cp->height);
  cr_expect_eq(cj->filter.type, cp->filter.type);
  cr_expect_eq(cj->filter.radius, cp->filter.radius);
  cr_expect_str_eq(j->integrator.name, p->integrator.name);
  cr_expect_eq(j->integrator.max_depth, p->integrator.max_depth);
  cr_expect_eq(j->render.spp, p->render.spp);
  cr_assert_eq(j->num_shapes, p->num_shapes);
  for (size_t i = 0; i < j->num_shapes; ++i) {
    const ss_mesh *a = j->shapes[i].mesh, *b = p->shapes[i].mesh;
    cr_assert_eq(a->num_vertices, b->num_vertices);
    cr_expect_eq(memcmp(a->positions, b->positions, 3 * a->num_vertices * sizeof(float)), 0,
                 "shape %zu's vertices differ", i);
    cr_expect_eq(j->shapes[i].material < 0, p->shapes[i].material < 0);
  }
  const ss_material *mj = &j->materials[0], *mp = &p->materials[p->shapes[0].material];
  cr_expect_eq(mj->eta, mp->eta);
  cr_expect_eq(mj->boundary, mp->boundary);
  const ss_medium *a = &j->media[mj->medium], *b = &p->media[mp->medium];
  cr_expect_eq(memcmp(&a->optics.sigma_s, &b->optics.sigma_s, sizeof(ss_rgb)), 0);
  cr_expect_eq(memcmp(&a->optics.sigma_a, &b->optics.sigma_a, sizeof(ss_rgb)), 0);
  cr_expect_eq(a->optics.phase, b->optics.phase);
  cr_assert_eq(j->num_lights, p->num_lights);
  cr_expect_eq(memcmp(&j->lights[0].value, &p->lights[0].value, sizeof(ss_rgb)), 0);
  ss_scene_destroy(j);
  ss_scene_destroy(p);
}

Test(pbrt_skin_sphere, renders_the_same_image_as_the_json_scene, .timeout = 300) {
  ss_scene *j = load("skin_sphere.json"), *p = load("skin_sphere.pbrt");
  ss_film *fj = render(j), *fp = render(p);
  int lit = 0;
  for (int y = 0; y < ss_film_height(fj); ++y) {
    for (int x = 0; x < ss_film_width(fj); ++x) {
      ss_rgb a = ss_film_pixel_mean(fj, x, y), b = ss_film_pixel_mean(fp, x, y);
      lit += a.c[0] > 0.0;
      cr_expect(memcmp(&a, &b, sizeof a) == 0, "pixel (%d, %d): json %g %g %g, pbrt %g %g %g", x, y,
                a.c[0], a.c[1], a.c[2], b.c[0], b.c[1], b.c[2]);
    }
  }
  cr_expect_gt(lit, 24 * 24 / 4, "the window should see the lit sphere (%d lit pixels)", lit);
  ss_film_destroy(fj);
  ss_film_destroy(fp);
  ss_scene_destroy(j);
  ss_scene_destroy(p);
}
