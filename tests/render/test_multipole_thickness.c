/* The multipole's local_thickness (issue 9): on a slab of known thickness
 * the render with the thickness measured by the integrator's probe ray at
 * each exit point equals the render with that thickness given explicitly,
 * and both differ from the half-space's (so the thickness is used). */
#include "subsurf/render.h"
#include "subsurf/scene.h"

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define SLAB 0.1 /* thickness: 0.6 and 0.9 diffusion lengths 1/sigma_tr in red and blue */

/* A 40 x 40 x SLAB slab of a multipole material with the given option,
 * top face at z = 0, under a directional light at 30 degrees, seen from
 * straight above through a 1 degree field of view. */
static ss_scene *slab(const char *option, const char *value) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  s->camera.width = 2;
  s->camera.height = 2;
  s->camera.position = ss_vec3_make(0, 0, 20);
  s->camera.target = ss_vec3_make(0, 0, 0);
  s->camera.up = ss_vec3_make(0, 1, 0);
  s->camera.fov_deg = 1.0;
  snprintf(s->integrator.name, sizeof s->integrator.name, "bssrdf");
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "medium");
  med.optics.sigma_s = ss_rgb_make(20.0, 15.0, 10.0);
  med.optics.sigma_a = ss_rgb_make(0.5, 1.0, 2.0);
  med.optics.phase = SS_PHASE_ISOTROPIC;
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK);
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "slab");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = SS_BOUNDARY_SMOOTH;
  m.eta = 1.3;
  m.lod = SS_LOD_BSSRDF;
  snprintf(m.bssrdf, sizeof m.bssrdf, "multipole");
  cr_assert_eq(ss_scene_add_medium(s, &med, &m.medium, &err), SS_OK, "%s", err.message);
  if (option) {
    cr_assert_eq(ss_bssrdf_params_set_option(&m.bssrdf_options, ss_bssrdf_model_find("multipole"),
                                             option, value, &err),
                 SS_OK, "%s", err.message);
  }
  cr_assert_eq(ss_scene_add_material(s, &m, NULL, &err), SS_OK, "%s", err.message);
  ss_mesh *box;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(40, 40, SLAB), 1, &box, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(box, ss_mat4_translate(ss_vec3_make(0, 0, -SLAB / 2)), &err),
               SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "slab", box, 0, NULL, &err), SS_OK, "%s", err.message);
  ss_light l;
  memset(&l, 0, sizeof l);
  snprintf(l.name, sizeof l.name, "sun");
  l.type = SS_LIGHT_DIRECTIONAL;
  l.direction = ss_vec3_make(0.5, 0.0, -sqrt(0.75));
  l.value = ss_rgb_gray(1.0);
  l.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

/* Mean and standard error per channel of n camera samples (fixed seed). */
static void estimate(const ss_scene *s, int n, double mean[3], double se[3]) {
  const ss_integrator_ops *ops = ss_integrator_find("bssrdf");
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  ss_path_stats stats;
  memset(&stats, 0, sizeof stats);
  for (int i = 0; i < n; ++i) {
    ss_rgb v = ss_render_sample(s, ops, NULL, i % 2, (i / 2) % 2, (uint32_t)(i / 4), 3, &stats);
    for (int c = 0; c < 3; ++c) {
      sum[c] += v.c[c];
      sum2[c] += v.c[c] * v.c[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum[c] / n;
    se[c] = sqrt(fmax(sum2[c] / n - mean[c] * mean[c], 0.0) / n);
  }
}

Test(multipole_thickness, local_thickness_on_a_slab_equals_its_explicit_thickness) {
  char d[32];
  snprintf(d, sizeof d, "%.17g", SLAB);
  ss_scene *explicit_d = slab("thickness", d), *local = slab("local_thickness", "true"),
           *halfspace = slab(NULL, NULL);
  cr_assert(ss_bssrdf_uses_thickness(ss_subsurface_bssrdf(local->subsurface, 0)));
  cr_assert(!ss_bssrdf_uses_thickness(ss_subsurface_bssrdf(explicit_d->subsurface, 0)));
  const int n = 400000;
  double me[3], se[3], ml[3], sl[3], mh[3], sh[3];
  estimate(explicit_d, n, me, se);
  estimate(local, n, ml, sl);
  estimate(halfspace, n, mh, sh);
  for (int c = 0; c < 3; ++c) {
    /* The same random numbers: only the measured thickness (SLAB to float
     * precision) differs. */
    cr_expect(fabs(ml[c] - me[c]) <= 1e-4 * me[c], "channel %d: local %.9g, explicit %.9g", c,
              ml[c], me[c]);
    cr_expect(fabs(mh[c] - me[c]) > 4.0 * (sh[c] + se[c]),
              "channel %d: the slab (%g +- %g) is not told from the half-space (%g +- %g)", c,
              me[c], se[c], mh[c], sh[c]);
  }
  ss_scene_destroy(explicit_d);
  ss_scene_destroy(local);
  ss_scene_destroy(halfspace);
}
