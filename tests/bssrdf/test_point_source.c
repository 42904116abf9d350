/* The models' point sources (bssrdf.h, point_source_exitance; the `hybrid`
 * integrator's hand-over): against the diffusion solution they stand for
 * (the flux and fluence of the source and its image through the surface,
 * differentiated numerically), their plane integrals (all the power leaves
 * a medium without absorption, from any depth; with absorption it decays as
 * e^{-sigma_tr z}), and each model's own profile, which is the point source
 * at the depths where light entering at normal incidence first scatters. */
#include "bssrdf/bssrdf_test_util.h"

#include <gsl/gsl_integration.h>

/* Reduced coefficients of a gray medium of albedo alpha, sigma_t 1, g 0. */
typedef struct {
  double sigma_t_p, alpha_p, sigma_a;
} medium;

static medium gray(double alpha) {
  return (medium){.sigma_t_p = 1.0, .alpha_p = alpha, .sigma_a = 1.0 - alpha};
}

/* The diffusion models' boundary: C_phi, C_E (0 and 1 for the classical
 * dipole, which counts the flux only), D, the extrapolation distance z_b and
 * sigma_tr = sqrt(sigma_a / D). */
typedef struct {
  double c_phi, c_e, D, z_b, sigma_tr;
} boundary;

/* Jensen et al. 2001: D = 1/(3 sigma_t'), z_b = 2 A D, A = (1 + Fdr)/(1 - Fdr). */
static boundary classical(medium m, double eta) {
  double D = 1.0 / (3.0 * m.sigma_t_p);
  return (boundary){0.0, 1.0, D, 2.0 * ss_fresnel_A(eta) * D, sqrt(m.sigma_a / D)};
}

/* d'Eon 2012 (and Habel et al. 2013): Grosjean's D, z_b = 2 A D with
 * A = (1 + 3 C2)/(1 - 2 C1), C_phi = (1 - 2 C1)/4, C_E = (1 - 3 C2)/2. */
static boundary grosjean(medium m, double eta) {
  double c1 = ss_fresnel_moment(1, eta), c2 = ss_fresnel_moment(2, eta);
  double s_p = m.alpha_p * m.sigma_t_p;
  double D = (2.0 * m.sigma_a + s_p) / (3.0 * m.sigma_t_p * m.sigma_t_p);
  double A = (1.0 + 3.0 * c2) / (1.0 - 2.0 * c1);
  return (boundary){0.25 * (1.0 - 2.0 * c1), 0.5 * (1.0 - 3.0 * c2), D, 2.0 * A * D,
                    sqrt(m.sigma_a / D)};
}

/* The fluence at depth zeta and lateral distance r of a unit isotropic
 * source at depth z with its negative image at -(z + 2 z_b) (zero fluence
 * on the extrapolated boundary). */
static double fluence(const boundary *b, double z, double zeta, double r) {
  double dr = hypot(r, zeta - z), dv = hypot(r, zeta + z + 2.0 * b->z_b);
  return (exp(-b->sigma_tr * dr) / dr - exp(-b->sigma_tr * dv) / dv) / (4.0 * SS_PI * b->D);
}

/* C_phi phi + C_E D dphi/dzeta at the surface zeta = 0 (the outward flux),
 * the derivative by a central difference. */
static double diffusion_exitance(const boundary *b, double z, double r) {
  double h = 1e-5 * (z + b->z_b);
  double flux = b->D * (fluence(b, z, h, r) - fluence(b, z, -h, r)) / (2.0 * h);
  return b->c_phi * fluence(b, z, 0.0, r) + b->c_e * flux;
}

/* make_gray, pbd without its table (none of this reads it). */
static ss_bssrdf *model(const char *name, double alpha, double eta) {
  if (strcmp(name, "pbd")) {
    return make_gray(name, alpha, 1.0, eta, 0.0);
  }
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, alpha, 1.0 - alpha, 0.0);
  p.eta = eta;
  ss_error err;
  cr_assert_eq(
      ss_bssrdf_params_set_option(&p, ss_bssrdf_model_find("pbd"), "tabulate", "false", &err),
      SS_OK, "%s", err.message);
  ss_bssrdf *b = NULL;
  cr_assert_eq(ss_bssrdf_create("pbd", &p, &b, &err), SS_OK, "%s", err.message);
  return b;
}

