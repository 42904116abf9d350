/* volpath against the plane-parallel reference (subsurf halfspace).
 *
 * The reference launches a collimated beam and tallies the total diffuse
 * reflectance R(theta_i) (plus the specular reflection Fr(theta_i) at
 * entry). By reciprocity the same number is the radiance leaving the
 * surface toward theta_i when the surface is lit by a uniform sky of
 * radiance 1 (directional-hemispherical = hemispherical-directional
 * reflectance), which is what a camera ray at theta_i measures. So volpath
 * renders a large, thick slab under a constant environment and its camera
 * rays at theta_i must see R + Fr within 3 combined standard errors. The slab
 * is wide and deep compared with the diffusion length, so light entering
 * through its sides and bottom does not reach the measured spot. */
#include <criterion/criterion.h>

#include "subsurf/halfspace.h"
#include "subsurf/integrator.h"
#include "subsurf/sampling.h"
#include "subsurf/scene.h"
#include "subsurf/stats.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct {
  double sigma_s, sigma_a, g, eta, theta_deg;
  ss_phase_type phase;
} config;

static ss_scene *slab_scene(const config *c) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "slab");
  med.optics.sigma_s = ss_rgb_gray(c->sigma_s);
  med.optics.sigma_a = ss_rgb_gray(c->sigma_a);
  med.optics.phase = c->phase;
  med.optics.g = ss_rgb_gray(c->g);
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK);
  ss_material mat;
  memset(&mat, 0, sizeof mat);
  snprintf(mat.name, sizeof mat.name, "slab");
  mat.kind = SS_MATERIAL_INTERFACE;
  mat.boundary = c->eta == 1.0 ? SS_BOUNDARY_INDEX_MATCHED : SS_BOUNDARY_SMOOTH;
  mat.eta = c->eta;
  cr_assert_eq(ss_scene_add_medium(s, &med, &mat.medium, &err), SS_OK);
  int mi;
  cr_assert_eq(ss_scene_add_material(s, &mat, &mi, &err), SS_OK, "%s", err.message);
  /* Top face at z = 0, 80 x 80 wide and 30 deep. */
  ss_mesh *box;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(80, 80, 30), 1, &box, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(box, ss_mat4_translate(ss_vec3_make(0, 0, -15)), &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "slab", box, mi, NULL, &err), SS_OK, "%s", err.message);
  ss_light env;
  memset(&env, 0, sizeof env);
  snprintf(env.name, sizeof env.name, "sky");
  env.type = SS_LIGHT_ENVIRONMENT;
  env.value = ss_rgb_gray(1.0);
  env.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &env, NULL, &err), SS_OK);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static void compare(const config *c, int paths) {
  ss_halfspace_params hp;
  ss_halfspace_params_default(&hp);
  hp.medium.sigma_s = ss_rgb_gray(c->sigma_s);
  hp.medium.sigma_a = ss_rgb_gray(c->sigma_a);
  hp.medium.g = ss_rgb_gray(c->g);
  hp.medium.phase = c->phase;
  hp.eta = c->eta;
  hp.theta_i = c->theta_deg * SS_PI / 180.0;
  hp.thickness = INFINITY;
  hp.paths = (uint64_t)paths;
  hp.seed = 4;
  hp.threads = 1;
  ss_halfspace_result *ref;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(&hp, &ref, &err), SS_OK, "%s", err.message);

  ss_scene *s = slab_scene(c);
  const ss_integrator_ops *vp = ss_integrator_find("volpath");
  ss_running_stats st;
  ss_running_stats_init(&st);
  ss_path_stats ps;
  memset(&ps, 0, sizeof ps);
  ss_rng rng;
  ss_rng_seed(&rng, 1, 2);
  double th = hp.theta_i;
  /* Rays toward the origin from the direction theta_i (in the x-z plane). */
  ss_vec3 dir = ss_vec3_make(sin(th), 0.0, -cos(th));
  for (int i = 0; i < paths; ++i) {
    ss_ray ray = {ss_vec3_madd(ss_vec3_make(0, 0, 0), dir, -5.0), dir, 0.0, INFINITY};
    ss_rgb L = vp->li(s, NULL, ray, &rng, &ps);
    ss_running_stats_add(&st, L.c[0]);
  }
  double expected = ref->reflectance.value + ref->specular.value;
  double se = sqrt(pow(ss_running_stats_stderr(&st), 2) + pow(ref->reflectance.error, 2));
  cr_expect(fabs(st.mean - expected) <= 3.0 * se,
            "sigma_s %g sigma_a %g g %g eta %g theta %g: volpath %.5f vs halfspace %.5f "
            "(R %.5f + Fr %.5f), 3 se = %.5f",
            c->sigma_s, c->sigma_a, c->g, c->eta, c->theta_deg, st.mean, expected,
            ref->reflectance.value, ref->specular.value, 3.0 * se);
  ss_halfspace_result_destroy(ref);
  ss_scene_destroy(s);
}

Test(slab_vs_halfspace, index_matched_isotropic_normal_incidence) {
  config c = {1.0, 0.1, 0.0, 1.0, 0.0, SS_PHASE_ISOTROPIC};
  compare(&c, 60000);
}

Test(slab_vs_halfspace, smooth_boundary_forward_scattering_oblique_incidence) {
  config c = {2.0, 0.2, 0.7, 1.33, 45.0, SS_PHASE_HG};
  compare(&c, 60000);
}

Test(slab_vs_halfspace, index_matched_gaussian_phase) {
  config c = {1.5, 0.1, 0.9, 1.0, 30.0, SS_PHASE_GAUSS};
  compare(&c, 60000);
}
