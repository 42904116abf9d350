/* The multipole's local_thickness: on a slab of known thickness
 * the render with the thickness measured by the integrator's probe ray at
 * each exit point equals the render with that thickness given explicitly,
 * and both differ from the half-space's (so the thickness is used). */
#include "subsurf/scene.h"

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* The slab's thickness: 0.6 and 0.9 diffusion lengths 1/sigma_tr in red and
 * blue. */
#define SLAB 0.1

/* A 40 x 40 x SLAB slab of a multipole material (eta 1.3) with the given
 * option, top face at z = 0, under a directional light at 30 degrees, seen from
 * straight above through a 1 degree field of view. */
static ss_scene *slab(const char *option, const char *value) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  test_slab_view(s);
  int mi = test_add_translucent(s, ss_rgb_make(20.0, 15.0, 10.0), ss_rgb_make(0.5, 1.0, 2.0),
                                SS_BOUNDARY_SMOOTH, "multipole");
  if (option) {
    cr_assert_eq(ss_bssrdf_params_set_option(&s->materials[mi].bssrdf_options,
                                             ss_bssrdf_model_find("multipole"), option, value,
                                             &err),
                 SS_OK, "%s", err.message);
  }
  ss_mesh *box;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(40, 40, SLAB), 1, &box, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(box, ss_mat4_translate(ss_vec3_make(0, 0, -SLAB / 2)), &err),
               SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "slab", box, mi, NULL, &err), SS_OK, "%s", err.message);
  test_add_sun(s, ss_vec3_make(0.5, 0.0, -sqrt(0.75)));
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
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
  test_estimate(explicit_d, n, 3, me, se);
  test_estimate(local, n, 3, ml, sl);
  test_estimate(halfspace, n, 3, mh, sh);
  for (int c = 0; c < 3; ++c) {
    /* The same random numbers: only the measured thickness (SLAB to float
     * precision) differs. */
    cr_expect(fabs(ml[c] - me[c]) <= 1e-4 * me[c], "channel %d: local %.9g, explicit %.9g", c,
              ml[c], me[c]);
    cr_expect(fabs(mh[c] - me[c]) > 4.0 * (sh[c] + se[c]),
              "channel %d: the slab (%g +- %g) is not told from the half-space "
              "(%g +- %g)",
              c, me[c], se[c], mh[c], sh[c]);
  }
  ss_scene_destroy(explicit_d);
  ss_scene_destroy(local);
  ss_scene_destroy(halfspace);
}