static double point(const ss_bssrdf *b, double z, double r) {
  double m[3];
  ss_bssrdf_point_source_exitance(b, z, r, m);
  cr_assert(m[0] == m[1] && m[1] == m[2], "gray medium: channels differ");
  return m[0];
}

/* PBD's correction for sources near the boundary (Ferrier2016, table 4). */
static double kappa(double sigma_t_p, double z, double r) {
  return 1.0 - exp(-2.0 * sigma_t_p * (hypot(r, z) + z));
}

Test(point_source, is_the_diffusion_solution_of_a_source_and_its_image) {
  const double albedos[] = {0.5, 0.99, 1.0};
  const double etas[] = {1.0, 1.33};
  const double depths[] = {0.0, 0.3, 1.0, 3.0, 10.0};
  const double radii[] = {0.05, 0.5, 2.0, 8.0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      medium m = gray(albedos[i]);
      boundary cl = classical(m, etas[j]), gr = grosjean(m, etas[j]);
      ss_bssrdf *d = model("dipole", albedos[i], etas[j]);
      ss_bssrdf *bd = model("better-dipole", albedos[i], etas[j]);
      ss_bssrdf *pbd = model("pbd", albedos[i], etas[j]);
      double t_out = ss_fresnel_transmission_out(etas[j]);
      for (int k = 0; k < 5; ++k) {
        for (int l = 0; l < 4; ++l) {
          double z = depths[k], r = radii[l];
          /* the classical dipole leaves with Jensen's Ft(w_o)/pi lobe: t_out of it */
          double want_d = t_out * diffusion_exitance(&cl, z, r);
          double want_bd = m.alpha_p * diffusion_exitance(&gr, z, r);
          double want_pbd = want_bd * kappa(m.sigma_t_p, z, r);
          double got_d = point(d, z, r), got_bd = point(bd, z, r), got_pbd = point(pbd, z, r);
          cr_expect(fabs(got_d - want_d) <= 1e-6 * want_d,
                    "dipole a %g eta %g z %g r %g: %.9g vs %.9g", albedos[i], etas[j], z, r, got_d,
                    want_d);
          cr_expect(fabs(got_bd - want_bd) <= 1e-6 * want_bd,
                    "better-dipole a %g eta %g z %g r %g: %.9g vs %.9g", albedos[i], etas[j], z, r,
                    got_bd, want_bd);
          cr_expect(fabs(got_pbd - want_pbd) <= 1e-6 * want_pbd,
                    "pbd a %g eta %g z %g r %g: %.9g vs %.9g", albedos[i], etas[j], z, r, got_pbd,
                    want_pbd);
        }
      }
      ss_bssrdf_destroy(d);
      ss_bssrdf_destroy(bd);
      ss_bssrdf_destroy(pbd);
    }
  }
}

typedef struct {
  const ss_bssrdf *b;
  double z;
} ring_ctx;

static double ring(double r, void *ctx) {
  const ring_ctx *c = ctx;
  return 2.0 * SS_PI * r * point(c->b, c->z, r);
}

/* 2 pi int M(r; z) r dr, in two pieces (the core of width z, the tail). */
static double plane_integral(const ss_bssrdf *b, double z) {
  ring_ctx c = {b, z};
  gsl_function f = {ring, &c};
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
  double core, tail, err;
  double split = fmax(z, 0.1);
  gsl_integration_qags(&f, 0.0, split, 1e-12, 1e-10, 1000, ws, &core, &err);
  gsl_integration_qagiu(&f, split, 1e-12, 1e-10, 1000, ws, &tail, &err);
  gsl_integration_workspace_free(ws);
  return core + tail;
}

