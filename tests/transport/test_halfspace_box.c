/* The half-space reference as a box lit by a diffuse spot (width and
 * spot_radius of ss_halfspace_params; Jakob et al. 2010's finite-element
 * validation, tests/validate/test_fem_fig10.c): light leaving through the
 * sides counts as transmitted, the spot's specular part is the
 * cosine-weighted mean of the Fresnel reflectance, and the exitance map
 * stays on the top face. */
#include "subsurf/fresnel.h"
#include "subsurf/halfspace.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

static void box_with_spot(ss_halfspace_params *p, double eta) {
  ss_halfspace_params_default(p);
  p->medium.sigma_s = ss_rgb_gray(1.0);
  p->medium.sigma_a = ss_rgb_gray(0.0);
  p->eta = eta;
  p->thickness = 3.0;
  p->width = 4.0;
  p->spot_radius = 0.5;
  p->paths = 20000;
  p->seed = 5;
  p->xmin = p->ymin = -3.0;
  p->xmax = p->ymax = 3.0;
  p->xbins = p->ybins = 6;
  p->want_map = 1;
}

static ss_halfspace_result *run(const ss_halfspace_params *p) {
  ss_halfspace_result *r = NULL;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(p, &r, &err), SS_OK, "%s", err.message);
  return r;
}

Test(halfspace_box, conservative_box_loses_nothing_through_top_bottom_and_sides) {
  ss_halfspace_params p;
  box_with_spot(&p, 1.0);
  ss_halfspace_result *r = run(&p);
  cr_expect_eq(r->specular.value, 0.0);
  cr_expect(fabs(r->reflectance.value + r->transmittance.value - 1.0) < 1e-12, "R + T = %.15f",
            r->reflectance.value + r->transmittance.value);
  /* the map's outer ring of bins lies beyond the box's sides (|x| > 2) */
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 6; ++i) {
      int outside = i == 0 || j == 0 || i == 5 || j == 5;
      cr_expect(outside ? r->map[j * 6 + i].value == 0.0 : r->map[j * 6 + i].value > 0.0,
                "bin %d %d: %g", i, j, r->map[j * 6 + i].value);
    }
  }
  /* sides exist: the same slab without them transmits less */
  p.width = INFINITY;
  ss_halfspace_result *slab = run(&p);
  cr_expect_gt(r->transmittance.value, slab->transmittance.value + 5.0 * r->transmittance.error);
  ss_halfspace_result_destroy(slab);
  ss_halfspace_result_destroy(r);
}

Test(halfspace_box, diffuse_spot_reflects_the_hemispherical_fresnel_mean) {
  ss_halfspace_params p;
  box_with_spot(&p, 1.4);
  ss_halfspace_result *r = run(&p);
  /* 2 int_0^1 Fr(mu) mu dmu, midpoint rule */
  double fr = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    double mu = (i + 0.5) / n;
    fr += 2.0 * ss_fresnel_dielectric(mu, 1.4) * mu / n;
  }
  cr_expect(fabs(r->specular.value - fr) < 4.0 * r->specular.error + 1e-6,
            "specular %g +- %g, expected %g", r->specular.value, r->specular.error, fr);
  double total = r->specular.value + r->reflectance.value + r->transmittance.value;
  cr_expect(fabs(total - 1.0) < 1e-12, "total %.15f", total);
  ss_halfspace_result_destroy(r);
}

Test(halfspace_box, spot_and_width_conflicts_are_named) {
  ss_halfspace_params p;
  ss_error err;
  box_with_spot(&p, 1.0);
  p.spot_radius = 2.0;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "spot radius"), "%s", err.message);
  box_with_spot(&p, 1.0);
  p.theta_i = 0.3;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "theta-i"), "%s", err.message);
  box_with_spot(&p, 1.0);
  p.n_theta_o = 1;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "width"), "%s", err.message);
  box_with_spot(&p, 1.0);
  p.width = -1.0;
  cr_expect_eq(ss_halfspace_validate(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "width"), "%s", err.message);
}
