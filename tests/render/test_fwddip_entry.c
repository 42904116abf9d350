/* The forward scattering dipole's entry sampling (fwddip_entry.h): the
 * one-sample MIS of probe rays and the ballistic ray reports the density it
 * lands with (a brute-force histogram over distance shells against uniform
 * area sampling of a sphere), its MIS weights sum to one, and a render of a
 * thin slab lit from below (transmission, where the ballistic ray lands)
 * equals the model's own prediction with the strategy off, mixed and alone. */
#include "subsurf/accel.h"
#include "subsurf/fwddip.h"
#include "subsurf/fwddip_entry.h"
#include "subsurf/mesh.h"
#include "subsurf/render.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/scene.h"
#include "subsurf/transform.h"

#include "render/probe_sphere.h"
#include "render/scene_builder.h"
#include "render/shell_histogram.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* A forward-scattering medium (g = 0.9) in the unit icosphere, seen from an
 * oblique direction at the exit point, so that the ballistic ray crosses the
 * sphere and the probe chords cross the curved surface. */
static void setup(probe_sphere *f, const char *ballistic) {
  ss_error err;
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, 10.0, 0.5, 0.9);
  p.eta = 1.3;
  const ss_bssrdf_ops *ops = ss_bssrdf_model_find("fwddip");
  cr_assert_eq(ss_bssrdf_params_set_option(&p, ops, "ballistic", ballistic, &err), SS_OK, "%s",
               err.message);
  probe_sphere_setup(f, "fwddip", &p, ss_vec3_normalize(ss_vec3_make(0.6, 0.0, 0.8)));
}

Test(fwddip_entry, mis_weights_of_probe_and_ballistic_ray_sum_to_one) {
  probe_sphere f;
  setup(&f, "0.5");
  double beta = ss_fwddip_ballistic_fraction(f.bssrdf);
  cr_assert_eq(beta, 0.5);
  ss_rng rng;
  ss_rng_seed(&rng, 1, 2);
  int n[2] = {0, 0};
  for (int i = 0; i < 4000; ++i) {
    double u[5];
    probe_sphere_uniforms(&rng, u);
    ss_probe_sample s;
    unsigned long long q = 0;
    if (!ss_fwddip_entry_sample(&f.probe, u, &s, &q)) {
      continue;
    }
    double pb = ss_fwddip_entry_ballistic_pdf(&f.probe, &s.hit, 0, &q);
    double pp = ss_probe_pdf(&f.probe, &s.hit, -1, 0, &q);
    double wb = beta * pb / s.pdf, wp = (1.0 - beta) * pp / s.pdf;
    cr_assert(fabs(wb + wp - 1.0) < 1e-9, "weights %.12g + %.12g", wb, wp);
    int ballistic = s.axis < 0;
    cr_assert_gt(ballistic ? wb : wp, 0.0, "the sampling strategy has weight 0");
    cr_assert(fabs(ss_fwddip_entry_pdf(&f.probe, &s.hit, &q) / s.pdf - 1.0) < 1e-9);
    n[ballistic]++;
  }
  cr_assert_gt(n[0], 300, "%d probe samples", n[0]);
  cr_assert_gt(n[1], 1000, "%d ballistic samples", n[1]);
  probe_sphere_teardown(&f);
}

#define SHELLS 8

/* E[1{x_i in shell} / p(x_i)] is the sphere's area in the shell: measured
 * from the sampler, and by uniform area sampling of the mesh. */
static void check_histogram(const char *ballistic) {
  probe_sphere f;
  setup(&f, ballistic);
  const double dmax = 2.0; /* the diameter */
  double sum[SHELLS] = {0}, sum2[SHELLS] = {0};
  ss_rng rng;
  ss_rng_seed(&rng, 3, 4);
  const int n = 150000;
  probe_sphere_shell_sums(&f, ss_fwddip_entry_sample, &rng, n, dmax, SHELLS, 1, sum, sum2);
  long count[SHELLS] = {0};
  const int m = 400000;
  /* Every point of the sphere lies within its diameter of x_o. */
  shell_histogram_brute_force(f.mesh, f.probe.x_o, dmax * (1.0 + 1e-12), SHELLS, m, &rng, count);
  char label[64];
  snprintf(label, sizeof label, "ballistic %s,", ballistic);
  shell_histogram_expect_match(sum, sum2, n, count, m, ss_mesh_area(f.mesh), SHELLS, label);
  probe_sphere_teardown(&f);
}

