/* Light sampling: the estimators built on ss_light_sample_li reproduce the
 * analytic irradiance of each light type, and ss_light_pdf_li agrees with
 * the density the sampler reports. */
#include <criterion/criterion.h>

#include "subsurf/accel.h"
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

/* Irradiance at ref (normal n) from light l by n samples: mean and standard
 * error; every sample's density checked against ss_light_pdf_li at its hit. */
static void irradiance(const ss_light *l, ss_vec3 ref, ss_vec3 n, int count, uint64_t seed,
                       ss_running_stats *st) {
  ss_running_stats_init(st);
  ss_rng rng;
  ss_rng_seed(&rng, seed, 7);
  for (int i = 0; i < count; ++i) {
    ss_light_sample s;
    double e = 0.0;
    if (ss_light_sample_li(l, ref, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &s)) {
      e = s.li.c[0] * fmax(0.0, ss_vec3_dot(s.wi, n)) / s.pdf;
      ss_hit hit;
      memset(&hit, 0, sizeof hit);
      hit.p = s.p;
      hit.ng = s.n;
      cr_expect_float_eq(ss_light_pdf_li(l, ref, s.wi, &hit), s.pdf, 1e-9 * s.pdf);
    }
    ss_running_stats_add(st, e);
  }
}

Test(lights, round_light_sampled_in_its_cone_gives_the_same_irradiance_with_less_noise) {
  /* A tessellated sphere light off to the side of a tilted receiver: cone
   * sampling (bound to an accel) and area sampling estimate the same
   * irradiance, the cone's with a smaller variance per sample. */
  ss_mesh *mesh;
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(2.0, 2, &mesh, &err), SS_OK);
  ss_accel *accel;
  const ss_mesh *meshes[1] = {mesh};
  cr_assert_eq(ss_accel_create(meshes, 1, &accel, &err), SS_OK, "%s", err.message);
  ss_light area = make(SS_LIGHT_AREA, ss_rgb_gray(10.0));
  area.shape = 0;
  cr_assert_eq(ss_light_init(&area, mesh, &err), SS_OK, "%s", err.message);
  cr_assert(area.round, "a sphere is round");
  ss_light cone = area;
  ss_light_bind(&cone, accel);
  cr_assert(cone.accel == accel);
  ss_vec3 ref = ss_vec3_make(3.0, 1.0, -5.0), n = ss_vec3_normalize(ss_vec3_make(0.2, 0, 1));
  ss_running_stats a, c;
  irradiance(&area, ref, n, 40000, 3, &a);
  irradiance(&cone, ref, n, 40000, 5, &c);
  double se = hypot(ss_running_stats_stderr(&a), ss_running_stats_stderr(&c));
  cr_expect(fabs(a.mean - c.mean) < 4.0 * se, "area %.5f, cone %.5f, +- %.5f", a.mean, c.mean, se);
  cr_expect(ss_running_stats_stderr(&c) < 0.5 * ss_running_stats_stderr(&a),
            "cone standard error %.3g, area %.3g", ss_running_stats_stderr(&c),
            ss_running_stats_stderr(&a));
  ss_light_free(&area);
  ss_accel_destroy(accel);
  ss_mesh_destroy(mesh);
}

Test(lights, cone_sampling_falls_back_to_area_inside_the_sphere_and_for_flat_lights) {
  ss_mesh *ico, *quad;
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(2.0, 0, &ico, &err), SS_OK);
  cr_assert_eq(ss_shape_quad(2.0, 2.0, 1, 1, &quad, &err), SS_OK);
  ss_accel *accel;
  const ss_mesh *meshes[2] = {ico, quad};
  cr_assert_eq(ss_accel_create(meshes, 2, &accel, &err), SS_OK, "%s", err.message);
  ss_light l = make(SS_LIGHT_AREA, ss_rgb_gray(1.0));
  l.shape = 0;
  cr_assert_eq(ss_light_init(&l, ico, &err), SS_OK, "%s", err.message);
  ss_light_bind(&l, accel);
  /* Outside the icosahedron, inside its bounding sphere (its faces lie at
   * 0.79 of the radius): sampled by area, p = d^2 / (cos_l A). */
  ss_vec3 ref = ss_vec3_make(0.0, 0.0, 0.0);
  int found = 0;
  for (int i = 0; i < 20 && !found; ++i) {
    ss_vec3 dir = ss_vec3_normalize(ss_vec3_make(1.0 + 0.1 * i, 0.3, 0.7));
    for (int k = 0; k < 200 && !found; ++k) {
      ss_vec3 q = ss_vec3_scale(dir, 1.6 + 0.002 * k);
      ss_light_sample s;
      for (int j = 0; j < 64; ++j) {
        if (ss_light_sample_li(&l, q, (j + 0.5) / 64.0, 0.37, &s)) {
          double cos_l = -ss_vec3_dot(s.wi, s.n);
          cr_expect_float_eq(s.pdf, s.dist * s.dist / (cos_l * l.area), 1e-9 * s.pdf);
          found = 1;
          ref = q;
          break;
        }
      }
    }
  }
  cr_expect(found, "some point between the faces and the bounding sphere sees a face");
  cr_expect(ss_vec3_length(ref) < l.bound_radius);
  ss_light flat = make(SS_LIGHT_AREA, ss_rgb_gray(1.0));
  flat.shape = 1;
  cr_assert_eq(ss_light_init(&flat, quad, &err), SS_OK, "%s", err.message);
  ss_light_bind(&flat, accel);
  cr_expect(!flat.round && flat.accel == NULL, "a flat light is sampled by area");
  ss_light_free(&l);
  ss_light_free(&flat);
  ss_accel_destroy(accel);
  ss_mesh_destroy(ico);
  ss_mesh_destroy(quad);
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
  /* pbrt-v3's falloff: t^4, t the place of cos(25 deg) between the cones'
   * cosines; pbrt-v4's smoothstep when asked. */
  double c = cos(25.0 * SS_PI / 180.0), c_out = cos(30.0 * SS_PI / 180.0),
         c_in = cos(20.0 * SS_PI / 180.0), t = (c - c_out) / (c_in - c_out);
  cr_expect_float_eq(s.li.c[0], full * t * t * t * t, 1e-12, "25 deg: %g", s.li.c[0]);
  l.spot_smoothstep = 1;
  cr_assert(ss_light_sample_li(&l, ss_vec3_make(x, 0, 0), 0.5, 0.5, &s));
  cr_expect_float_eq(s.li.c[0], full * t * t * (3.0 - 2.0 * t), 1e-12, "smoothstep: %g", s.li.c[0]);
  cr_expect(
      !ss_light_sample_li(&l, ss_vec3_make(2.0 * tan(35.0 * SS_PI / 180.0), 0, 0), 0.5, 0.5, &s),
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
