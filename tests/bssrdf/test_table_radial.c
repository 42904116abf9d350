/* pbrt-style radial table: accuracy against direct PBD, the sampler against
 * its pdf, rho_eff and its inversion, and the `table-radial` model. */
#include "subsurf/bssrdf.h"
#include "subsurf/chi2.h"
#include "subsurf/pbd.h"
#include "subsurf/sampling.h"
#include "subsurf/table_radial.h"

#include "bssrdf/bssrdf_test_util.h"

#include <criterion/criterion.h>
#include <math.h>

extern const ss_bssrdf_ops ss_bssrdf_model_table_radial;

static ss_table_radial *table;

static void build(void) {
  ss_error err;
  cr_assert_eq(ss_table_radial_build(1.33, 0.0, &table, &err), SS_OK, "%s", err.message);
}

static void teardown(void) { ss_table_radial_destroy(table); }

TestSuite(table_radial, .init = build, .fini = teardown);

/* Interior: between the nodes, inside the central 98% of the radial
 * energy (the first interval holds r log r, the far tail decays by e^-3
 * between nodes; both carry < 1% of the samples). */
Test(table_radial, matches_direct_pbd_within_half_percent_at_interior_points) {
  const double rhos[] = {0.1, 0.3, 0.5, 0.8, 0.9, 0.99};
  for (size_t k = 0; k < sizeof rhos / sizeof rhos[0]; ++k) {
    ss_pbd p;
    ss_error err;
    cr_assert_eq(ss_pbd_init(&p, rhos[k], 1.0 - rhos[k], 0.0, 1.33, 32, &err), SS_OK);
    ss_pbd_beam beam = ss_pbd_beam_make(&p, 0.0);
    double lo = ss_table_radial_sample(table, rhos[k], 0.01);
    double hi = ss_table_radial_sample(table, rhos[k], 0.99);
    int checked = 0;
    for (size_t i = 1; i + 1 < table->n_r; ++i) {
      for (int s = 1; s < 4; ++s) {
        double r = table->radius[i] + (table->radius[i + 1] - table->radius[i]) * s / 4.0;
        if (r < lo || r > hi) {
          continue;
        }
        double ref = ss_pbd_ms(&p, &beam, r, 0.0) + ss_pbd_ss(&p, r);
        double v = ss_table_radial_sp(table, rhos[k], r);
        cr_assert_float_eq(v, ref, 0.005 * ref, "rho %g r %g: %g vs %g", rhos[k], r, v, ref);
        ++checked;
      }
    }
    cr_assert_gt(checked, 50);
  }
}

Test(table_radial, rho_eff_matches_the_direct_effective_albedo) {
  /* The table integrates up to r = 204 mean free paths with a spline: within
   * 1% of the converged integral for absorbing media. */
  const double rhos[] = {0.3, 0.5, 0.9, 0.99};
  for (size_t k = 0; k < 4; ++k) {
    ss_pbd p;
    ss_error err;
    cr_assert_eq(ss_pbd_init(&p, rhos[k], 1.0 - rhos[k], 0.0, 1.33, 32, &err), SS_OK);
    double direct = ss_pbd_effective_albedo(&p);
    cr_assert_float_eq(ss_table_radial_rho_eff(table, rhos[k]), direct, 0.01 * direct);
  }
}

Test(table_radial, subsurface_from_diffuse_inverts_rho_eff) {
  for (double rho = 0.05; rho < 1.0; rho += 0.0731) {
    double a = ss_table_radial_rho_eff(table, rho);
    cr_assert_float_eq(ss_table_radial_invert(table, a), rho, 2e-4, "rho %g", rho);
  }
  double diffuse[3] = {0.2, 0.5, 0.8}, mfp[3] = {1.0, 0.5, 2.0}, ss[3], sa[3];
  ss_error err;
  cr_assert_eq(ss_subsurface_from_diffuse(table, diffuse, mfp, ss, sa, &err), SS_OK);
  for (int c = 0; c < 3; ++c) {
    cr_assert_float_eq(ss[c] + sa[c], 1.0 / mfp[c], 1e-12);
    double rho = ss[c] * mfp[c];
    cr_assert_float_eq(ss_table_radial_rho_eff(table, rho), diffuse[c], 1e-4);
  }
  diffuse[1] = 1.5;
  cr_assert_eq(ss_subsurface_from_diffuse(table, diffuse, mfp, ss, sa, &err),
               SS_ERR_INVALID_ARGUMENT);
}

