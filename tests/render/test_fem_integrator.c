/* The `fem` integrator (Jakob et al. 2010, sec. 6.2): on a wide slab lit
 * by a distant light along its normal, far from the edges, the rendered
 * diffusion term equals the exact solution of the same boundary-value
 * problem on the half-space (the 1D Robin solution below) and agrees with
 * the `bssrdf` integrator's dipole render within the difference of the two
 * models' total reflectances; the irradiance pass returns the mean refracted
 * direction of the light; lit obliquely, the rays' volume source
 * follows the refracted light as the half-space says; lit only by a
 * diffuse ceiling, its indirect
 * light enters as the `bssrdf` integrator says, and without a reflector the
 * option indirect changes nothing; 1 and 2 threads render the same image;
 * bad options are refused naming the key; an open surface is refused. */
#include "subsurf/fresnel.h"
#include "subsurf/irradiance_points.h"
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

/* A sun at theta_i degrees from the slab's normal (+y), travelling toward
 * +x for theta_i > 0 (toward -x for theta_i < 0), with a black wall (albedo
 * 0) 0.05 outside the side face it would light, as high as the slab: only
 * the top face is lit, the half-space's boundary. (Without the wall the
 * side face, lit 2.9 times as strongly as the top at 69 degrees and 5 from
 * the view, raised the fem's exitance there by 1.6 % at 52 degrees and
 * 8.8 % at 69.) */
static void add_sun(ss_scene *s, const char *name, double theta_i) {
  double t = theta_i * SS_PI / 180.0, side = theta_i > 0.0 ? -1.0 : 1.0;
  ss_error err;
  ss_light l;
  memset(&l, 0, sizeof l);
  snprintf(l.name, sizeof l.name, "%s", name);
  l.type = SS_LIGHT_DIRECTIONAL;
  l.direction = ss_vec3_make(sin(t), -cos(t), 0);
  l.value = ss_rgb_gray(1.0);
  l.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
  if (theta_i == 0.0) {
    return;
  }
  ss_material mat;
  memset(&mat, 0, sizeof mat);
  snprintf(mat.name, sizeof mat.name, "%s wall", name);
  mat.kind = SS_MATERIAL_DIFFUSE;
  mat.medium = -1;
  int m;
  cr_assert_eq(ss_scene_add_material(s, &mat, &m, &err), SS_OK, "%s", err.message);
  ss_mesh *wall;
  cr_assert_eq(ss_shape_quad(12, 6, 1, 1, &wall, &err), SS_OK);
  ss_mat4 to = ss_mat4_mul(ss_mat4_translate(ss_vec3_make(5.05 * side, -3, 0)),
                           ss_mat4_rotate(90, ss_vec3_make(0, 1, 0)));
  cr_assert_eq(ss_mesh_transform(wall, to, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, mat.name, wall, m, NULL, &err), SS_OK, "%s", err.message);
}

/* A 10 x 5 x 10 slab (in mean free paths 11 x 5.5 x 11; the fluence decays
 * over 1/sigma_tr = 1.74) below a sun at theta_i degrees from its normal
 * (+y), in the x-y plane, seen from straight above through a 2 degree field
 * of view (the central 0.7 x 0.7, 5 from the sides), with the smooth
 * boundary of eta 1.3 and the dipole model for the `bssrdf` integrator. */
static ss_scene *slab_scene_sun(const char *integrator, double theta_i) {
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
  add_sun(s, "sun", theta_i);
  return s;
}

/* The same under the sun along the normal. */
static ss_scene *slab_scene(const char *integrator) { return slab_scene_sun(integrator, 0.0); }

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
 * condition phi/4 + (A/2) D dphi/dn = Gamma_s/Fdt (Jakob2010 eq. 38),
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

