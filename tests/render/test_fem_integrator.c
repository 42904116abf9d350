/* The `fem` integrator (Jakob et al. 2010, sec. 6.2): on a wide slab lit
 * by a distant light along its normal, far from the edges, the rendered
 * diffusion term equals the exact solution of the same boundary-value
 * problem on the half-space (the 1D Robin solution below) and agrees with
 * the `bssrdf` integrator's dipole render within the difference of the two
 * models' total reflectances; lit only by a diffuse ceiling, its indirect
 * light enters as the `bssrdf` integrator says, and without a reflector the
 * option indirect changes nothing; 1 and 2 threads render the same image;
 * bad options are refused naming the key; an open surface is refused. */
#include "subsurf/fresnel.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"

#include "render/scene_builder.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define SIGMA_S 1.0
#define SIGMA_A 0.1
#define ETA 1.3

/* A 10 x 5 x 10 slab (in mean free paths 11 x 5.5 x 11; the fluence decays
 * over 1/sigma_tr = 1.74) below a sun along -y, seen from straight above
 * through a 2 degree field of view (the central 0.7 x 0.7, 5 from the
 * sides), with the smooth boundary of eta 1.3 and the dipole model for the
 * `bssrdf` integrator. */
static ss_scene *slab_scene(const char *integrator) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  s->camera.width = 4;
  s->camera.height = 4;
  s->camera.position = ss_vec3_make(0, 20, 0);
  s->camera.target = ss_vec3_make(0, 0, 0);
  s->camera.up = ss_vec3_make(0, 0, -1);
  s->camera.fov_deg = 2.0;
  snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrator);
  int m = test_add_translucent(s, ss_rgb_gray(SIGMA_S), ss_rgb_gray(SIGMA_A), SS_BOUNDARY_SMOOTH,
                               "dipole");
  ss_mesh *mesh;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(10, 5, 10), 1, &mesh, &err), SS_OK);
  cr_assert_eq(ss_mesh_transform(mesh, ss_mat4_translate(ss_vec3_make(0, -2.5, 0)), &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "slab", mesh, m, NULL, &err), SS_OK, "%s", err.message);
  test_add_sun(s, ss_vec3_make(0, -1, 0));
  return s;
}

static void commit(ss_scene *s) {
  ss_error err;
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
}

static ss_film *render(const ss_scene *s, int threads, int spp, ss_status expect, ss_error *err) {
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  o.seed = 5;
  o.threads = threads;
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_status st = ss_render(s, &o, &film, &stats, err);
  cr_assert_eq(st, expect, "%s", st != SS_OK ? err->message : "rendered");
  return film;
}

static double image_mean(const ss_film *f) {
  double sum = 0.0;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      sum += ss_rgb_average(ss_film_pixel_mean(f, x, y));
    }
  }
  return sum / 16.0;
}

/* The half-space's exact solution of the FEM's problem under a uniform
 * refracted irradiance E: phi = phi0 exp(-sigma_tr z) with the boundary
 * condition phi/4 + (A/2) D dphi/dn = Gamma_s/Fdt (seed 003, eq. 38),
 * Gamma_s = E exp(-sigma_a/sigma_s'), so the exitance M_o = phi0/(2A) -
 * Gamma_s/A, seen along the normal as Ft(1) M_o/(pi eta^2 Fdt). */
static double robin_radiance(void) {
  double st = SIGMA_S + SIGMA_A, D = 1.0 / (3.0 * st), s_tr = sqrt(3.0 * SIGMA_A * st);
  double A = ss_fresnel_A(ETA), Fdt = 1.0 - ss_fresnel_diffuse_reflectance(ETA);
  double Ft = 1.0 - ss_fresnel_dielectric(1.0, ETA), E = Ft;
  double gamma = E * exp(-SIGMA_A / SIGMA_S);
  double phi0 = gamma / Fdt / (0.25 + 0.5 * A * D * s_tr);
  return Ft * (phi0 / (2.0 * A) - gamma / A) / (SS_PI * ETA * ETA * Fdt);
}

