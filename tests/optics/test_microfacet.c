#include "optics/bsdf_chi2.h"
#include "subsurf/bsdf.h"
#include "subsurf/chi2.h"
#include "subsurf/fresnel.h"
#include "subsurf/microfacet.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

static const ss_microfacet_type types[2] = {SS_MICROFACET_BECKMANN, SS_MICROFACET_GGX};

static ss_microfacet make_mf(ss_microfacet_type type, double alpha) {
  ss_microfacet m;
  ss_error err;
  cr_assert_eq(ss_microfacet_init(&m, type, alpha, &err), SS_OK, "%s", err.message);
  return m;
}

static ss_vec3 dir_at(double theta_deg, double phi_deg) {
  double t = theta_deg * SS_PI / 180.0, p = phi_deg * SS_PI / 180.0;
  return ss_vec3_make(sin(t) * cos(p), sin(t) * sin(p), cos(t));
}

/* Integral over the upper hemisphere by the midpoint rule in (theta, phi),
 * theta = (pi/2) s^2 to resolve peaks at the pole. */
typedef double (*hemi_fn)(void *ctx, ss_vec3 w);
static double integrate_hemisphere(hemi_fn f, void *ctx, int nt, int np) {
  double sum = 0.0;
  for (int i = 0; i < nt; ++i) {
    double s = (i + 0.5) / nt, theta = 0.5 * SS_PI * s * s, dtheta = SS_PI * s / nt;
    for (int j = 0; j < np; ++j) {
      double phi = 2.0 * SS_PI * (j + 0.5) / np;
      ss_vec3 w = ss_spherical_direction(cos(theta), phi);
      sum += f(ctx, w) * sin(theta) * dtheta * (2.0 * SS_PI / np);
    }
  }
  return sum;
}

static double projected_d(void *ctx, ss_vec3 wm) { return ss_microfacet_d(ctx, wm) * wm.z; }

Test(microfacet, d_is_normalised_over_projected_area) {
  const double alphas[] = {0.02, 0.1, 0.4, 1.0, 2.0};
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 5; ++a) {
      ss_microfacet m = make_mf(types[t], alphas[a]);
      /* Isotropic: one phi column suffices. */
      double integral = integrate_hemisphere(projected_d, &m, 200000, 1);
      /* GGX's tail ~ alpha^2 / theta'^3 near the horizon is resolved less
       * well than Beckmann's Gaussian; 1e-3 bounds the quadrature error. */
      cr_assert_float_eq(integral, 1.0, 1e-3, "%s alpha %g: %g", ss_microfacet_type_name(types[t]),
                         alphas[a], integral);
    }
  }
}

typedef struct {
  const ss_microfacet *m;
  ss_vec3 w;
} vis_ctx;

static double visible_projected(void *p, ss_vec3 wm) {
  const vis_ctx *c = p;
  return fmax(0.0, ss_vec3_dot(c->w, wm)) * ss_microfacet_d(c->m, wm);
}

/* Smith's Lambda is consistent with D: the projected area of the visible
 * microfacets is cos(theta) (1 + Lambda) (Heitz 2014, eq. 17 with eq. 43). */
Test(microfacet, lambda_matches_the_projected_area_of_d) {
  const double alphas[] = {0.1, 0.5, 1.2};
  const double thetas[] = {0.0, 40.0, 75.0, 88.0};
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 3; ++a) {
      ss_microfacet m = make_mf(types[t], alphas[a]);
      for (int k = 0; k < 4; ++k) {
        vis_ctx c = {&m, dir_at(thetas[k], 30.0)};
        double area = integrate_hemisphere(visible_projected, &c, 1500, 360);
        double expected = c.w.z * (1.0 + ss_microfacet_lambda(&m, c.w));
        cr_assert_float_eq(area, expected, 2e-3 * expected + 1e-5, "%s alpha %g theta %g: %g vs %g",
                           ss_microfacet_type_name(types[t]), alphas[a], thetas[k], area, expected);
        cr_assert_leq(ss_microfacet_g1(&m, c.w, ss_vec3_make(0, 0, 1)), 1.0);
      }
    }
  }
}