/* The same half-space with the rays' volume source (option volume_source)
 * under a sun at cos_i from the normal, refracted to mu = cos t: the
 * irradiance E = Ft(cos_i) cos_i enters as the first scattering events
 * E alpha' k exp(-k z), k = sigma/mu (sigma = sigma_t', the ray's extinction
 * over depth), in D phi'' - sigma_a phi = -Q0 (Jakob2010 eq. 35, isotropic)
 * with phi/4 + (A/2) D dphi/dn = 0 (eq. 38, no Gamma_s; dphi/dn = -phi'(0)):
 *     phi = C exp(-k z) + B exp(-sigma_tr z),  C = E alpha' k/(sigma_a - D k^2),
 *     B = -C (1 + 2 A D k)/(1 + 2 A D sigma_tr),
 *     phi0 = C + B = 2 A D C (sigma_tr - k)/(1 + 2 A D sigma_tr)
 *          = 2 A E alpha' k/((k + sigma_tr)(1 + 2 A D sigma_tr))
 * (sigma_a = D sigma_tr^2); M_o = phi0/(2A), seen along the normal. A ray
 * along the normal at oblique incidence is mu = 1 with the same E. (The 16
 * depth strata of fem_rays.c change phi0 by 0.1 % at normal incidence.) */
static double robin_volume_radiance(double cos_i, double mu) {
  double st = SIGMA_S + SIGMA_A, D = 1.0 / (3.0 * st), s_tr = sqrt(3.0 * SIGMA_A * st);
  double A = ss_fresnel_A(ETA), Fdt = 1.0 - ss_fresnel_diffuse_reflectance(ETA);
  double E = (1.0 - ss_fresnel_dielectric(cos_i, ETA)) * cos_i, k = st / mu;
  double C = E * (SIGMA_S / st) * k / (SIGMA_A - D * k * k);
  double phi0 = C * 2.0 * A * D * (s_tr - k) / (1.0 + 2.0 * A * D * s_tr);
  double Ft = 1.0 - ss_fresnel_dielectric(1.0, ETA);
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

static double fem_slab_sun(double theta_i, int volume_source) {
  ss_scene *s = slab_scene_sun("fem", theta_i);
  cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 0.5, NULL), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "volume_source", volume_source, NULL), SS_OK);
  double mean = render_mean(s, 1);
  ss_scene_destroy(s);
  return mean;
}

static double fem_slab(int volume_source) { return fem_slab_sun(0.0, volume_source); }

Test(fem_integrator, slab_far_from_edges_matches_the_half_space_and_the_dipole, .timeout = 300) {
  double boundary = fem_slab(0), volume = fem_slab(1);
  double exact[2] = {robin_radiance(), robin_volume_radiance(1.0, 1.0)},
         fem[2] = {boundary, volume};
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

/* The volume source under oblique light: the fem render with one ray per
 * face along the mean refracted direction against the exact half-space of
 * the same problem (robin_volume_radiance) at 0, 52 and 69 degrees, within
 * 4 % (the elements' error, measured 2.9-3.0 % below at every angle), and
 * against normal incidence within 1 % (the elements' error cancels;
 * measured 0.07 % and 0.04 %). A ray along the inward normal misses the
 * exact solution by 7 % at 52 degrees and 10 % at 69 (the first events too
 * deep: 1/sigma instead of cos t/sigma), and its render fails both checks
 * there (a scratch build: 0.903 and 0.870 of the exact solution). Two suns
 * at +-52 degrees refract into one mean direction, the inward normal, of
 * length cos t: the ray's extinction sigma/cos t puts its first events at
 * the depth of either sun's, and the render is twice the one sun's within
 * 1 % (measured 0.4 % above; with the extinction sigma along the normal, a
 * scratch build, 6.2 % below). */
Test(fem_integrator, the_volume_source_follows_the_refracted_light, .timeout = 300) {
  const double angles[3] = {0.0, 52.0, 69.0};
  double fem[3], exact[3];
  for (int k = 0; k < 3; ++k) {
    double ci = cos(angles[k] * SS_PI / 180.0), si = sin(angles[k] * SS_PI / 180.0);
    double mu = sqrt(1.0 - si * si / (ETA * ETA));
    fem[k] = fem_slab_sun(angles[k], 1);
    exact[k] = robin_volume_radiance(ci, mu);
    double normal = robin_volume_radiance(ci, 1.0);
    cr_log_info("%g degrees: fem %g, exact %g (ratio %g), along the normal %g", angles[k], fem[k],
                exact[k], fem[k] / exact[k], normal / exact[k]);
    cr_expect(fabs(fem[k] / exact[k] - 1.0) < 0.04, "%g degrees: fem %g vs the exact %g (%g)",
              angles[k], fem[k], exact[k], fem[k] / exact[k]);
    cr_expect(fabs(fem[k] / fem[0] / (exact[k] / exact[0]) - 1.0) < 0.01,
              "%g degrees: fem over normal incidence %g, exact %g", angles[k], fem[k] / fem[0],
              exact[k] / exact[0]);
    if (k == 2) {
      cr_assert(normal / exact[k] < 1.0 - 0.04 - 0.03, "the checks cannot tell the normal: %g",
                normal / exact[k]);
    }
  }
  ss_scene *s = slab_scene_sun("fem", 52.0);
  add_sun(s, "sun 2", -52.0);
  cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 0.5, NULL), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "volume_source", 1, NULL), SS_OK);
  double two = render_mean(s, 1);
  ss_scene_destroy(s);
  cr_log_info("two suns at +-52 degrees: fem %g, twice one sun's %g", two, 2.0 * fem[1]);
  cr_expect(fabs(two / (2.0 * fem[1]) - 1.0) < 0.01, "two suns %g, twice one sun's %g", two,
            2.0 * fem[1]);
}

