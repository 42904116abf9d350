/* Manifold next-event estimation in volpath (src/render/integrators/mnee.h):
 * on a smooth-boundary sphere lit by a small sphere light, and on a core
 * nested in a clear glass shell (a chain of two refractions), the image
 * with MNEE equals the one without it within the Monte Carlo error, with
 * far less variance; a point light equals the limit of a shrinking sphere
 * light of the same power (on both) and a directional light that of a
 * receding point light; scenes/skin_sphere.json keeps its mean; the
 * point-light scenes are lit only through MNEE; sampled toward an area
 * light at a rate below 1 (mnee_solid_angle below the light's), MNEE
 * still equals phase sampling alone and traces fewer rays in proportion,
 * delta lights are sampled at every vertex whatever the option, and a
 * scene lit by its environment alone traces no MNEE rays; bad options are
 * refused naming them. Tolerances: K_SIGMA standard errors of the difference (plus, for
 * the limits, the geometric difference at the size used, bounded below). */
#include "subsurf/integrator.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"
#include "subsurf/stats.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define K_SIGMA 4.5
#define RES 4

/* The scene's media, materials and first shapes: a unit icosphere of an
 * RGB medium behind a smooth boundary of eta 1.33, or (SHELL) a core of
 * that medium and boundary, radius 0.6, nested by priority in a clear
 * glass sphere of eta 1.5 (two smooth interfaces in series). */
#define MEDIUM                                                                                     \
  "\"media\": [{\"name\": \"m\", \"sigma_s\": [2, 3, 4], \"sigma_a\": [0.1, 0.3, 0.6]}],\n"
#define TRANSLUCENT                                                                                \
  "{\"name\": \"t\", \"type\": \"translucent\", \"boundary\": \"smooth\", \"eta\": 1.33,"          \
  " \"medium\": \"m\", \"priority\": 2}"
#define BALL                                                                                       \
  MEDIUM "\"materials\": [" TRANSLUCENT "],\n"                                                     \
         "\"shapes\": [{\"name\": \"ball\", \"type\": \"sphere\", \"subdivisions\": 5, "           \
         "\"material\": \"t\"}"
#define SHELL                                                                                      \
  MEDIUM "\"materials\": [" TRANSLUCENT ",\n"                                                      \
         "  {\"name\": \"glass\", \"type\": \"dielectric\", \"eta\": 1.5, \"priority\": 1}],\n"    \
         "\"shapes\": [{\"name\": \"shell\", \"type\": \"sphere\", \"subdivisions\": 5,"           \
         " \"material\": \"glass\"},\n"                                                            \
         " {\"name\": \"core\", \"type\": \"sphere\", \"subdivisions\": 5, \"radius\": 0.6,"       \
         " \"material\": \"t\"}"

/* `body` (BALL or SHELL) seen by a RES x RES camera whose every pixel sees
 * it; `shapes` is the scene's further shapes and `lights` its lights JSON,
 * `options` the integrator's extra keys. */