static int sample_vis(void *p, double u1, double u2, double u3, ss_vec3 *dir) {
  const vis_ctx *c = p;
  *dir = ss_microfacet_sample_visible(c->m, c->w, u1, u2);
  return 1;
}

static double pdf_vis(void *p, ss_vec3 dir) {
  const vis_ctx *c = p;
  return ss_microfacet_pdf_visible(c->m, c->w, dir);
}

Test(microfacet, visible_normal_sampling_passes_chi_square) {
  const double alphas[] = {0.1, 0.35, 1.0};
  const double thetas[] = {0.0, 50.0, 85.0};
  const int tests = 2 * 3 * 3;
  double level = ss_chi2_sidak_alpha(0.01, tests);
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 3; ++a) {
      for (int k = 0; k < 3; ++k) {
        ss_microfacet m = make_mf(types[t], alphas[a]);
        vis_ctx c = {&m, dir_at(thetas[k], 70.0)};
        ss_chi2_sphere_options opt;
        ss_chi2_sphere_options_default(&opt);
        opt.theta_max = 0.5 * SS_PI;
        opt.theta_power = alphas[a] < 0.2 ? 2.0 : 1.0;
        opt.theta_bins = 40;
        opt.phi_bins = 80;
        opt.samples = 300000;
        opt.seed = (uint64_t)(100 + 10 * t + 3 * a + k);
        ss_chi2_result res;
        ss_chi2_test_sphere(sample_vis, pdf_vis, &c, &opt, &res);
        cr_assert_gt(res.p_value, level, "%s alpha %g theta %g: %s",
                     ss_microfacet_type_name(types[t]), alphas[a], thetas[k], res.message);
        cr_assert_float_eq(res.pdf_integral, 1.0, 2e-3, "%s", res.message);
        cr_assert_eq(res.invalid, 0u);
      }
    }
  }
}

/* Anisotropic (alpha_u != alpha_v): D stays normalised, Lambda matches the
 * projected area of the visible microfacets at azimuths off the axes, and
 * the visible normals sample their density. */
Test(microfacet, anisotropic_d_lambda_and_visible_sampling_agree) {
  double level = ss_chi2_sidak_alpha(0.01, 4);
  for (int t = 0; t < 2; ++t) {
    ss_microfacet m;
    ss_error err;
    cr_assert_eq(ss_microfacet_init_anisotropic(&m, types[t], 0.12, 0.5, &err), SS_OK);
    cr_assert(ss_microfacet_is_anisotropic(&m));
    double integral = integrate_hemisphere(projected_d, &m, 3000, 720);
    cr_expect_float_eq(integral, 1.0, 2e-3, "%s: %g", ss_microfacet_type_name(types[t]), integral);
    for (int k = 0; k < 2; ++k) {
      vis_ctx c = {&m, dir_at(k == 0 ? 40.0 : 75.0, 35.0)};
      double area = integrate_hemisphere(visible_projected, &c, 1500, 720);
      double expected = c.w.z * (1.0 + ss_microfacet_lambda(&m, c.w));
      cr_expect_float_eq(area, expected, 2e-3 * expected, "%s theta %d: %g vs %g",
                         ss_microfacet_type_name(types[t]), k, area, expected);
      ss_chi2_sphere_options opt;
      ss_chi2_sphere_options_default(&opt);
      opt.theta_max = 0.5 * SS_PI;
      opt.theta_power = 2.0;
      opt.theta_bins = 40;
      opt.phi_bins = 80;
      opt.samples = 300000;
      opt.seed = (uint64_t)(900 + 2 * t + k);
      ss_chi2_result res;
      ss_chi2_test_sphere(sample_vis, pdf_vis, &c, &opt, &res);
      cr_expect_gt(res.p_value, level, "%s theta %d: %s", ss_microfacet_type_name(types[t]), k,
                   res.message);
      cr_expect_float_eq(res.pdf_integral, 1.0, 2e-3, "%s", res.message);
    }
  }
}

