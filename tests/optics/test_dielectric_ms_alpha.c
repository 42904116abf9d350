/* Energy compensation over a textured roughness: the tables over
 * alpha (ss_dielectric_ms_alpha) equal the per-material tables at their
 * nodes, hold the single-scattering albedo between them, give the
 * compensated BSDF albedo 1 on both sides at roughnesses between nodes,
 * and are built once per (distribution, eta) and shared. */
#include <criterion/criterion.h>

#include "optics/bsdf_albedo.h"
#include "subsurf/bsdf.h"
#include "subsurf/rng.h"
#include "subsurf/stats.h"

#include <math.h>
#include <string.h>

static const ss_microfacet_type types[] = {SS_MICROFACET_BECKMANN, SS_MICROFACET_GGX};

static const ss_dielectric_ms_alpha *tables(ss_microfacet_type type, double eta, double lo,
                                            double hi) {
  const ss_dielectric_ms_alpha *t;
  ss_error err;
  cr_assert_eq(ss_dielectric_ms_alpha_get(type, eta, lo, hi, &t, &err), SS_OK, "%s", err.message);
  cr_assert_not_null(t);
  return t;
}

/* The compensated BSDF at alpha: from the tables over alpha (t) or, with t
 * NULL, from its own tables. */
static ss_bsdf make(ss_microfacet_type type, double alpha, double eta,
                    const ss_dielectric_ms_alpha *t) {
  ss_microfacet m;
  ss_error err;
  cr_assert_eq(ss_microfacet_init(&m, type, alpha, &err), SS_OK, "%s", err.message);
  ss_bsdf b;
  ss_status st = t ? ss_bsdf_rough_dielectric_ms_at(&b, eta, &m, SS_TRANSPORT_IMPORTANCE, t, &err)
                   : ss_bsdf_rough_dielectric_ms_init(&b, eta, &m, SS_TRANSPORT_IMPORTANCE, &err);
  cr_assert_eq(st, SS_OK, "%s", err.message);
  cr_assert(b.ms.on);
  return b;
}

Test(dielectric_ms_alpha, nodes_equal_the_per_material_tables) {
  const double alphas[] = {0.3, 0.65, 1.5};
  for (int t = 0; t < 2; ++t) {
    for (int a = 0; a < 3; ++a) {
      const ss_dielectric_ms_alpha *tab = tables(types[t], 1.33, alphas[a], alphas[a]);
      ss_bsdf own = make(types[t], alphas[a], 1.33, NULL),
              at = make(types[t], alphas[a], 1.33, tab);
      for (int side = 0; side < 2; ++side) {
        for (int k = 0; k <= SS_DIELECTRIC_MS_NODES; ++k) {
          cr_expect_eq(own.ms.e[side][k], at.ms.e[side][k], "%s alpha %g side %d node %d",
                       ss_microfacet_type_name(types[t]), alphas[a], side, k);
        }
        cr_expect_eq(own.ms.e_avg[side], at.ms.e_avg[side]);
        cr_expect_float_eq(own.ms.x[side], at.ms.x[side], 1e-14);
      }
    }
  }
}

/* Halfway between nodes, alpha 0.1 to 1.2, the interpolated albedo is
 * within 3e-3 of the table built at that roughness at every cosine (the
 * same estimator, so only the interpolation counts; 2.5e-3 measured, for
 * Beckmann at alpha 1.0625, in a cell of width 1/8). */
Test(dielectric_ms_alpha, interpolation_holds_the_single_scattering_albedo) {
  const double alphas[] = {0.1125, 0.3125, 0.6875, 1.0625, 1.1875}, etas[] = {1.5, 1.0 / 1.33};
  for (int t = 0; t < 2; ++t) {
    for (int e = 0; e < 2; ++e) {
      for (int a = 0; a < 5; ++a) {
        /* Only the cell's two nodes: the test stays cheap under sanitizers. */
        const ss_dielectric_ms_alpha *tab = tables(types[t], etas[e], alphas[a], alphas[a]);
        ss_bsdf own = make(types[t], alphas[a], etas[e], NULL);
        ss_bsdf at = make(types[t], alphas[a], etas[e], tab);
        double worst = 0.0;
        for (int side = 0; side < 2; ++side) {
          for (int k = 0; k <= SS_DIELECTRIC_MS_NODES; ++k) {
            worst = fmax(worst, fabs(own.ms.e[side][k] - at.ms.e[side][k]));
          }
        }
        cr_expect(worst <= 3e-3, "%s eta %g alpha %g: interpolated albedo off by %g",
                  ss_microfacet_type_name(types[t]), etas[e], alphas[a], worst);
      }
    }
  }
}

Test(dielectric_ms_alpha, interpolated_compensation_has_albedo_one) {
  const double mus[] = {0.15, 0.5, 0.95};
  for (int t = 0; t < 2; ++t) {
    const ss_dielectric_ms_alpha *tab = tables(types[t], 1.5, 0.4, 0.6);
    ss_bsdf b = make(types[t], 0.4321, 1.5, tab);
    for (int side = 0; side < 2; ++side) {
      for (int m = 0; m < 3; ++m) {
        ss_running_stats st;
        albedo(&b, mus[m], side == 0 ? 1.0 : -1.0, 10000, (uint64_t)(m + 3 * side), &st);
        double se = ss_running_stats_stderr(&st);
        cr_expect(fabs(st.mean - 1.0) <= 4.5 * se + 1e-3, "%s side %d mu %g: albedo %.5f +- %.5f",
                  ss_microfacet_type_name(types[t]), side, mus[m], st.mean, se);
      }
    }
  }
}

Test(dielectric_ms_alpha, tables_are_shared_per_distribution_and_eta) {
  const ss_dielectric_ms_alpha *a = tables(SS_MICROFACET_GGX, 1.4, 0.2, 0.3);
  cr_expect_eq(tables(SS_MICROFACET_GGX, 1.4, 0.25, 0.35), a, "same (distribution, eta)");
  cr_expect_neq(tables(SS_MICROFACET_BECKMANN, 1.4, 0.2, 0.3), a, "another distribution");
  cr_expect_neq(tables(SS_MICROFACET_GGX, 1.45, 0.2, 0.3), a, "another eta");
}

Test(dielectric_ms_alpha, bad_arguments_are_refused) {
  const ss_dielectric_ms_alpha *t;
  ss_error err;
  cr_expect_eq(ss_dielectric_ms_alpha_get(SS_MICROFACET_GGX, 1.0, 0.1, 0.2, &t, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "eta"), "%s", err.message);
  cr_expect_eq(ss_dielectric_ms_alpha_get(SS_MICROFACET_GGX, 1.5, 0.1, 4.5, &t, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "roughness"), "%s", err.message);
  cr_expect_eq(ss_dielectric_ms_alpha_get(SS_MICROFACET_GGX, 1.5, 0.3, 0.2, &t, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect_null(t);
}