/* The irradiance pass at n points at the centre of the slab's top face
 * (each its own random stream), with the flux vectors: the lights' direct
 * light, or (indirect) the direct and indirect estimates. */
static void top_face_flux(const ss_scene *s, int indirect, size_t n, int samples,
                          ss_irradiance_point *pts, ss_irradiance_flux *flux) {
  double etas[8];
  cr_assert(s->num_shapes <= 8);
  for (size_t i = 0; i < 8; ++i) {
    etas[i] = ETA;
  }
  for (size_t i = 0; i < n; ++i) {
    pts[i] = (ss_irradiance_point){.n = ss_vec3_make(0, 1, 0), .area = 1.0, .shape = 0};
  }
  if (indirect) {
    ss_irradiance_points_compute(s, pts, n, etas, samples, 7, 2, flux, NULL);
  } else {
    ss_irradiance_points_direct(s, pts, n, etas, samples, 7, 2, flux, NULL);
  }
}

/* The flux vector of the irradiance pass (irradiance_points.h), which the
 * volume source's rays follow. Under the sun at 52 degrees F/E is the sun's
 * refracted direction in every channel. Under a uniform sky (radiance 1)
 * E = 2 pi int Ft mu dmu and the component of F/E along -n is the
 * transmitted-flux-weighted mean cosine of the refracted light,
 * int Ft mu mu_t dmu / int Ft mu dmu (0.840 at eta 1.3; 2/3 were the
 * directions not refracted, 0.833 were the weights without Ft), its
 * tangential part 0: the means over 64 points of 1024 samples each within
 * 4 standard errors (from the points' spread; measured for the mean cosine
 * 0.8394 +- 0.0006 and 0.8394 +- 0.0003), with the direct light alone and
 * with the direct and indirect estimates (the sky sampled as a light and
 * reached by the continuation). */