static ss_scene *scene_of(const char *body, const char *shapes, const char *lights,
                          const char *options) {
  char text[4096];
  snprintf(text, sizeof text,
           "{\"camera\": {\"position\": [0, 0, 5], \"fov\": 18, \"resolution\": [%d, %d]},\n"
           " %s%s],\n"
           " \"lights\": [%s],\n"
           " \"integrator\": {\"type\": \"volpath\"%s}}\n",
           RES, RES, body, shapes, lights, options);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_parse_json(text, "test", NULL, &s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_scene *sphere_scene(const char *shapes, const char *lights, const char *options) {
  return scene_of(BALL, shapes, lights, options);
}

/* Mean, standard error and per-sample variance of n samples over the
 * pixels with volpath and the scene's options. */
typedef struct {
  double mean[3], se[3], var[3], seconds;
  double shadow_rays; /* per sample (MNEE's seed, projection and shadow rays among them) */
} estimate;

static estimate run(const ss_scene *s, int n, uint64_t seed) {
  const ss_integrator_ops *ops = ss_integrator_find("volpath");
  void *state = NULL;
  ss_error err;
  cr_assert_eq(ops->prepare(s, &state, &err), SS_OK, "%s", err.message);
  ss_running_stats st[3];
  for (int c = 0; c < 3; ++c) {
    ss_running_stats_init(&st[c]);
  }
  ss_path_stats ps;
  memset(&ps, 0, sizeof ps);
  double t0 = ss_seconds();
  for (int i = 0; i < n; ++i) {
    int w = s->camera.width, h = s->camera.height;
    ss_rgb v =
        ss_render_sample(s, ops, state, i % w, (i / w) % h, (uint32_t)(i / (w * h)), seed, &ps);
    for (int c = 0; c < 3; ++c) {
      cr_assert(isfinite(v.c[c]));
      ss_running_stats_add(&st[c], v.c[c]);
    }
  }
  estimate e;
  e.seconds = ss_seconds() - t0;
  e.shadow_rays = (double)ps.shadow_rays / n;
  for (int c = 0; c < 3; ++c) {
    e.mean[c] = st[c].mean;
    e.se[c] = ss_running_stats_stderr(&st[c]);
    e.var[c] = ss_running_stats_variance(&st[c]);
  }
  ops->release(state);
  return e;
}

/* |a - b| within K_SIGMA standard errors plus `slack` (relative to b). */
static void expect_equal(const estimate *a, const estimate *b, double slack, const char *what) {
  for (int c = 0; c < 3; ++c) {
    double se = hypot(a->se[c], b->se[c]);
    cr_expect(fabs(a->mean[c] - b->mean[c]) <= K_SIGMA * se + slack * fabs(b->mean[c]),
              "%s, channel %d: %.5g +- %.2g vs %.5g +- %.2g", what, c, a->mean[c], a->se[c],
              b->mean[c], b->se[c]);
    cr_log_info("%s, channel %d: %.5g +- %.2g vs %.5g +- %.2g", what, c, a->mean[c], a->se[c],
                b->mean[c], b->se[c]);
  }
}

#define LAMP_SHAPE(r)                                                                              \
  ", {\"name\": \"lamp\", \"type\": \"sphere\", \"radius\": " #r ", \"center\": [2.5, 1.5, 2],"    \
  " \"subdivisions\": 3}"
#define LAMP_LIGHT(l)                                                                              \
  "{\"name\": \"lamp\", \"type\": \"area\", \"shape\": \"lamp\", \"radiance\": " #l "}"

/* Every vertex: mnee_solid_angle above 4 pi, which no light subtends. */
#define EVERY_VERTEX ", \"mnee_solid_angle\": 100"

/* MNEE on, a sample at every vertex, against phase sampling alone (4x its
 * samples) under a sphere light of radius 0.3: equal means, and the
 * per-sample variance at least `min_gain` times lower with MNEE. */
static void expect_mnee_equals_phase_sampling(const char *body, int n, double min_gain,
                                              const char *what) {
  ss_scene *on = scene_of(body, LAMP_SHAPE(0.3), LAMP_LIGHT(40), ", \"mnee\": 1" EVERY_VERTEX);
  ss_scene *off = scene_of(body, LAMP_SHAPE(0.3), LAMP_LIGHT(40), ", \"mnee\": 0");
  estimate a = run(on, n, 1), b = run(off, 4 * n, 2);
  expect_equal(&a, &b, 0.0, what);
  for (int c = 0; c < 3; ++c) {
    double ratio = b.var[c] / a.var[c];
    cr_log_info("%s, channel %d: variance per sample off/on %.1f, time per sample on/off %.2f",
                what, c, ratio, (a.seconds / n) / (b.seconds / (4 * n)));
    cr_expect(ratio > min_gain, "%s, channel %d: variance ratio %.2f", what, c, ratio);
  }
  ss_scene_destroy(on);
  ss_scene_destroy(off);
}

Test(mnee, equals_phase_sampling_within_the_error_with_far_less_variance) {
  expect_mnee_equals_phase_sampling(BALL, 16000, 5.0, "mnee on vs off");
}

/* The chain of two: a core nested in a clear glass shell. */
Test(mnee, through_a_glass_shell_equals_phase_sampling_with_less_variance) {
  ss_scene *s = scene_of(SHELL, "", "", "");
  cr_assert(s->nested_material >= 0, "the core is not nested");
  ss_scene_destroy(s);
  expect_mnee_equals_phase_sampling(SHELL, 64000, 3.0, "shell: mnee on vs off");
}

/* mnee_solid_angle 0.0023 sr: a sample toward the lamp (0.015-0.044 sr
 * at the medium, its bounding sphere's) at 5-15 % of the vertices. The
 * MIS weights carry the rate (the phase-sampled path takes the weight of
 * the samples not taken): the mean equals phase
 * sampling alone (a weight without the rate would lose 90 % of MNEE's
 * share of the light, most of it here: 6.6 and 8.2 standard errors of the
 * difference, measured), and the rays traced per sample fall toward the
 * rate's share (MNEE's rays are nearly all of them at every vertex). */
static void expect_rate_keeps_the_mean(const char *body, int n, const char *what) {
  ss_scene *low = scene_of(body, LAMP_SHAPE(0.3), LAMP_LIGHT(40), ", \"mnee_solid_angle\": 0.0023");
  ss_scene *full = scene_of(body, LAMP_SHAPE(0.3), LAMP_LIGHT(40), EVERY_VERTEX);
  ss_scene *off = scene_of(body, LAMP_SHAPE(0.3), LAMP_LIGHT(40), ", \"mnee\": 0");
  estimate a = run(low, n, 21), f = run(full, n / 8, 22), b = run(off, 4 * n, 23);
  expect_equal(&a, &b, 0.0, what);
  cr_log_info("%s: shadow rays per sample %.2f, %.2f at every vertex", what, a.shadow_rays,
              f.shadow_rays);
  cr_expect(a.shadow_rays < 0.25 * f.shadow_rays, "%s: %.2f rays per sample, %.2f at every vertex",
            what, a.shadow_rays, f.shadow_rays);
  ss_scene_destroy(low);
  ss_scene_destroy(full);
  ss_scene_destroy(off);
}

/* On the ball and through the glass shell (a chain of two). */
Test(mnee, at_a_low_rate_equals_phase_sampling_with_fewer_rays) {
  expect_rate_keeps_the_mean(BALL, 16000, "5-15 % vs mnee off");
  expect_rate_keeps_the_mean(SHELL, 32000, "shell: 5-15 % vs mnee off");
}

/* Delta lights are sampled at every vertex: mnee_solid_angle leaves a
 * point-lit image as it is, bit for bit (no number is drawn for it). */
Test(mnee, the_rate_leaves_delta_lights_alone) {
  const char *point = "{\"name\": \"p\", \"type\": \"point\", \"position\": [2.5, 1.5, 2],"
                      " \"intensity\": 2}";
  ss_scene *low = sphere_scene("", point, ", \"mnee_solid_angle\": 1e-6");
  ss_scene *full = sphere_scene("", point, "");
  estimate a = run(low, 2000, 31), b = run(full, 2000, 31);
  for (int c = 0; c < 3; ++c) {
    cr_expect(a.mean[c] > 10.0 * a.se[c], "channel %d: the point light does not light it", c);
    cr_expect_eq(a.mean[c], b.mean[c], "channel %d: %.17g at 1e-6 sr, %.17g by default", c,
                 a.mean[c], b.mean[c]);
  }
  ss_scene_destroy(low);
  ss_scene_destroy(full);
}

/* A scene lit by its environment alone: nothing for MNEE to solve for, so
 * no ray is traced for it (volpath traces no other shadow ray behind a
 * smooth boundary), and the image is phase sampling's. */
Test(mnee, an_environment_alone_costs_no_mnee_rays) {
  const char *sky = "{\"name\": \"sky\", \"type\": \"environment\", \"radiance\": 1}";
  ss_scene *on = sphere_scene("", sky, ", \"mnee\": 1");
  ss_scene *off = sphere_scene("", sky, ", \"mnee\": 0");
  estimate a = run(on, 2000, 41), b = run(off, 2000, 41);
  cr_expect_eq(a.shadow_rays, 0.0, "%.3f shadow rays per sample", a.shadow_rays);
  for (int c = 0; c < 3; ++c) {
    cr_expect(a.mean[c] > 0.0);
    cr_expect_eq(a.mean[c], b.mean[c], "channel %d: %.17g on, %.17g off", c, a.mean[c], b.mean[c]);
  }
  ss_scene_destroy(on);
  ss_scene_destroy(off);
}

/* A point light at the lamp's centre against sphere lights of the same
 * power (pi L A = 4 pi I, A the faceted sphere's area) shrinking onto it. */
static void expect_point_light_limit(const char *body, uint64_t seed, const char *what) {
  const double intensity = 2.0;
  ss_scene *point = scene_of(body, "",
                             "{\"name\": \"p\", \"type\": \"point\", \"position\": [2.5, 1.5, 2],"
                             " \"intensity\": 2}",
                             ", \"mnee\": 1");
  estimate p = run(point, 16000, seed);
  cr_expect(p.mean[0] > 10.0 * p.se[0], "%s: the point light does not light the medium", what);
  static const double radii[] = {0.2, 0.02};
  for (int i = 0; i < 2; ++i) {
    ss_mesh *m;
    ss_error err;
    cr_assert_eq(ss_shape_icosphere(radii[i], 3, &m, &err), SS_OK);
    double radiance = 4.0 * intensity / ss_mesh_area(m);
    ss_mesh_destroy(m);
    char shape[256], light[256];
    snprintf(shape, sizeof shape,
             ", {\"name\": \"lamp\", \"type\": \"sphere\", \"radius\": %.17g,"
             " \"center\": [2.5, 1.5, 2], \"subdivisions\": 3}",
             radii[i]);
    snprintf(light, sizeof light,
             "{\"name\": \"lamp\", \"type\": \"area\", \"shape\": \"lamp\", \"radiance\": %.17g}",
             radiance);
    ss_scene *sphere = scene_of(body, shape, light, ", \"mnee\": 1");
    estimate a = run(sphere, 16000, seed + 1);
    char label[96];
    snprintf(label, sizeof label, "%s: sphere light of radius %g vs point light", what, radii[i]);
    /* The finite light differs by O((r / distance)^2): 1 % at r = 0.2. */
    expect_equal(&a, &p, radii[i] > 0.1 ? 0.01 : 0.0, label);
    ss_scene_destroy(sphere);
  }
  ss_scene_destroy(point);
}

Test(mnee, point_light_equals_the_limit_of_a_shrinking_sphere_light) {
  expect_point_light_limit(BALL, 3, "ball");
}

Test(mnee, through_a_glass_shell_a_point_light_equals_the_limit_of_a_sphere_light) {
  expect_point_light_limit(SHELL, 11, "shell");
}

/* A directional light against a point light 1000 units away along it with
 * intensity E d^2 (the same irradiance; the difference is O(1 / d)). */
Test(mnee, directional_light_equals_the_limit_of_a_receding_point_light) {
  ss_scene *dir = sphere_scene("",
                               "{\"name\": \"sun\", \"type\": \"directional\","
                               " \"direction\": [-0.6, -0.48, -0.64], \"irradiance\": 1}",
                               ", \"mnee\": 1");
  ss_scene *far =
      sphere_scene("",
                   "{\"name\": \"p\", \"type\": \"point\", \"position\": [600, 480, 640],"
                   " \"intensity\": 1e6}",
                   ", \"mnee\": 1");
  estimate a = run(dir, 16000, 5), b = run(far, 16000, 6);
  cr_expect(a.mean[0] > 10.0 * a.se[0], "the directional light does not light the medium");
  expect_equal(&a, &b, 0.0, "directional vs distant point light");
  ss_scene_destroy(dir);
  ss_scene_destroy(far);
}

/* Options out of range are refused before the first sample, naming them. */
Test(mnee, bad_options_are_refused_naming_them) {
  static const struct {
    const char *option, *needle;
  } cases[] = {
      {", \"mnee_iterations\": 0", "mnee_iterations"},
      {", \"mnee_iterations\": 2.5", "mnee_iterations"},
      {", \"mnee_tolerance\": 0", "mnee_tolerance"},
      {", \"mnee_tolerance\": -1e-6", "mnee_tolerance"},
      {", \"mnee\": 2", "mnee"},
      {", \"mnee_solid_angle\": 0", "mnee_solid_angle"},
      {", \"mnee_solid_angle\": -1", "mnee_solid_angle"},
  };
  const ss_integrator_ops *ops = ss_integrator_find("volpath");
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    ss_scene *s = sphere_scene("", "", cases[i].option);
    void *state = NULL;
    ss_error err;
    cr_expect_eq(ops->prepare(s, &state, &err), SS_ERR_INVALID_ARGUMENT, "%s accepted",
                 cases[i].option);
    cr_expect(strstr(err.message, cases[i].needle), "%s: '%s'", cases[i].option, err.message);
    ss_scene_destroy(s);
  }
  /* NaN cannot be written in a scene file; the library refuses it too. */
  ss_scene *s = sphere_scene("", "", "");
  ss_error err;
  cr_assert_eq(ss_scene_set_integrator_option(s, "mnee_tolerance", NAN, &err), SS_OK);
  void *state = NULL;
  cr_expect_eq(ops->prepare(s, &state, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "mnee_tolerance"), "%s", err.message);
  ss_scene_destroy(s);
}

/* A bundled scene seen through 4 x 4 pixels on the sphere (a narrower view
 * of the same camera). */
static ss_scene *bundled(const char *name) {
  const char *root = getenv("SUBSURF_SOURCE_DIR");
  cr_assert_not_null(root, "SUBSURF_SOURCE_DIR is not set");
  char path[1024];
  snprintf(path, sizeof path, "%s/scenes/%s", root, name);
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_read_json(path, &s, &err), SS_OK, "%s", err.message);
  s->camera.width = s->camera.height = RES;
  s->camera.fov_deg = 18.0;
  cr_assert_eq(ss_camera_init(&s->camera, &err), SS_OK);
  return s;
}