/* The same half-space with the rays' volume source (option volume_source):
 * the first scattering events E alpha' sigma exp(-sigma z) along the normal,
 * sigma = sigma_t', in D phi'' - sigma_a phi = -Q0 (seed 003, eq. 35,
 * isotropic) with phi/4 + (A/2) D dphi/dn = 0 (eq. 38, no Gamma_s):
 * phi = C exp(-sigma z) + B exp(-sigma_tr z), C = E alpha' sigma /
 * (sigma_a - D sigma^2), and the Robin condition at z = 0 gives
 * phi0 = C 2 A D (sigma_tr - sigma)/(1 + 2 A D sigma_tr); M_o = phi0/(2A).
 * (The 16 depth strata of fem_rays.c change phi0 by 0.1 % here.) */
static double robin_volume_radiance(void) {
  double st = SIGMA_S + SIGMA_A, D = 1.0 / (3.0 * st), s_tr = sqrt(3.0 * SIGMA_A * st);
  double A = ss_fresnel_A(ETA), Fdt = 1.0 - ss_fresnel_diffuse_reflectance(ETA);
  double Ft = 1.0 - ss_fresnel_dielectric(1.0, ETA), E = Ft;
  double C = E * (SIGMA_S / st) * st / (SIGMA_A - D * st * st);
  double phi0 = C * 2.0 * A * D * (s_tr - st) / (1.0 + 2.0 * A * D * s_tr);
  return Ft * phi0 / (2.0 * A) / (SS_PI * ETA * ETA * Fdt);
}

/* The dipole's diffuse reflectance (Jensen et al. 2001, eq. 5) integrated
 * over the slab's 10 x 10 top face about its centre (the `bssrdf`
 * integrator's probes stay on the object: its tail beyond the sides is
 * lost) and seen the same way: Ft(1) E R / pi with E = Ft(1). */
static double dipole_radiance(void) {
  double st = SIGMA_S + SIGMA_A, ap = SIGMA_S / st, s_tr = sqrt(3.0 * SIGMA_A * st);
  double zr = 1.0 / st, zv = zr * (1.0 + 4.0 / 3.0 * ss_fresnel_A(ETA));
  double Ft = 1.0 - ss_fresnel_dielectric(1.0, ETA), total = 0.0;
  const int nt = 200, nr = 2000;
  for (int i = 0; i < nt; ++i) {
    double th = (i + 0.5) * (SS_PI / 4.0) / nt, rmax = 5.0 / cos(th), dr = rmax / nr;
    for (int j = 0; j < nr; ++j) {
      double r = (j + 0.5) * dr, dr_ = sqrt(r * r + zr * zr), dv = sqrt(r * r + zv * zv);
      double Rd = ap / (4.0 * SS_PI) *
                  (zr * (s_tr * dr_ + 1.0) * exp(-s_tr * dr_) / (dr_ * dr_ * dr_) +
                   zv * (s_tr * dv + 1.0) * exp(-s_tr * dv) / (dv * dv * dv));
      total += Rd * r * dr * (SS_PI / 4.0) / nt;
    }
  }
  return Ft * Ft * 8.0 * total / SS_PI;
}

/* The image mean of `s` committed and rendered on 2 threads at `spp`. */
static double render_mean(ss_scene *s, int spp) {
  commit(s);
  ss_error err;
  ss_film *f = render(s, 2, spp, SS_OK, &err);
  double mean = image_mean(f);
  ss_film_destroy(f);
  return mean;
}

static double fem_slab(int volume_source) {
  ss_scene *s = slab_scene("fem");
  cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 0.5, NULL), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "volume_source", volume_source, NULL), SS_OK);
  double mean = render_mean(s, 1);
  ss_scene_destroy(s);
  return mean;
}

Test(fem_integrator, slab_far_from_edges_matches_the_half_space_and_the_dipole, .timeout = 300) {
  double boundary = fem_slab(0), volume = fem_slab(1);
  double exact[2] = {robin_radiance(), robin_volume_radiance()}, fem[2] = {boundary, volume};
  /* linear elements of 0.55 mean free paths against a decay length of
   * 1.74: a discretisation error of a few per cent (measured: boundary
   * source 2.6 % below, volume source 2.9 % below) */
  for (int k = 0; k < 2; ++k) {
    cr_expect(fabs(fem[k] / exact[k] - 1.0) < 0.03,
              "%s source: fem %g vs the exact half-space %g (ratio %g)", k ? "volume" : "boundary",
              fem[k], exact[k], fem[k] / exact[k]);
  }
  /* The dipole's reflectance over the face differs from these problems'
   * (by 8 and 9 %): fem / bssrdf is the ratio of the models within 5 %
   * (measured: boundary source 1.072 against 1.080, volume source 1.081
   * against 1.093). */
  ss_scene *s = slab_scene("bssrdf");
  commit(s);
  ss_error err;
  ss_film *f = render(s, 2, 256, SS_OK, &err);
  double dip = image_mean(f), model = dipole_radiance();
  for (int k = 0; k < 2; ++k) {
    cr_expect(fabs(fem[k] / dip - exact[k] / model) < 0.05,
              "%s source: fem / bssrdf %g, expected %g", k ? "volume" : "boundary", fem[k] / dip,
              exact[k] / model);
  }
  ss_film_destroy(f);
  ss_scene_destroy(s);
}

