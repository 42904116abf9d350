/* Energy compensation of rough dielectrics (Kulla & Conty 2017): the tables
 * hold the single-scattering albedo, the compensated BSDF has albedo 1 from
 * every direction on both sides, obeys the reciprocity of refraction, and
 * samples its own pdf (chi-square). Tolerances are 4.5 standard errors. */
#include <criterion/criterion.h>

#include "optics/bsdf_albedo.h"
#include "optics/bsdf_chi2.h"
#include "subsurf/bsdf.h"
#include "subsurf/chi2.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/stats.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

static const ss_microfacet_type types[] = {SS_MICROFACET_BECKMANN, SS_MICROFACET_GGX};

static ss_bsdf make(ss_microfacet_type type, double alpha, double eta, int compensated,
                    ss_transport_mode mode) {
  ss_microfacet m;
  ss_error err;
  cr_assert_eq(ss_microfacet_init(&m, type, alpha, &err), SS_OK, "%s", err.message);
  ss_bsdf b;
  ss_status st = compensated ? ss_bsdf_rough_dielectric_ms_init(&b, eta, &m, mode, &err)
                             : ss_bsdf_rough_dielectric_init(&b, eta, &m, mode, &err);
  cr_assert_eq(st, SS_OK, "%s", err.message);
  return b;
}

Test(dielectric_ms, table_holds_the_single_scattering_albedo) {
  const double alphas[] = {0.1, 0.6}, etas[] = {1.33, 1.0 / 1.5};
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 2; ++a) {
      for (int e = 0; e < 2; ++e) {
        ss_bsdf single = make(types[t], alphas[a], etas[e], 0, SS_TRANSPORT_IMPORTANCE);
        ss_bsdf comp = make(types[t], alphas[a], etas[e], 1, SS_TRANSPORT_IMPORTANCE);
        for (int side = 0; side < 2; ++side) {
          for (int k = 5; k <= SS_DIELECTRIC_MS_NODES; k += 9) {
            double mu = (double)k / SS_DIELECTRIC_MS_NODES;
            ss_running_stats st;
            albedo(&single, mu, side == 0 ? 1.0 : -1.0, 10000, (uint64_t)(k + 40 * side), &st);
            double tab = ss_dielectric_ms_albedo(&comp.ms, side, mu);
            cr_expect(fabs(tab - st.mean) <= 4.5 * ss_running_stats_stderr(&st) + 1e-4,
                      "%s alpha %g eta %g side %d mu %g: table %.5f, MC %.5f +- %.5f",
                      ss_microfacet_type_name(types[t]), alphas[a], etas[e], side, mu, tab, st.mean,
                      ss_running_stats_stderr(&st));
          }
        }
      }
    }
  }
}

Test(dielectric_ms, compensated_albedo_is_one_on_both_sides) {
  const double alphas[] = {0.3, 1.0}, etas[] = {1.5, 1.0 / 1.33};
  const double mus[] = {0.15, 0.5, 0.95};
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 2; ++a) {
      for (int e = 0; e < 2; ++e) {
        ss_bsdf b = make(types[t], alphas[a], etas[e], 1, SS_TRANSPORT_IMPORTANCE);
        ss_bsdf single = make(types[t], alphas[a], etas[e], 0, SS_TRANSPORT_IMPORTANCE);
        for (int side = 0; side < 2; ++side) {
          for (int m = 0; m < 3; ++m) {
            double sign = side == 0 ? 1.0 : -1.0;
            ss_running_stats st, lost;
            albedo(&b, mus[m], sign, 10000, (uint64_t)(7 + m + 3 * side), &st);
            albedo(&single, mus[m], sign, 2000, (uint64_t)(7 + m + 3 * side), &lost);
            double se = ss_running_stats_stderr(&st);
            cr_expect(fabs(st.mean - 1.0) <= 4.5 * se + 1e-3,
                      "%s alpha %g eta %g side %d mu %g: albedo %.5f +- %.5f (single %.5f)",
                      ss_microfacet_type_name(types[t]), alphas[a], etas[e], side, mus[m], st.mean,
                      se, lost.mean);
          }
        }
      }
    }
  }
}

