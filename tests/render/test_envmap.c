/* Environment maps: the sampling density is the one reported (chi-square
 * over the sphere) and integrates to one; the map is oriented as
 * documented; a constant map renders the uniform environment and a map
 * with one bright pixel the distant light of the same power, within
 * Monte Carlo error, in every integrator that sees the environment. */
#include "render/scene_builder.h"

#include "subsurf/chi2.h"
#include "subsurf/envmap.h"
#include "subsurf/integrator.h"
#include "subsurf/light.h"

#define W 64
#define H 32

static const char *const integrators[] = {"path", "volpath", "bssrdf"};

/* A W x H RGB image: `fill` everywhere, or the pattern of a sky with a sun
 * when fill < 0. */
static ss_image *make_image(double fill) {
  ss_image *img = ss_image_create(W, H, 3);
  cr_assert_not_null(img);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      float *p = ss_image_pixel(img, x, y);
      for (int c = 0; c < 3; ++c) {
        p[c] = fill >= 0.0 ? (float)fill
                           : (float)(0.2 + 0.1 * c + (y < H / 2 ? 1.0 : 0.05) * (x % 7) +
                                     (x == 40 && y == 9 ? 500.0 : 0.0));
      }
    }
  }
  return img;
}

static ss_envmap *make_map(ss_image *img, ss_vec3 up, ss_vec3 front, double rotation) {
  ss_envmap_frame f;
  ss_error err;
  cr_assert_eq(ss_envmap_frame_make(up, front, rotation, &f, NULL, &err), SS_OK, "%s", err.message);
  ss_envmap *m;
  cr_assert_eq(ss_envmap_create(img, &f, &m, &err), SS_OK, "%s", err.message);
  return m;
}

static int chi2_sample(void *ctx, double u1, double u2, double u3, ss_vec3 *dir) {
  (void)u3;
  double pdf;
  ss_rgb le;
  return ss_envmap_sample(ctx, u1, u2, dir, &pdf, &le);
}

static double chi2_pdf(void *ctx, ss_vec3 dir) {
  double pdf;
  ss_envmap_eval(ctx, dir, &pdf);
  return pdf;
}

Test(envmap, sampling_density_passes_a_chi_square_test, .timeout = 120) {
  ss_envmap *m = make_map(make_image(-1.0), ss_vec3_make(0.3, 1, 0.2), ss_vec3_make(0, 0, -1), 30);
  ss_chi2_sphere_options o;
  ss_chi2_sphere_options_default(&o);
  o.seed = 7;
  ss_chi2_result res;
  ss_chi2_test_sphere(chi2_sample, chi2_pdf, m, &o, &res);
  cr_expect_gt(res.p_value, 0.01, "%s", res.message);
  cr_expect(fabs(res.pdf_integral - 1.0) < 2e-3, "the density integrates to %.6f",
            res.pdf_integral);
  cr_expect_lt(res.invalid, o.samples / 100000 + 1, "%llu samples refused",
               (unsigned long long)res.invalid);
  ss_envmap_destroy(m);
}

Test(envmap, a_sample_reports_the_lookup_and_density_of_its_direction) {
  ss_envmap *m = make_map(make_image(-1.0), ss_vec3_make(0, 0, 1), ss_vec3_make(1, 0, 0), -70);
  ss_rng rng;
  ss_rng_seed(&rng, 1, 2);
  for (int i = 0; i < 20000; ++i) {
    ss_vec3 w;
    double pdf;
    ss_rgb le;
    if (!ss_envmap_sample(m, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &w, &pdf, &le)) {
      continue;
    }
    cr_assert_float_eq(ss_vec3_length(w), 1.0, 1e-12);
    double p_eval;
    ss_rgb e = ss_envmap_eval(m, w, &p_eval);
    cr_assert_float_eq(p_eval, pdf, 1e-9 * pdf, "sample %d", i);
    cr_assert(!memcmp(&e, &le, sizeof e), "sample %d: lookup %g, sample %g", i, e.c[0], le.c[0]);
  }
  ss_envmap_destroy(m);
}

Test(envmap, the_map_is_oriented_as_documented) {
  /* up +y, front -z turned 90 degrees about +y: the centre faces -x. */
  ss_image *img = make_image(1.0);
  ss_image_pixel(img, W / 2, H / 2)[0] = 7.0f;     /* centre */
  ss_image_pixel(img, 3 * W / 4, H / 2)[0] = 5.0f; /* a quarter turn right of it */
  ss_image_pixel(img, 0, 0)[0] = 3.0f;             /* at the top */
  ss_envmap *m = make_map(img, ss_vec3_make(0, 1, 0), ss_vec3_make(0, 0, -1), 90);
  const double e = 1e-3;
  /* Pixels span [u, u + 1/W) x [v, v + 1/H): each direction lies just
   * right of and below the pixel's corner. */
  cr_expect_eq(ss_envmap_eval(m, ss_vec3_normalize(ss_vec3_make(-1, -e, -e)), NULL).c[0], 7.0);
  /* right of a viewer looking along -x with +y up is front x up = -z */
  cr_expect_eq(ss_envmap_eval(m, ss_vec3_normalize(ss_vec3_make(e, -e, -1)), NULL).c[0], 5.0);
  /* u = 0 is behind the viewer (+x), its first column on the viewer's left */
  cr_expect_eq(ss_envmap_eval(m, ss_vec3_normalize(ss_vec3_make(e, 1, 1e-6)), NULL).c[0], 3.0);
  double omega;
  ss_vec3 d = ss_envmap_pixel_direction(m, W / 2, H / 2, &omega);
  cr_expect(d.x < -0.99, "the centre pixel looks along (%g, %g, %g)", d.x, d.y, d.z);
  double total = 0.0;
  for (int y = 0; y < H; ++y) {
    ss_envmap_pixel_direction(m, 0, y, &omega);
    total += omega * W;
  }
  cr_expect_float_eq(total, 4.0 * SS_PI, 1e-12);
  ss_envmap_destroy(m);
}