/* The reference scene's mean with MNEE on and off. */
Test(mnee, skin_sphere_scene_keeps_its_mean) {
  ss_scene *s = bundled("skin_sphere.json");
  ss_error err;
  estimate e[2];
  for (int on = 0; on < 2; ++on) {
    cr_assert_eq(ss_scene_set_integrator_option(s, "mnee", on, &err), SS_OK);
    e[on] = run(s, on ? 8000 : 32000, 7 + (uint64_t)on);
  }
  expect_equal(&e[1], &e[0], 0.0, "skin_sphere.json, mnee on vs off");
  ss_scene_destroy(s);
}

/* A bundled point-light scene: lit through MNEE, black without it. */
static void expect_lit_only_through_mnee(const char *name) {
  ss_scene *s = bundled(name);
  ss_error err;
  estimate on = run(s, 2000, 9);
  cr_assert_eq(ss_scene_set_integrator_option(s, "mnee", 0, &err), SS_OK);
  estimate off = run(s, 2000, 9);
  for (int c = 0; c < 3; ++c) {
    cr_expect(on.mean[c] > 10.0 * on.se[c], "channel %d: %g +- %g", c, on.mean[c], on.se[c]);
    cr_expect_eq(off.mean[c], 0.0, "channel %d lit without MNEE: %g", c, off.mean[c]);
  }
  ss_scene_destroy(s);
}

Test(mnee, point_light_scene_is_lit_only_through_mnee) {
  expect_lit_only_through_mnee("skin_sphere_point.json");
}

/* Through two smooth interfaces in series (a chain of two refractions). */
Test(mnee, skin_in_glass_scene_is_lit_only_through_the_chain) {
  expect_lit_only_through_mnee("skin_in_glass.json");
}