/* ---- BSDFs. */

static ss_bsdf rough(ss_microfacet_type type, double alpha, double eta, ss_transport_mode mode) {
  ss_microfacet m = make_mf(type, alpha);
  ss_bsdf b;
  ss_error err;
  cr_assert_eq(ss_bsdf_rough_dielectric_init(&b, eta, &m, mode, &err), SS_OK, "%s", err.message);
  return b;
}

Test(bsdf, rough_dielectric_sampling_passes_chi_square) {
  const double etas[] = {1.33, 1.0 / 1.33};
  const double wo_theta[] = {35.0, 150.0}; /* from outside and from inside */
  const double alphas[] = {0.15, 0.5};
  const int tests = 2 * 2 * 2 * 2;
  double level = ss_chi2_sidak_alpha(0.01, tests);
  int n = 0;
  for (int t = 0; t < 2; ++t) {
    for (int e = 0; e < 2; ++e) {
      for (int w = 0; w < 2; ++w) {
        for (int a = 0; a < 2; ++a, ++n) {
          ss_bsdf b = rough(types[t], alphas[a], etas[e], SS_TRANSPORT_RADIANCE);
          char what[64];
          snprintf(what, sizeof what, "%s alpha %g eta %g wo %g", ss_microfacet_type_name(types[t]),
                   alphas[a], etas[e], wo_theta[w]);
          expect_rough_bsdf_chi2(&b, dir_at(wo_theta[w], 20.0), 250000, (uint64_t)(200 + n), level,
                                 what);
        }
      }
    }
  }
}

Test(bsdf, diffuse_sampling_passes_chi_square_and_has_albedo_r) {
  ss_bsdf b;
  ss_error err;
  cr_assert_eq(ss_bsdf_diffuse_init(&b, ss_vec3_make(0.5, 0.5, 0.5), &err), SS_OK);
  for (int side = 0; side < 2; ++side) {
    bsdf_ctx c = {&b, dir_at(side ? 120.0 : 30.0, 10.0), 0.0};
    ss_chi2_sphere_options opt;
    ss_chi2_sphere_options_default(&opt);
    opt.samples = 300000;
    opt.seed = 300 + (uint64_t)side;
    ss_chi2_result res;
    ss_chi2_test_sphere(sample_bsdf, pdf_bsdf, &c, &opt, &res);
    cr_assert_gt(res.p_value, ss_chi2_sidak_alpha(0.01, 2), "%s", res.message);
    cr_assert_float_eq(res.pdf_integral, 1.0, 1e-3);
    cr_assert_lt(c.max_weight_error, 1e-12);
  }
  ss_bsdf_sample s;
  cr_assert(ss_bsdf_sample_dir(&b, dir_at(30, 0), 0.5, 0.3, 0.7, &s));
  cr_assert_float_eq(s.f.y * fabs(s.wi.z) / s.pdf, 0.5, 1e-12);
  cr_assert_eq(ss_bsdf_diffuse_init(&b, ss_vec3_make(1.2, 0, 0), &err), SS_ERR_INVALID_ARGUMENT);
}

/* Albedo of wo: E[f |cos| / pdf] over the BSDF's own samples, in importance
 * mode where a lossless interface conserves energy exactly. */
static void albedo(const ss_bsdf *b, ss_vec3 wo, int n, uint64_t seed, double *mean, double *sem) {
  ss_rng rng;
  ss_rng_seed(&rng, seed, 3);
  double s1 = 0.0, s2 = 0.0;
  for (int i = 0; i < n; ++i) {
    ss_bsdf_sample s;
    double w = 0.0;
    if (ss_bsdf_sample_dir(b, wo, ss_rng_uniform(&rng), ss_rng_uniform(&rng), ss_rng_uniform(&rng),
                           &s)) {
      w = s.f.x * fabs(s.wi.z) / s.pdf;
    }
    s1 += w;
    s2 += w * w;
  }
  *mean = s1 / n;
  *sem = sqrt(fmax(0.0, s2 / n - *mean * *mean) / n);
}