/* The slab lit only indirectly: a spot light 1 above its top face points
 * up (cone of 75 degrees, intensity 3000) at a 400 x 400 white (albedo 0.8)
 * diffuse ceiling facing down at height 30; the camera looks down from 4 at
 * the central 2 x 2 of the top face (field of view 28 degrees). The lit
 * patch, 108 in radius, is broad against the decay length 1.74: the
 * transmitted irradiance is uniform near the centre (1.083 by quadrature
 * over the patch; the fem's faces there measure 1.081). */
static ss_scene *ceiling_scene(const char *integrator) {
  ss_scene *s = slab_scene(integrator);
  s->num_lights = 0;
  s->camera.position = ss_vec3_make(0, 4, 0);
  s->camera.fov_deg = 28.0;
  test_add_diffuse_square(s, "ceiling", 400, 30, 0.8, 0);
  ss_error err;
  ss_light l;
  memset(&l, 0, sizeof l);
  snprintf(l.name, sizeof l.name, "spot");
  l.type = SS_LIGHT_SPOT;
  l.position = ss_vec3_make(0, 1, 0);
  l.direction = ss_vec3_make(0, 1, 0);
  l.cone_angle = 75.0;
  l.falloff_angle = 75.0;
  l.value = ss_rgb_gray(3000.0);
  l.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
  return s;
}

/* Mean of the fem render of `s` (element size 0.5, 256 irradiance samples
 * per face, 16 spp) with option indirect. */
static double fem_mean(ss_scene *s, int indirect) {
  cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 0.5, NULL), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "irradiance_samples", 256, NULL), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "indirect", indirect, NULL), SS_OK);
  return render_mean(s, 16);
}

/* Mean of the bssrdf render of `s` and its standard error from the spread
 * of the 16 pixels (the lighting is uniform over the view). */
static double bssrdf_mean(ss_scene *s, int spp, double *se) {
  commit(s);
  ss_error err;
  ss_film *f = render(s, 2, spp, SS_OK, &err);
  double mean = image_mean(f), var = 0.0;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      double d = ss_rgb_average(ss_film_pixel_mean(f, x, y)) - mean;
      var += d * d / 15.0;
    }
  }
  *se = sqrt(var / 16.0);
  ss_film_destroy(f);
  return mean;
}

/* The diffusion term lit only by the ceiling (option indirect, the
 * default) against the `bssrdf` integrator, which reaches the ceiling by
 * continuing its paths from the entry points: fem(indirect 1) - fem(indirect
 * 0) is the fem's diffusion term (indirect 0 leaves it dark: what remains is
 * the boundary's reflection of the ceiling, the same path in both
 * integrators), bssrdf - fem(indirect 0) the dipole's. Their ratio is that of
 * the models' reflectances, exact / model = 1.080 under light along the
 * normal (the first test). The ceiling's light arrives from every direction
 * while both models ignore the incident direction except through the
 * Fresnel transmission, so the ratio may move with it: measured under a sun
 * at 52 and 69 degrees, 1.096 and 1.126 (against 1.069 along the normal);
 * hence 8 % plus 3 standard errors of the bssrdf render (2 % at 1024 spp).
 * The irradiance takes 256 samples per face and the view covers 2 x 2 about
 * the centre (16 spp): with 16 samples the noise of each face's Gamma_s
 * moves the exitance at one vertex by 10 %. Measured: 1.036. */
