/* Conductors: the complex-index Fresnel reflectance, smooth and rough
 * conductors (isotropic and anisotropic, Beckmann and GGX) that sample their
 * own pdf (chi-square), are reciprocal, and with energy compensation
 * reflect everything when F = 1 (white furnace); the named metals' RGB
 * conversion. Tolerances are 4.5 standard errors. */
#include <criterion/criterion.h>

#include "optics/bsdf_albedo.h"
#include "optics/bsdf_chi2.h"
#include "subsurf/bsdf.h"
#include "subsurf/fresnel.h"
#include "subsurf/metals.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/stats.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const ss_microfacet_type types[] = {SS_MICROFACET_BECKMANN, SS_MICROFACET_GGX};

static ss_vec3 grey(double v) { return ss_vec3_make(v, v, v); }

static ss_bsdf make(ss_microfacet_type type, double au, double av, ss_vec3 eta, ss_vec3 k,
                    int compensate) {
  ss_microfacet m;
  ss_error err;
  cr_assert_eq(ss_microfacet_init_anisotropic(&m, type, au, av, &err), SS_OK, "%s", err.message);
  ss_bsdf b;
  cr_assert_eq(ss_bsdf_conductor_init(&b, eta, k, &m, compensate, &err), SS_OK, "%s", err.message);
  return b;
}

Test(conductor, fresnel_without_absorption_is_the_dielectric_one) {
  for (int i = 0; i <= 20; ++i) {
    double c = i / 20.0;
    cr_expect_float_eq(ss_fresnel_conductor(c, 1.5, 0.0), ss_fresnel_dielectric(c, 1.5), 1e-12,
                       "cos %g", c);
  }
}

Test(conductor, fresnel_at_normal_incidence_and_grazing) {
  const double n = 0.2, k = 3.3;
  double r0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
  cr_expect_float_eq(ss_fresnel_conductor(1.0, n, k), r0, 1e-12);
  cr_expect_float_eq(ss_fresnel_conductor(0.0, n, k), 1.0, 1e-12);
  /* A metal's reflectance dips before rising to 1 at grazing (the
   * pseudo-Brewster angle): below R0 somewhere, never above 1. */
  double lowest = 1.0;
  for (int i = 1; i < 100; ++i) {
    double r = ss_fresnel_conductor(i / 100.0, 2.5, 3.0);
    cr_assert(r <= 1.0);
    lowest = fmin(lowest, r);
  }
  cr_expect_lt(lowest, ss_fresnel_conductor(1.0, 2.5, 3.0));
  cr_expect_gt(ss_fresnel_conductor(0.5, 1.0, 1e4), 1.0 - 1e-6);
}

Test(conductor, smooth_reflects_the_fresnel_reflectance) {
  ss_bsdf b;
  ss_error err;
  ss_vec3 eta = ss_vec3_make(0.2, 0.5, 1.4), k = ss_vec3_make(3.0, 2.4, 1.8);
  cr_assert_eq(ss_bsdf_conductor_init(&b, eta, k, NULL, 1, &err), SS_OK, "%s", err.message);
  cr_assert(b.lobes & SS_BSDF_DELTA);
  ss_vec3 wo = ss_vec3_normalize(ss_vec3_make(0.6, 0.2, 0.5));
  ss_bsdf_sample s;
  cr_assert(ss_bsdf_sample_dir(&b, wo, 0.3, 0.4, 0.5, &s));
  ss_vec3 w = ss_vec3_scale(s.f, fabs(s.wi.z) / s.pdf);
  cr_expect_float_eq(w.x, ss_fresnel_conductor(wo.z, 0.2, 3.0), 1e-12);
  cr_expect_float_eq(w.z, ss_fresnel_conductor(wo.z, 1.4, 1.8), 1e-12);
  cr_expect_float_eq(s.wi.z, wo.z, 1e-15);
  /* One-sided: nothing from inside. */
  cr_expect_not(ss_bsdf_sample_dir(&b, ss_vec3_neg(wo), 0.3, 0.4, 0.5, &s));
}