/* The mean and standard error of the 8 x 8 view of the floor under `env`
 * (plus `extra`, unless its type is the environment's) with integrator
 * `name`. */
static void render_floor(const char *name, ss_light env, const ss_light *extra, int spp,
                         double mean[3], double se[3]) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  test_sphere_view(s, 8, 8);
  test_add_floor(s, 0.0);
  cr_assert_eq(ss_scene_add_light(s, &env, NULL, &err), SS_OK, "%s", err.message);
  if (extra) {
    cr_assert_eq(ss_scene_add_light(s, extra, NULL, &err), SS_OK, "%s", err.message);
  }
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  const ss_integrator_ops *ops = ss_integrator_find(name);
  cr_assert_not_null(ops);
  void *state = NULL;
  if (ops->prepare) {
    cr_assert_eq(ops->prepare(s, &state, &err), SS_OK, "%s: %s", name, err.message);
  }
  test_image_mean(s, ops, state, spp, 5, mean, se);
  if (ops->release) {
    ops->release(state);
  }
  ss_scene_destroy(s);
}

static void expect_same(const char *what, const char *name, const double a[3], const double sa[3],
                        const double b[3], const double sb[3]) {
  for (int c = 0; c < 3; ++c) {
    double z = (a[c] - b[c]) / sqrt(sa[c] * sa[c] + sb[c] * sb[c]);
    cr_log_info("%s, %s, channel %d: %.5f +- %.5f vs %.5f +- %.5f (z %.2f)", what, name, c, a[c],
                sa[c], b[c], sb[c], z);
    cr_expect(fabs(z) < 4.0 && b[c] > 0.0, "%s, %s, channel %d: %.5f +- %.5f vs %.5f +- %.5f", what,
              name, c, a[c], sa[c], b[c], sb[c]);
  }
}

Test(envmap, a_constant_map_renders_the_uniform_environment, .timeout = 300) {
  ss_rgb value = ss_rgb_make(0.5, 1.0, 2.0);
  ss_light uniform = test_light("sky", SS_LIGHT_ENVIRONMENT, -1, value);
  for (size_t k = 0; k < sizeof integrators / sizeof integrators[0]; ++k) {
    ss_light mapped = test_light("sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_make(1, 2, 4));
    ss_image *img = make_image(0.5);
    mapped.map = make_map(img, ss_vec3_make(0, 1, 0.4), ss_vec3_make(1, 0, 0), 10);
    /* Seen directly the two are the same radiance, bit for bit. */
    for (int i = 0; i < 100; ++i) {
      ss_vec3 w = ss_sample_uniform_sphere((i + 0.5) / 100, fmod(i * 0.618034, 1.0));
      ss_rgb a = ss_light_le(&uniform, w, w), b = ss_light_le(&mapped, w, w);
      cr_assert(!memcmp(&a, &b, sizeof a));
    }
    double m1[3], s1[3], m2[3], s2[3];
    render_floor(integrators[k], uniform, NULL, 256, m1, s1);
    render_floor(integrators[k], mapped, NULL, 256, m2, s2);
    expect_same("constant map", integrators[k], m2, s2, m1, s1);
  }
}

Test(envmap, one_bright_pixel_equals_a_distant_light_of_its_power, .timeout = 300) {
  /* A pixel up and behind the camera (u near 0: opposite the map's centre,
   * which faces -z): the floor is lit, the camera never sees it. */
  const int px = 4, py = 8;
  const double radiance = 50.0;
  for (size_t k = 0; k < sizeof integrators / sizeof integrators[0]; ++k) {
    ss_image *img = make_image(0.0);
    for (int c = 0; c < 3; ++c) {
      ss_image_pixel(img, px, py)[c] = (float)(radiance * (1 + c) / 2.0);
    }
    ss_light mapped = test_light("sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_gray(1.0));
    mapped.map = make_map(img, ss_vec3_make(0, 1, 0), ss_vec3_make(0, 0, -1), 0);
    double omega;
    ss_vec3 d = ss_envmap_pixel_direction(mapped.map, px, py, &omega);
    cr_assert(d.y > 0.5 && d.z > 0.5, "the pixel looks along (%g, %g, %g)", d.x, d.y, d.z);
    ss_light sun =
        test_light("sun", SS_LIGHT_DIRECTIONAL, -1,
                   ss_rgb_make(radiance * omega * 0.5, radiance * omega, radiance * omega * 1.5));
    sun.direction = ss_vec3_neg(d);
    /* The distant light's scene needs an environment too: a black one. */
    ss_light black = test_light("sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_gray(0.0));
    double m1[3], s1[3], m2[3], s2[3];
    render_floor(integrators[k], mapped, NULL, 256, m1, s1);
    render_floor(integrators[k], black, &sun, 256, m2, s2);
    expect_same("bright pixel", integrators[k], m1, s1, m2, s2);
  }
}
