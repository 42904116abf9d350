/* Light sampling: the estimators built on ss_light_sample_li reproduce the
 * analytic irradiance of each light type, and ss_light_pdf_li agrees with
 * the density the sampler reports. */
#include <criterion/criterion.h>

#include "subsurf/light.h"
#include "subsurf/rng.h"
#include "subsurf/stats.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static ss_light make(ss_light_type type, ss_rgb value) {
  ss_light l;
  memset(&l, 0, sizeof l);
  l.type = type;
  l.value = value;
  l.shape = -1;
  snprintf(l.name, sizeof l.name, "test");
  return l;
}

Test(lights, sphere_area_light_gives_the_analytic_irradiance) {
  /* A sphere of radius r and radiance L seen from distance d, on a surface
   * facing its centre: E = pi L (r / d)^2 (the sphere subtends a cone of
   * sin(alpha) = r / d). Tessellation makes the mesh slightly smaller. */
  const double r = 2.0, d = 6.0, radiance = 10.0;
  ss_mesh *mesh;
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(r, 5, &mesh, &err), SS_OK);
  ss_light l = make(SS_LIGHT_AREA, ss_rgb_gray(radiance));
  l.shape = 0;
  cr_assert_eq(ss_light_init(&l, mesh, &err), SS_OK, "%s", err.message);
  ss_vec3 ref = ss_vec3_make(0, 0, -d), n = ss_vec3_make(0, 0, 1);
  ss_running_stats st;
  ss_running_stats_init(&st);
  ss_rng rng;
  ss_rng_seed(&rng, 3, 4);
  for (int i = 0; i < 200000; ++i) {
    ss_light_sample s;
    double e = 0.0;
    if (ss_light_sample_li(&l, ref, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &s)) {
      e = s.li.c[0] * fmax(0.0, ss_vec3_dot(s.wi, n)) / s.pdf;
      if (i % 1000 == 0) {
        /* The pdf of hitting that point from ref, as used by MIS. */
        ss_hit hit;
        memset(&hit, 0, sizeof hit);
        hit.p = s.p;
        hit.ng = s.n;
        cr_expect_float_eq(ss_light_pdf_li(&l, ref, s.wi, &hit), s.pdf, 1e-9 * s.pdf);
      }
    }
    ss_running_stats_add(&st, e);
  }
  double expected = SS_PI * radiance * (r / d) * (r / d);
  cr_expect(fabs(st.mean - expected) < 4.0 * ss_running_stats_stderr(&st) + 2e-3 * expected,
            "irradiance %.5f +- %.5f, expected %.5f", st.mean, ss_running_stats_stderr(&st),
            expected);
  ss_light_free(&l);
  ss_mesh_destroy(mesh);
}

Test(lights, beam_lights_its_cylinder_only) {
  ss_light l = make(SS_LIGHT_BEAM, ss_rgb_gray(2.0));
  l.position = ss_vec3_make(1, 1, 5);
  l.direction = ss_vec3_make(0, 0, -3);
  l.radius = 0.5;
  ss_error err;
  cr_assert_eq(ss_light_init(&l, NULL, &err), SS_OK, "%s", err.message);
  ss_light_sample s;
  cr_assert(ss_light_sample_li(&l, ss_vec3_make(1.3, 0.8, 0), 0.5, 0.5, &s));
  cr_expect(s.delta);
  cr_expect_float_eq(s.li.c[0], 2.0 / (SS_PI * 0.25), 1e-12);
  cr_expect_float_eq(s.wi.z, 1.0, 1e-12);
  cr_expect_float_eq(s.dist, 5.0, 1e-12);
  cr_expect(!ss_light_sample_li(&l, ss_vec3_make(1.6, 1, 0), 0.5, 0.5, &s), "outside radius");
  cr_expect(!ss_light_sample_li(&l, ss_vec3_make(1, 1, 6), 0.5, 0.5, &s), "behind the source");
}

Test(lights, spot_falls_off_between_its_cones) {
  ss_light l = make(SS_LIGHT_SPOT, ss_rgb_gray(4.0));
  l.position = ss_vec3_make(0, 0, 2);
  l.direction = ss_vec3_make(0, 0, -1);
  l.cone_angle = 30.0;
  l.falloff_angle = 20.0;
  ss_error err;
  cr_assert_eq(ss_light_init(&l, NULL, &err), SS_OK, "%s", err.message);
  ss_light_sample s;
  cr_assert(ss_light_sample_li(&l, ss_vec3_make(0, 0, 0), 0.5, 0.5, &s));
  cr_expect_float_eq(s.li.c[0], 1.0, 1e-12, "I / d^2 on the axis");
  double x = 2.0 * tan(25.0 * SS_PI / 180.0);
  cr_assert(ss_light_sample_li(&l, ss_vec3_make(x, 0, 0), 0.5, 0.5, &s));
  double full = 4.0 / (4.0 + x * x);
  cr_expect(s.li.c[0] > 0.0 && s.li.c[0] < full, "25 deg is in the falloff: %g", s.li.c[0]);
  cr_expect(!ss_light_sample_li(&l, ss_vec3_make(2.0 * tan(35.0 * SS_PI / 180.0), 0, 0), 0.5,
                                0.5, &s),
            "35 deg is outside the cone");
}

Test(lights, point_directional_and_environment) {
  ss_error err;
  ss_light p = make(SS_LIGHT_POINT, ss_rgb_gray(8.0));
  p.position = ss_vec3_make(0, 2, 0);
  cr_assert_eq(ss_light_init(&p, NULL, &err), SS_OK);
  ss_light_sample s;
  cr_assert(ss_light_sample_li(&p, ss_vec3_make(0, 0, 0), 0.1, 0.2, &s));
  cr_expect_float_eq(s.li.c[0], 2.0, 1e-12);
  ss_light d = make(SS_LIGHT_DIRECTIONAL, ss_rgb_gray(3.0));
  d.direction = ss_vec3_make(0, -2, 0);
  cr_assert_eq(ss_light_init(&d, NULL, &err), SS_OK);
  cr_assert(ss_light_sample_li(&d, ss_vec3_make(5, 5, 5), 0.1, 0.2, &s));
  cr_expect_float_eq(s.wi.y, 1.0, 1e-12);
  cr_expect(isinf(s.dist));
  ss_light e = make(SS_LIGHT_ENVIRONMENT, ss_rgb_gray(0.5));
  cr_assert_eq(ss_light_init(&e, NULL, &err), SS_OK);
  cr_assert(ss_light_sample_li(&e, ss_vec3_make(0, 0, 0), 0.3, 0.7, &s));
  cr_expect_float_eq(s.pdf, 1.0 / (4.0 * SS_PI), 1e-12);
  cr_expect_float_eq(ss_light_pdf_li(&e, ss_vec3_make(0, 0, 0), s.wi, NULL), s.pdf, 1e-12);
  ss_light bad = make(SS_LIGHT_DIRECTIONAL, ss_rgb_gray(1.0));
  cr_expect_eq(ss_light_init(&bad, NULL, &err), SS_ERR_INVALID_ARGUMENT, "zero direction");
}