Test(conductor, rough_sampling_passes_chi_square) {
  const double alphas[][2] = {{0.3, 0.3}, {0.1, 0.6}};
  const double wo_theta[] = {30.0, 75.0};
  const int tests = 2 * 2 * 2 * 2;
  double level = ss_chi2_sidak_alpha(0.01, tests);
  int n = 0;
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 2; ++a) {
      for (int c = 0; c < 2; ++c) {
        ss_bsdf b =
            make(types[t], alphas[a][0], alphas[a][1], grey(0.3), ss_vec3_make(3.0, 2.0, 1.0), c);
        for (int w = 0; w < 2; ++w, ++n) {
          double th = wo_theta[w] * SS_PI / 180.0;
          char what[96];
          snprintf(what, sizeof what, "%s alpha (%g, %g) compensated %d wo %g",
                   ss_microfacet_type_name(types[t]), alphas[a][0], alphas[a][1], c, wo_theta[w]);
          /* Azimuth 40 degrees: off both axes of the anisotropy. */
          double ph = 40.0 * SS_PI / 180.0;
          ss_vec3 wo = ss_vec3_make(sin(th) * cos(ph), sin(th) * sin(ph), cos(th));
          expect_rough_bsdf_chi2(&b, wo, 150000, (uint64_t)(500 + n), level, what);
        }
      }
    }
  }
}

Test(conductor, rough_is_reciprocal) {
  ss_rng rng;
  ss_rng_seed(&rng, 4, 4);
  for (int t = 0; t < 2; ++t) {
    ss_bsdf b = make(types[t], 0.2, 0.7, grey(0.5), ss_vec3_make(4.0, 2.5, 1.5), 1);
    cr_assert(b.cms != NULL);
    for (int i = 0; i < 300; ++i) {
      ss_vec3 wo = ss_sample_cosine_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
      ss_vec3 wi = ss_sample_uniform_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
      ss_vec3 f = ss_bsdf_eval(&b, wo, wi), g = ss_bsdf_eval(&b, wi, wo);
      cr_expect(fabs(f.x - g.x) <= 1e-9 * fmax(f.x, g.x) &&
                    fabs(f.z - g.z) <= 1e-9 * fmax(f.z, g.z),
                "f(wo, wi) = (%g, %g), f(wi, wo) = (%g, %g)", f.x, f.z, g.x, g.z);
    }
  }
}

/* The white furnace: with F = 1 (k = 10^4) the compensated conductor
 * reflects everything from every direction; without compensation it loses
 * energy (more at high roughness), which the test must see. */
Test(conductor, compensated_with_unit_fresnel_reflects_everything) {
  const double alphas[][2] = {{0.3, 0.3}, {1.0, 1.0}, {0.15, 0.9}};
  const double mus[] = {0.15, 0.5, 0.95};
  const double phis[] = {0.0, 0.6, 1.3};
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 3; ++a) {
      ss_bsdf b = make(types[t], alphas[a][0], alphas[a][1], grey(1.0), grey(1e4), 1);
      ss_bsdf single = make(types[t], alphas[a][0], alphas[a][1], grey(1.0), grey(1e4), 0);
      for (int m = 0; m < 3; ++m) {
        ss_vec3 wo = ss_spherical_direction(mus[m], phis[m]);
        ss_running_stats st, lost;
        ss_rng rng;
        ss_rng_seed(&rng, (uint64_t)(10 * a + m), (uint64_t)t);
        ss_running_stats_init(&st);
        ss_running_stats_init(&lost);
        for (int i = 0; i < 20000; ++i) {
          double uc = ss_rng_uniform(&rng), u1 = ss_rng_uniform(&rng), u2 = ss_rng_uniform(&rng);
          ss_bsdf_sample s;
          ss_running_stats_add(
              &st, ss_bsdf_sample_dir(&b, wo, uc, u1, u2, &s) ? s.f.y * s.wi.z / s.pdf : 0.0);
          ss_running_stats_add(&lost, ss_bsdf_sample_dir(&single, wo, uc, u1, u2, &s)
                                          ? s.f.y * s.wi.z / s.pdf
                                          : 0.0);
        }
        double se = ss_running_stats_stderr(&st);
        cr_expect(fabs(st.mean - 1.0) <= 4.5 * se + 2e-3,
                  "%s alpha (%g, %g) mu %g phi %g: albedo %.5f +- %.5f (single %.5f)",
                  ss_microfacet_type_name(types[t]), alphas[a][0], alphas[a][1], mus[m], phis[m],
                  st.mean, se, lost.mean);
        if (alphas[a][0] >= 1.0) {
          cr_expect_lt(lost.mean, 0.95, "single scattering at alpha 1 loses energy: %g", lost.mean);
        }
      }
    }
  }
}