/* Without absorption every source's power leaves, from any depth (pbd's
 * kappa takes a little from sources within a mean free path); the exit
 * lobe's part t_out of it for the classical dipole. With absorption the
 * escaping part decays exactly as e^{-sigma_tr z} for the dipoles (each
 * term's plane integral does), and so for pbd's deep sources. */
Test(point_source, all_the_power_leaves_without_absorption_and_decays_with_depth_with_it) {
  const char *models[] = {"dipole", "better-dipole", "pbd"};
  const double etas[] = {1.0, 1.33};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      ss_bssrdf *b = model(models[i], 1.0, etas[j]);
      double want = i == 0 ? ss_fresnel_transmission_out(etas[j]) : 1.0;
      const double depths[] = {3.0, 10.0, 30.0};
      for (int k = 0; k < 3; ++k) {
        double got = plane_integral(b, depths[k]);
        cr_expect(fabs(got - want) < 1e-5, "%s eta %g z %g: escaping %.8f, want %.8f", models[i],
                  etas[j], depths[k], got, want);
      }
      ss_bssrdf_destroy(b);
      b = model(models[i], 0.99, etas[j]);
      medium m = gray(0.99);
      double sigma_tr = (i == 0 ? classical(m, etas[j]) : grosjean(m, etas[j])).sigma_tr;
      double near = plane_integral(b, 3.0), far = plane_integral(b, 6.0);
      cr_expect(fabs(far / near - exp(-3.0 * sigma_tr)) < 1e-5 * exp(-3.0 * sigma_tr),
                "%s eta %g: escaping from z 6 / z 3 = %.8f, want e^{-3 sigma_tr} = %.8f", models[i],
                etas[j], far / near, exp(-3.0 * sigma_tr));
      ss_bssrdf_destroy(b);
    }
  }
}

/* The models' own profiles: the dipoles' exitance at normal incidence is
 * Ft(1) alpha' M(r; z_r), z_r = 1/sigma_t'; pbd's multiple scattering is
 * int rho' sigma_t' e^{-sigma_t' z} M(r; z) dz. */
typedef struct {
  const ss_bssrdf *b;
  double r;
} depth_ctx;

static double beam_point(double z, void *ctx) {
  const depth_ctx *c = ctx;
  return exp(-z) * point(c->b, z, c->r); /* rho' sigma_t' = rho' at sigma_t' = 1 */
}

Test(point_source, the_models_profiles_are_their_point_sources_at_the_first_scattering_depths) {
  const double albedos[] = {0.5, 0.95, 0.999};
  const double radii[] = {0.02, 0.3, 1.0, 4.0, 12.0};
  for (int i = 0; i < 3; ++i) {
    double eta = 1.33;
    const char *dipoles[] = {"dipole", "better-dipole"};
    for (int k = 0; k < 2; ++k) {
      ss_bssrdf *b = model(dipoles[k], albedos[i], eta);
      for (int l = 0; l < 5; ++l) {
        double e[3];
        ss_bssrdf_exitance(b, 1.0, radii[l], 0.0, e);
        double want = e[0] / ss_ft_outside(1.0, eta);
        double got = albedos[i] * point(b, 1.0, radii[l]);
        cr_expect(fabs(got - want) <= 1e-12 * want, "%s a %g r %g: %.12g vs %.12g", dipoles[k],
                  albedos[i], radii[l], got, want);
      }
      ss_bssrdf_destroy(b);
    }
    ss_bssrdf *b = model("pbd", albedos[i], eta);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    for (int l = 0; l < 5; ++l) {
      depth_ctx c = {b, radii[l]};
      gsl_function f = {beam_point, &c};
      double near, deep, err;
      gsl_integration_qags(&f, 0.0, radii[l], 1e-13, 1e-10, 1000, ws, &near, &err);
      gsl_integration_qagiu(&f, radii[l], 1e-13, 1e-10, 1000, ws, &deep, &err);
      ss_bssrdf_profile_value v;
      ss_bssrdf_profile(b, 0, radii[l], &v);
      double got = albedos[i] * (near + deep);
      cr_expect(fabs(got - v.ms) <= 1e-6 * v.ms, "pbd a %g r %g: %.10g vs profile %.10g",
                albedos[i], radii[l], got, v.ms);
    }
    gsl_integration_workspace_free(ws);
    ss_bssrdf_destroy(b);
  }
}