typedef struct {
  double rho;
} radius_ctx;

static int sample_r(void *c, double u1, double u2, double *x) {
  (void)u2;
  *x = ss_table_radial_sample(table, ((radius_ctx *)c)->rho, u1);
  return *x > 0.0;
}

static double pdf_r(void *c, double r) {
  return ss_table_radial_pdf_area(table, ((radius_ctx *)c)->rho, r) * 2.0 * SS_PI * r;
}

Test(table_radial, radius_sampler_matches_its_pdf_chi2) {
  /* Cells aligned with the spline pieces, two per piece. */
  double edges[2 * (SS_TABLE_RADIUS_COUNT - 1) + 1];
  size_t n = 2 * (table->n_r - 1);
  for (size_t i = 0; i + 1 < table->n_r; ++i) {
    edges[2 * i] = table->radius[i];
    edges[2 * i + 1] = 0.5 * (table->radius[i] + table->radius[i + 1]);
  }
  edges[n] = table->radius[table->n_r - 1] * (1.0 + 1e-12);
  const double rhos[] = {0.5, 0.87, 0.99};
  for (int k = 0; k < 3; ++k) {
    radius_ctx ctx = {rhos[k]};
    ss_chi2_result res;
    ss_chi2_test_1d(sample_r, pdf_r, &ctx, edges, n, 300000, 11 + (uint64_t)k, &res);
    cr_assert(res.p_value > ss_chi2_sidak_alpha(0.01, 3), "rho %g: %s", rhos[k], res.message);
    cr_assert_eq(res.invalid, 0);
    cr_assert_float_eq(res.pdf_integral, 1.0, 1e-5, "rho %g", rhos[k]);
  }
}

/* The model in world units (sigma_t = 4): entry sampling against pdf_entry. */
Test(table_radial, model_entry_sampling_matches_pdf_entry_chi2) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  p.eta = 1.33;
  p.medium.sigma_s.c[1] = 3.6;
  p.medium.sigma_a.c[1] = 0.4;
  ss_error err;
  entry_chi2_ctx m = {NULL, 1, 0.3, {{0, 0, 0}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 0, 0}}};
  cr_assert_eq(ss_bssrdf_create_ops(&ss_bssrdf_model_table_radial, &p, &m.b, &err), SS_OK, "%s",
               err.message);
  double rmax = table->radius[table->n_r - 1] / 4.0;
  double edges[2 * (SS_TABLE_RADIUS_COUNT - 1) + 1];
  size_t n = 2 * (table->n_r - 1);
  for (size_t i = 0; i + 1 < table->n_r; ++i) {
    edges[2 * i] = table->radius[i] / 4.0;
    edges[2 * i + 1] = 0.5 * (table->radius[i] + table->radius[i + 1]) / 4.0;
  }
  edges[n] = rmax * (1.0 + 1e-12);
  ss_chi2_result res;
  ss_chi2_test_1d(entry_radius_sample, entry_radius_pdf, &m, edges, n, 200000, 5, &res);
  cr_assert(res.p_value > 0.01, "%s", res.message);
  /* Scale invariance: rho_eff is the same in any units. */
  double rd[3];
  ss_bssrdf_rd(m.b, rd);
  cr_assert_float_eq(rd[1], ss_table_radial_rho_eff(table, 0.9), 1e-12);
  ss_bssrdf_destroy(m.b);
}