Test(fem_integrator, indirect_light_enters_as_the_bssrdf_integrator_says, .timeout = 300) {
  ss_scene *s = ceiling_scene("fem");
  double ind = fem_mean(s, 1), none = fem_mean(s, 0);
  ss_scene_destroy(s);
  s = ceiling_scene("bssrdf");
  double se, dip = bssrdf_mean(s, 1024, &se);
  ss_scene_destroy(s);
  double ratio = (ind - none) / (dip - none), expected = robin_radiance() / dipole_radiance();
  cr_log_info("fem / bssrdf under indirect light %g (bssrdf %g +- %g, fem %g, reflection %g)",
              ratio, dip, se, ind, none);
  cr_expect(ind > 2.0 * none, "indirect light adds the diffusion term: %g against %g", ind, none);
  cr_expect(fabs(ratio / expected - 1.0) < 0.08 + 3.0 * se / (dip - none),
            "fem / bssrdf under indirect light %g, expected %g (bssrdf %g +- %g, fem %g, "
            "reflection %g)",
            ratio, expected, dip, se, ind, none);
}

/* Without anything to reflect the sun, indirect light adds nothing: the
 * continuation rays leave the scene, the sun is sampled as before (a delta
 * light takes no MIS weight), and the images are equal bit for bit. */
Test(fem_integrator, without_a_reflector_indirect_light_changes_nothing, .timeout = 120) {
  ss_film *f[2];
  for (int k = 0; k < 2; ++k) {
    ss_scene *s = slab_scene("fem");
    cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 1.5, NULL), SS_OK);
    cr_assert_eq(ss_scene_set_integrator_option(s, "indirect", k, NULL), SS_OK);
    commit(s);
    ss_error err;
    f[k] = render(s, 2, 1, SS_OK, &err);
    ss_scene_destroy(s);
  }
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      ss_rgb u = ss_film_pixel_mean(f[0], x, y), v = ss_film_pixel_mean(f[1], x, y);
      cr_assert(!memcmp(&u, &v, sizeof u), "pixel %d,%d differs", x, y);
      cr_assert(u.c[0] > 0.0, "pixel %d,%d is dark", x, y);
    }
  }
  ss_film_destroy(f[0]);
  ss_film_destroy(f[1]);
}

Test(fem_integrator, one_and_two_threads_render_the_same_image, .timeout = 120) {
  ss_scene *s = slab_scene("fem");
  cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 1.5, NULL), SS_OK);
  test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_make(0.1, 0.2, 0.3));
  s->camera.fov_deg = 40.0; /* the edges, the sides and the sky too */
  /* two tiles for the two threads */
  s->camera.width = 2 * SS_RENDER_TILE;
  s->camera.height = 1;
  commit(s);
  test_expect_thread_independent(s, 2, 5);
  ss_scene_destroy(s);
}

Test(fem_integrator, bad_options_are_refused_naming_the_key) {
  const char *names[] = {"element_size", "element_size",  "irradiance_samples",
                         "pcg",          "max_elements",  "min_density",
                         "volume_source", "medium_element_size", "indirect"};
  double values[] = {0.0, NAN, 2.5, 2.0, 10.0, 0.0, 0.5, -1.0, 0.5};
  for (int k = 0; k < 9; ++k) {
    ss_scene *s = slab_scene("fem");
    cr_assert_eq(ss_scene_set_integrator_option(s, names[k], values[k], NULL), SS_OK);
    commit(s);
    ss_error err;
    render(s, 1, 1, SS_ERR_INVALID_ARGUMENT, &err);
    cr_expect(strstr(err.message, names[k]), "%s", err.message);
    ss_scene_destroy(s);
  }
  /* a mesh too fine for max_elements is refused before meshing */
  ss_scene *s = slab_scene("fem");
  cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 0.01, NULL), SS_OK);
  commit(s);
  ss_error err;
  render(s, 1, 1, SS_ERR_INVALID_ARGUMENT, &err);
  cr_expect(strstr(err.message, "max_elements"), "%s", err.message);
  ss_scene_destroy(s);
}

/* A translucent open surface never reaches the integrator: the scene
 * refuses it, naming the shape (the finite elements fill closed shapes). */
Test(fem_integrator, an_open_surface_is_refused) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  snprintf(s->integrator.name, sizeof s->integrator.name, "fem");
  int m = test_add_translucent(s, ss_rgb_gray(SIGMA_S), ss_rgb_gray(SIGMA_A), SS_BOUNDARY_SMOOTH,
                               "dipole");
  ss_mesh *quad;
  cr_assert_eq(ss_shape_quad(10, 10, 1, 1, &quad, &err), SS_OK);
  cr_expect_eq(ss_scene_add_shape(s, "sheet", quad, m, NULL, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "sheet") && strstr(err.message, "not closed"), "%s", err.message);
  ss_scene_destroy(s);
}