Test(fem_integrator, the_irradiance_pass_returns_the_mean_refracted_direction) {
  ss_irradiance_point pts[64];
  ss_irradiance_flux flux[64];
  ss_scene *s = slab_scene_sun("fem", 52.0);
  commit(s);
  top_face_flux(s, 0, 1, 16, pts, flux);
  ss_vec3 to_sun = ss_vec3_neg(s->lights[0].direction), w_t;
  cr_assert(ss_refract(to_sun, pts[0].n, ETA, &w_t));
  double cos_i = to_sun.y, E = (1.0 - ss_fresnel_dielectric(cos_i, ETA)) * cos_i;
  for (int c = 0; c < 3; ++c) {
    ss_vec3 m = ss_vec3_scale(flux[0].c[c], 1.0 / pts[0].E.c[c]);
    cr_expect(fabs(pts[0].E.c[c] / E - 1.0) < 1e-12, "E %g, expected %g", pts[0].E.c[c], E);
    cr_expect(ss_vec3_length(ss_vec3_sub(m, w_t)) < 1e-12,
              "channel %d: (%g %g %g), refracted (%g %g %g)", c, m.x, m.y, m.z, w_t.x, w_t.y,
              w_t.z);
  }
  ss_scene_destroy(s);
  double ft_mu = 0.0, ft_mu_mu_t = 0.0;
  const int nq = 20000;
  for (int i = 0; i < nq; ++i) {
    double mu = (i + 0.5) / nq, ft = 1.0 - ss_fresnel_dielectric(mu, ETA);
    ft_mu += ft * mu / nq;
    ft_mu_mu_t += ft * mu * sqrt(1.0 - (1.0 - mu * mu) / (ETA * ETA)) / nq;
  }
  double want[3] = {2.0 * SS_PI * ft_mu, ft_mu_mu_t / ft_mu, 0.0};
  for (int indirect = 0; indirect < 2; ++indirect) {
    s = slab_scene("fem");
    s->num_lights = 0;
    test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_gray(1.0));
    commit(s);
    top_face_flux(s, indirect, 64, 1024, pts, flux);
    ss_scene_destroy(s);
    /* per point: E, the mean cosine and the tangential components */
    double sum[4] = {0, 0, 0, 0}, sum2[4] = {0, 0, 0, 0};
    for (int i = 0; i < 64; ++i) {
      double E_i = pts[i].E.c[0],
             v[4] = {E_i, -flux[i].c[0].y / E_i, flux[i].c[0].x / E_i, flux[i].c[0].z / E_i};
      for (int k = 0; k < 4; ++k) {
        sum[k] += v[k] / 64.0;
        sum2[k] += v[k] * v[k] / 64.0;
      }
    }
    const char *names[4] = {"E", "mean cosine", "x", "z"};
    for (int k = 0; k < 4; ++k) {
      double se = sqrt((sum2[k] - sum[k] * sum[k]) / 63.0), w = want[k < 2 ? k : 2];
      cr_log_info("indirect %d: %s %g +- %g, expected %g", indirect, names[k], sum[k], se, w);
      cr_expect(fabs(sum[k] - w) < 4.0 * se, "indirect %d: %s %g +- %g, expected %g", indirect,
                names[k], sum[k], se, w);
    }
  }
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
 * Fresnel transmission, so the ratio may move with it; under a sun at 0,
 * 52 and 69 degrees with the lit side face shaded (add_sun) it does not:
 * 1.064 at each (1024 spp; the rise to 1.088 and 1.116 without the shade is
 * the side face's light, which reaches the fem's view more than the
 * dipole's). The ceiling lights the sides too: 8 % plus 3 standard errors of
 * the bssrdf render (2 % at 1024 spp).
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

/* With either source; with the rays' volume source each face's ray follows
 * the mean refracted direction of the sun and the sky, the continuation's
 * samples included. */
Test(fem_integrator, one_and_two_threads_render_the_same_image, .timeout = 120) {
  for (int volume_source = 0; volume_source < 2; ++volume_source) {
    ss_scene *s = slab_scene("fem");
    cr_assert_eq(ss_scene_set_integrator_option(s, "element_size", 1.5, NULL), SS_OK);
    cr_assert_eq(ss_scene_set_integrator_option(s, "volume_source", volume_source, NULL), SS_OK);
    test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_make(0.1, 0.2, 0.3));
    s->camera.fov_deg = 40.0; /* the edges, the sides and the sky too */
    /* two tiles for the two threads */
    s->camera.width = 2 * SS_RENDER_TILE;
    s->camera.height = 1;
    commit(s);
    test_expect_thread_independent(s, 2, 5);
    ss_scene_destroy(s);
  }
}

Test(fem_integrator, bad_options_are_refused_naming_the_key) {
  const char *names[] = {"element_size",  "element_size",        "irradiance_samples",
                         "pcg",           "max_elements",        "min_density",
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