/* Veach 1997, eq. 5.14 (generalised reciprocity): for wo outside and wi
 * inside, f(wo, wi) = f(wi, wo) / eta^2 in radiance mode; reflection is
 * symmetric. The split x_s obeys the balance x_0 (1 - E_avg,0) = eta^2 x_1
 * (1 - E_avg,1). */
Test(dielectric_ms, compensated_bsdf_is_reciprocal) {
  ss_rng rng;
  ss_rng_seed(&rng, 3, 3);
  for (int t = 0; t < 2; ++t) {
    for (int e = 0; e < 2; ++e) {
      double eta = e == 0 ? 1.5 : 0.8;
      ss_bsdf b = make(types[t], 0.6, eta, 1, SS_TRANSPORT_RADIANCE);
      const ss_dielectric_ms *ms = &b.ms;
      cr_assert(ms->on);
      cr_expect_float_eq(ms->x[0] * (1.0 - ms->e_avg[0]),
                         eta * eta * ms->x[1] * (1.0 - ms->e_avg[1]), 1e-12);
      for (int i = 0; i < 200; ++i) {
        ss_vec3 wo = ss_sample_cosine_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
        ss_vec3 wi = ss_sample_cosine_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
        ss_vec3 wr = wi;
        wi.z = -wi.z;
        double f = ss_bsdf_eval(&b, wo, wi).x, g = ss_bsdf_eval(&b, wi, wo).x / (eta * eta);
        cr_expect(fabs(f - g) <= 1e-9 * fmax(f, g), "transmission %g vs %g", f, g);
        double r = ss_bsdf_eval(&b, wo, wr).x, r2 = ss_bsdf_eval(&b, wr, wo).x;
        cr_expect(fabs(r - r2) <= 1e-9 * fmax(r, r2), "reflection %g vs %g", r, r2);
      }
    }
  }
}

Test(dielectric_ms, compensated_sampling_passes_chi_square) {
  const double etas[] = {1.33, 1.0 / 1.33};
  const double wo_theta[] = {35.0, 150.0};
  const int tests = 2 * 2 * 2;
  double level = ss_chi2_sidak_alpha(0.01, tests);
  int n = 0;
  for (int t = 0; t < 2; ++t) {
    for (int e = 0; e < 2; ++e) {
      for (int w = 0; w < 2; ++w, ++n) {
        ss_bsdf b = make(types[t], 0.7, etas[e], 1, SS_TRANSPORT_RADIANCE);
        double th = wo_theta[w] * SS_PI / 180.0;
        char what[64];
        snprintf(what, sizeof what, "%s eta %g wo %g", ss_microfacet_type_name(types[t]), etas[e],
                 wo_theta[w]);
        expect_rough_bsdf_chi2(&b, ss_vec3_make(sin(th), 0.0, cos(th)), 150000, (uint64_t)(300 + n),
                               level, what);
      }
    }
  }
}

/* The table's nodes are built in parallel with their own seeds: one thread
 * and two give the same table bit for bit. */
Test(dielectric_ms, table_is_the_same_for_one_and_two_threads) {
  int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  ss_bsdf one = make(SS_MICROFACET_GGX, 0.3, 1.33, 1, SS_TRANSPORT_RADIANCE);
  omp_set_num_threads(2);
  ss_bsdf two = make(SS_MICROFACET_GGX, 0.3, 1.33, 1, SS_TRANSPORT_RADIANCE);
  omp_set_num_threads(threads);
  cr_assert(one.ms.on && two.ms.on);
  /* Field by field: the struct's padding is not part of the table. */
  cr_assert_eq(memcmp(one.ms.e, two.ms.e, sizeof one.ms.e), 0, "the albedo nodes differ");
  cr_assert_eq(memcmp(one.ms.e_avg, two.ms.e_avg, sizeof one.ms.e_avg), 0, "E_avg differs");
  cr_assert_eq(memcmp(one.ms.x, two.ms.x, sizeof one.ms.x), 0, "the shares differ");
}