Test(bsdf, rough_dielectric_albedo_is_at_most_one_and_near_one_when_smooth) {
  const double etas[] = {1.33, 1.0 / 1.33};
  for (int t = 0; t < 2; ++t) {
    for (int e = 0; e < 2; ++e) {
      for (int w = 0; w < 2; ++w) {
        ss_vec3 wo = dir_at(w ? 140.0 : 40.0, 0.0);
        double mean, sem;
        ss_bsdf smooth_ish = rough(types[t], 0.01, etas[e], SS_TRANSPORT_IMPORTANCE);
        albedo(&smooth_ish, wo, 100000, 400 + (uint64_t)(4 * t + 2 * e + w), &mean, &sem);
        cr_assert(mean <= 1.0 + 3.0 * sem && mean > 0.995, "%s eta %g wo %d alpha 0.01: %g +- %g",
                  ss_microfacet_type_name(types[t]), etas[e], w, mean, sem);
        ss_bsdf very_rough = rough(types[t], 0.8, etas[e], SS_TRANSPORT_IMPORTANCE);
        albedo(&very_rough, wo, 100000, 500 + (uint64_t)(4 * t + 2 * e + w), &mean, &sem);
        /* Single scattering loses the energy of multiply-bounced paths. */
        cr_assert(mean <= 1.0 + 3.0 * sem && mean > 0.6, "%s eta %g wo %d alpha 0.8: %g +- %g",
                  ss_microfacet_type_name(types[t]), etas[e], w, mean, sem);
      }
    }
  }
}

Test(bsdf, rough_dielectric_obeys_generalised_reciprocity) {
  ss_rng rng;
  ss_rng_seed(&rng, 600, 1);
  const double eta = 1.33;
  for (int t = 0; t < 2; ++t) {
    ss_bsdf rad = rough(types[t], 0.3, eta, SS_TRANSPORT_RADIANCE);
    ss_bsdf imp = rough(types[t], 0.3, eta, SS_TRANSPORT_IMPORTANCE);
    int nonzero = 0;
    for (int i = 0; i < 20000; ++i) {
      ss_vec3 wo = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
      ss_vec3 wi = ss_sample_uniform_sphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
      double n_o = wo.z > 0.0 ? 1.0 : eta, n_i = wi.z > 0.0 ? 1.0 : eta;
      double a = ss_bsdf_eval(&rad, wo, wi).x / (n_o * n_o);
      double b = ss_bsdf_eval(&rad, wi, wo).x / (n_i * n_i);
      /* Near-opposite wo and wi make the half vector ill-conditioned. */
      cr_assert_float_eq(a, b, 1e-6 * fabs(a) + 1e-300, "radiance mode, pair %d", i);
      /* Importance mode is the adjoint of radiance mode. */
      double c = ss_bsdf_eval(&imp, wo, wi).x, d = ss_bsdf_eval(&rad, wi, wo).x;
      cr_assert_float_eq(c, d, 1e-6 * fabs(c) + 1e-300, "importance mode, pair %d", i);
      /* The modes differ by exactly 1/eta_rel^2 on transmission. */
      if (wo.z * wi.z < 0.0 && c > 1e-200) {
        double etap = n_i / n_o;
        cr_assert_float_eq(ss_bsdf_eval(&rad, wo, wi).x * etap * etap, c, 1e-12 * c);
        ++nonzero;
      }
    }
    cr_assert_gt(nonzero, 1000);
  }
}