/* The tables hold the single-scattering albedo with F = 1. */
Test(conductor, table_holds_the_single_scattering_albedo) {
  ss_bsdf single = make(SS_MICROFACET_GGX, 0.2, 0.8, grey(1.0), grey(1e4), 0);
  ss_bsdf comp = make(SS_MICROFACET_GGX, 0.2, 0.8, grey(1.0), grey(1e4), 1);
  for (int m = 1; m <= 4; ++m) {
    for (int p = 0; p < 3; ++p) {
      ss_vec3 wo = ss_spherical_direction(0.22 * m, 0.5 * p + 0.1);
      ss_running_stats st;
      ss_running_stats_init(&st);
      ss_rng rng;
      ss_rng_seed(&rng, (uint64_t)m, (uint64_t)p);
      for (int i = 0; i < 20000; ++i) {
        ss_bsdf_sample s;
        double w =
            ss_bsdf_sample_dir(&single, wo, 0.0, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &s)
                ? s.f.x * s.wi.z / s.pdf
                : 0.0;
        ss_running_stats_add(&st, w);
      }
      double tab = ss_conductor_ms_albedo(comp.cms, wo);
      cr_expect(fabs(tab - st.mean) <= 4.5 * ss_running_stats_stderr(&st) + 2e-3,
                "mu %g phi %g: table %.5f, MC %.5f +- %.5f", wo.z, 0.5 * p + 0.1, tab, st.mean,
                ss_running_stats_stderr(&st));
    }
  }
}

Test(conductor, bad_parameters_are_refused) {
  ss_bsdf b;
  ss_error err;
  cr_expect_neq(ss_bsdf_conductor_init(&b, grey(1.0), ss_vec3_make(1.0, -0.1, 1.0), NULL, 0, &err),
                SS_OK);
  cr_expect(strstr(err.message, "k") != NULL, "%s", err.message);
  cr_expect_neq(ss_bsdf_conductor_init(&b, grey(0.0), grey(1.0), NULL, 0, &err), SS_OK);
}

Test(metals, rgb_keeps_the_measured_normal_reflectance) {
  for (size_t i = 0; i < ss_metal_count(); ++i) {
    ss_vec3 eta, k, r = ss_metal_reflectance(i);
    ss_metal_rgb(i, &eta, &k);
    const double e[3] = {eta.x, eta.y, eta.z}, kk[3] = {k.x, k.y, k.z}, rr[3] = {r.x, r.y, r.z};
    for (int c = 0; c < 3; ++c) {
      cr_expect_float_eq(ss_fresnel_conductor(1.0, e[c], kk[c]), rr[c], 1e-9, "%s channel %d",
                         ss_metal_name(i), c);
    }
    cr_expect(strstr(ss_metal_names(), ss_metal_name(i)) != NULL);
    cr_expect_eq(ss_metal_find(ss_metal_name(i)), (int)i);
  }
  cr_expect_eq(ss_metal_find("unobtainium"), -1);
  cr_expect_eq(ss_metal_find("au"), ss_metal_find("Au"));
}

/* The colours people know: gold and copper reflect red most and blue
 * least, silver and aluminium are bright and nearly neutral. The figures
 * are the normal-incidence reflectance of the measured data (gold about
 * 0.95 at 700 nm and 0.38 at 450 nm in JohnsonChristy1972). */
Test(metals, colours_are_those_of_the_metals) {
  ss_vec3 au = ss_metal_reflectance((size_t)ss_metal_find("Au"));
  ss_vec3 cu = ss_metal_reflectance((size_t)ss_metal_find("Cu"));
  ss_vec3 ag = ss_metal_reflectance((size_t)ss_metal_find("Ag"));
  ss_vec3 al = ss_metal_reflectance((size_t)ss_metal_find("Al"));
  cr_expect(au.x > au.y && au.y > au.z && au.z < 0.5 && au.x > 0.85, "Au (%g, %g, %g)", au.x, au.y,
            au.z);
  cr_expect(cu.x > cu.y && cu.y > cu.z, "Cu (%g, %g, %g)", cu.x, cu.y, cu.z);
  cr_expect(fmin(ag.x, fmin(ag.y, ag.z)) > 0.85, "Ag (%g, %g, %g)", ag.x, ag.y, ag.z);
  cr_expect(fmin(al.x, fmin(al.y, al.z)) > 0.85 && fmax(al.x, fmax(al.y, al.z)) < 0.95,
            "Al (%g, %g, %g)", al.x, al.y, al.z);
  double n, k;
  ss_metal_index_at((size_t)ss_metal_find("Au"), 659.5, &n, &k);
  cr_expect_float_eq(n, 0.14, 1e-9);
  cr_expect_float_eq(k, 3.697, 1e-9);
}