Test(fwddip_entry, mixed_density_matches_a_brute_force_histogram_on_a_sphere) {
  check_histogram("0.5");
}

Test(fwddip_entry, ballistic_density_alone_matches_a_brute_force_histogram_on_a_sphere) {
  check_histogram("1");
}

/* A 200 x 200 x H slab (top face at z = 0) of a forward-scattering medium
 * behind a smooth boundary, lit from below by a directional light of unit
 * irradiance travelling along +z, seen straight down through a 1 degree
 * field of view: all the light is transmitted through the bottom face. */
#define SLAB_H 1.0

static ss_scene *slab_scene(const char *ballistic) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  test_slab_view(s);
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "medium");
  med.optics.sigma_s = ss_rgb_gray(10.0);
  med.optics.sigma_a = ss_rgb_gray(0.1);
  med.optics.phase = SS_PHASE_HG;
  med.optics.g = ss_rgb_gray(0.9);
  cr_assert_eq(ss_medium_init(&med, &err), SS_OK);
  int mi;
  cr_assert_eq(ss_scene_add_medium(s, &med, &mi, &err), SS_OK, "%s", err.message);
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "translucent");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = SS_BOUNDARY_SMOOTH;
  m.eta = 1.3;
  m.medium = mi;
  snprintf(m.bssrdf, sizeof m.bssrdf, "fwddip");
  ss_bssrdf_params_default(&m.bssrdf_options);
  cr_assert_eq(ss_bssrdf_params_set_option(&m.bssrdf_options, ss_bssrdf_model_find("fwddip"),
                                           "ballistic", ballistic, &err),
               SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_add_material(s, &m, NULL, &err), SS_OK, "%s", err.message);
  ss_mesh *slab;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(200, 200, SLAB_H), 1, &slab, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(slab, ss_mat4_translate(ss_vec3_make(0, 0, -0.5 * SLAB_H)), &err),
               SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "slab", slab, 0, NULL, &err), SS_OK, "%s", err.message);
  test_add_sun(s, ss_vec3_make(0.0, 0.0, 1.0));
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

/* The model's prediction: int S(x_i, -z; 0, +z) dA over the bottom face
 * (radially symmetric about the point below x_o), composite Simpson in
 * r = u^2 over [0, 40]. */
static double transmission_prediction(const ss_bssrdf *b) {
  const int n = 600;
  const double umax = sqrt(40.0), h = umax / n;
  ss_vec3 down = ss_vec3_make(0, 0, -1), up = ss_vec3_make(0, 0, 1);
  double sum = 0.0;
  for (int k = 1; k <= n; ++k) {
    double u = k * h, r = u * u, wgt = k == n ? 1.0 : (k % 2 ? 4.0 : 2.0), s[3];
    ss_bssrdf_query q = {
        ss_vec3_make(r, 0, -SLAB_H), down, down, ss_vec3_make(0, 0, 0), up, up, 0.0};
    ss_bssrdf_eval(b, &q, s);
    sum += wgt * h / 3.0 * 2.0 * 3.14159265358979323846 * r * s[0] * 2.0 * u;
  }
  return sum;
}

/* Returns the standard error of the render. */
static double check_transmission(const char *ballistic, int n) {
  ss_scene *s = slab_scene(ballistic);
  double want = transmission_prediction(ss_subsurface_bssrdf(s->subsurface, 0));
  double mean[3], se[3];
  test_estimate(s, n, 7, mean, se);
  cr_expect(fabs(mean[0] - want) < 4.0 * se[0] + 2e-3 * want,
            "ballistic %s: render %g +- %g, model %g (%+.2f%%)", ballistic, mean[0], se[0], want,
            100.0 * (mean[0] / want - 1.0));
  ss_scene_destroy(s);
  return se[0];
}

Test(fwddip_entry, thin_slab_transmission_render_equals_the_model_with_and_without_the_ray,
     .timeout = 300) {
  double se_probe = check_transmission("0", 8000);
  double se_mixed = check_transmission("0.5", 8000);
  check_transmission("1", 8000);
  /* Measured: 4.6x smaller (21x less variance) at 20000 samples. */
  cr_expect_lt(se_mixed, 0.5 * se_probe, "standard error %g mixed, %g probe rays alone", se_mixed,
               se_probe);
}