/* The exit lobe carries the exitance: 2 pi int_0^1 L_o(mu) mu dmu = M. */
typedef struct {
  const ss_bssrdf *b;
} lobe_ctx;

static double lobe(double mu, void *ctx) {
  const lobe_ctx *c = ctx;
  double l[3];
  ss_bssrdf_point_source_radiance(c->b, 2.0, 0.5, mu, l);
  return 2.0 * SS_PI * l[0] * mu;
}

Test(point_source, the_exit_lobe_carries_the_exitance) {
  const char *models[] = {"dipole", "better-dipole", "pbd"};
  const double etas[] = {1.0, 1.33, 1.5};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      ss_bssrdf *b = model(models[i], 0.9, etas[j]);
      lobe_ctx c = {b};
      gsl_function f = {lobe, &c};
      gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
      double got, err;
      gsl_integration_qags(&f, 0.0, 1.0, 1e-14, 1e-10, 1000, ws, &got, &err);
      gsl_integration_workspace_free(ws);
      double want = point(b, 2.0, 0.5);
      cr_expect(fabs(got - want) < 1e-7 * want, "%s eta %g: %.10g vs %.10g", models[i], etas[j],
                got, want);
      ss_bssrdf_destroy(b);
    }
  }
}

/* A model built for one path vertex (textures) has the same lobe. */
Test(point_source, a_single_use_model_has_the_same_lobe) {
  const char *models[] = {"dipole", "better-dipole", "pbd"};
  for (int i = 0; i < 3; ++i) {
    ss_bssrdf *b = model(models[i], 0.9, 1.33);
    ss_bssrdf_params p = *ss_bssrdf_get_params(b);
    p.single_use = 1;
    ss_bssrdf *once = NULL;
    ss_error err;
    cr_assert_eq(ss_bssrdf_create(models[i], &p, &once, &err), SS_OK, "%s", err.message);
    double l[3], l_once[3];
    ss_bssrdf_point_source_radiance(b, 2.0, 0.5, 0.7, l);
    ss_bssrdf_point_source_radiance(once, 2.0, 0.5, 0.7, l_once);
    cr_expect(l[0] > 0.0 && fabs(l_once[0] - l[0]) <= 1e-14 * l[0], "%s: %.17g vs %.17g", models[i],
              l_once[0], l[0]);
    ss_bssrdf_destroy(once);
    ss_bssrdf_destroy(b);
  }
}

/* Sources on the surface stay finite (the hand-over clamps depths to >= 0),
 * and a model without a point source says so and gives 0. */
Test(point_source, is_finite_on_the_surface_and_absent_from_other_models) {
  const char *models[] = {"dipole", "better-dipole", "pbd"};
  for (int i = 0; i < 3; ++i) {
    ss_bssrdf *b = model(models[i], 0.9, 1.33);
    cr_expect(ss_bssrdf_has_point_source(b));
    const double radii[] = {0.0, 1e-9, 0.1};
    for (int l = 0; l < 3; ++l) {
      double m = point(b, 0.0, radii[l]), below = point(b, -1.0, radii[l]);
      cr_expect(isfinite(m) && m > 0.0, "%s z 0 r %g: %g", models[i], radii[l], m);
      cr_expect_eq(below, m, "%s: a negative depth is the surface", models[i]);
    }
    ss_bssrdf_destroy(b);
  }
  ss_bssrdf *b = model("burley", 0.9, 1.33);
  cr_expect_not(ss_bssrdf_has_point_source(b));
  double m[3] = {1, 1, 1};
  ss_bssrdf_point_source_exitance(b, 1.0, 1.0, m);
  cr_expect(m[0] == 0.0 && m[1] == 0.0 && m[2] == 0.0);
  ss_bssrdf_destroy(b);
}