Test(bsdf, smooth_dielectric_picks_lobes_by_fresnel_and_obeys_snell) {
  ss_bsdf rad, imp;
  ss_error err;
  const double eta = 1.33;
  cr_assert_eq(ss_bsdf_dielectric_init(&rad, eta, SS_TRANSPORT_RADIANCE, &err), SS_OK);
  cr_assert_eq(ss_bsdf_dielectric_init(&imp, eta, SS_TRANSPORT_IMPORTANCE, &err), SS_OK);
  cr_assert(imp.lobes & SS_BSDF_DELTA);
  ss_vec3 wo = dir_at(60.0, 45.0);
  double fr = ss_fresnel_dielectric(wo.z, eta);
  ss_rng rng;
  ss_rng_seed(&rng, 700, 1);
  const int n = 100000;
  int reflected = 0;
  for (int i = 0; i < n; ++i) {
    ss_bsdf_sample s;
    cr_assert(ss_bsdf_sample_dir(&imp, wo, ss_rng_uniform(&rng), 0.5, 0.5, &s));
    cr_assert(s.lobe & SS_BSDF_DELTA);
    /* Each lobe's weight is 1: the Fresnel split is done by the choice. */
    cr_assert_float_eq(s.f.x * fabs(s.wi.z) / s.pdf, 1.0, 1e-12);
    if (s.lobe & SS_BSDF_REFLECTION) {
      ++reflected;
      cr_assert_float_eq(s.wi.z, wo.z, 1e-15);
    } else {
      double sin_o = sqrt(1.0 - wo.z * wo.z), sin_i = sqrt(1.0 - s.wi.z * s.wi.z);
      cr_assert_float_eq(sin_o, eta * sin_i, 1e-12);
      cr_assert_lt(s.wi.z, 0.0);
      cr_assert_float_eq(s.eta, eta, 0.0);
      ss_bsdf_sample sr;
      cr_assert(ss_bsdf_sample_dir(&rad, wo, 0.999999, 0.5, 0.5, &sr));
      cr_assert_float_eq(sr.f.x * fabs(sr.wi.z) / sr.pdf, 1.0 / (eta * eta), 1e-12);
    }
  }
  double sigma = sqrt(n * fr * (1.0 - fr));
  cr_assert_lt(fabs(reflected - n * fr), 5.0 * sigma, "reflected %d, expected %g", reflected,
               n * fr);
  /* From inside beyond the critical angle: total internal reflection. */
  ss_bsdf_sample s;
  cr_assert(ss_bsdf_sample_dir(&imp, dir_at(130.0, 0.0), 0.999, 0.5, 0.5, &s));
  cr_assert(s.lobe & SS_BSDF_REFLECTION);
  cr_assert_float_eq(ss_bsdf_eval(&imp, wo, s.wi).x, 0.0, 0.0);
  cr_assert_float_eq(ss_bsdf_pdf(&imp, wo, s.wi), 0.0, 0.0);
  /* Index matched: straight through with weight 1. */
  ss_bsdf matched;
  ss_microfacet m = make_mf(SS_MICROFACET_GGX, 0.3);
  cr_assert_eq(ss_bsdf_rough_dielectric_init(&matched, 1.0, &m, SS_TRANSPORT_RADIANCE, &err),
               SS_OK);
  cr_assert(ss_bsdf_sample_dir(&matched, wo, 0.3, 0.5, 0.5, &s));
  cr_assert_float_eq(s.wi.x, -wo.x, 1e-15);
  cr_assert_float_eq(s.wi.z, -wo.z, 1e-15);
  cr_assert_float_eq(s.f.x * fabs(s.wi.z) / s.pdf, 1.0, 1e-12);
}

Test(bsdf, invalid_parameters_are_rejected) {
  ss_bsdf b;
  ss_error err;
  ss_microfacet m;
  cr_assert_eq(ss_bsdf_dielectric_init(&b, 0.0, SS_TRANSPORT_RADIANCE, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert_eq(ss_microfacet_init(&m, SS_MICROFACET_GGX, -0.1, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert_eq(ss_microfacet_init(&m, SS_MICROFACET_GGX, NAN, &err), SS_ERR_INVALID_ARGUMENT);
  ss_microfacet_type type;
  cr_assert(ss_microfacet_type_from_name("GGX", &type) && type == SS_MICROFACET_GGX);
  cr_assert_not(ss_microfacet_type_from_name("phong", &type));
}
