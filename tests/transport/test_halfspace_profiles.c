/* The white Monte Carlo profiles (one run, every albedo) against the
 * half-space reference run once per albedo. */
#include "subsurf/halfspace.h"
#include "subsurf/halfspace_profiles.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

/* Both estimators' bins for albedos 0.5 and 0.95 at eta 1.3, g 0.6: the
 * reflectance within 4 combined standard errors, and the radial bins with at
 * most 2 % of them beyond 3.5 (a weight alpha^(n+1) fails both, a radius
 * scaled by sigma_t instead of sigma_t' the bins). */
Test(halfspace_profiles, one_run_matches_the_reference_run_per_albedo) {
  const double g = 0.6, albedos[] = {0.5, 0.95};
  ss_halfspace_profiles_params pp;
  ss_halfspace_profiles_params_default(&pp);
  pp.g = g;
  pp.n_albedo = 2;
  pp.albedo[0] = albedos[0];
  pp.albedo[1] = albedos[1];
  pp.rmin = 0.05;
  pp.rmax = 20.0;
  pp.rbins = 24;
  pp.paths = 100000;
  pp.seed = 3;
  pp.max_depth = 5000; /* 0.95^5000 ~ 1e-111: the cut paths weigh nothing */
  ss_halfspace_profiles_result *w;
  ss_error err;
  cr_assert_eq(ss_halfspace_profiles_run(&pp, &w, &err), SS_OK, "%s", err.message);
  for (int k = 0; k < 2; ++k) {
    double sigma_t_prime = 1.0 - g * albedos[k];
    ss_halfspace_params hp;
    ss_halfspace_params_default(&hp);
    hp.medium = ss_medium_optics_gray(albedos[k], 1.0 - albedos[k], g, SS_PHASE_HG);
    hp.eta = 1.3;
    hp.paths = 100000;
    hp.seed = 11;
    /* the same bins in units of 1/sigma_t' */
    hp.rmin = pp.rmin / sigma_t_prime;
    hp.rmax = pp.rmax / sigma_t_prime;
    hp.rbins = pp.rbins;
    hp.xbins = hp.ybins = 1;
    ss_halfspace_result *h;
    cr_assert_eq(ss_halfspace_run(&hp, &h, &err), SS_OK, "%s", err.message);
    double dr = fabs(w->reflectance[k].value - h->reflectance.value);
    double er = hypot(w->reflectance[k].error, h->reflectance.error);
    cr_expect(dr < 4.0 * er, "albedo %g: R %g +- %g against %g +- %g", albedos[k],
              w->reflectance[k].value, w->reflectance[k].error, h->reflectance.value,
              h->reflectance.error);
    int far = 0, compared = 0;
    for (int i = 0; i < pp.rbins; ++i) {
      ss_estimate a = w->radial[(size_t)k * (size_t)pp.rbins + (size_t)i];
      /* reference exitance per unit area in 1/sigma_t'^2 */
      double s2 = sigma_t_prime * sigma_t_prime;
      double b = h->radial[i].value / s2, eb = h->radial[i].error / s2;
      double e = hypot(a.error, eb);
      if (e > 0.0 && b > 0.0) {
        compared++;
        far += fabs(a.value - b) > 3.5 * e;
      }
    }
    cr_expect(compared >= pp.rbins - 4, "albedo %g: %d bins compared", albedos[k], compared);
    cr_expect(far <= 0.02 * compared + 0.5, "albedo %g: %d of %d bins beyond 3.5 sigma", albedos[k],
              far, compared);
    ss_halfspace_result_destroy(h);
  }
  ss_halfspace_profiles_result_destroy(w);
}

Test(halfspace_profiles, refuses_bad_parameters) {
  ss_halfspace_profiles_params pp;
  ss_halfspace_profiles_params_default(&pp);
  ss_halfspace_profiles_result *w;
  ss_error err;
  cr_expect_eq(ss_halfspace_profiles_run(&pp, &w, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "albedos") != NULL, "%s", err.message);
  pp.n_albedo = 1;
  pp.albedo[0] = 1.5;
  cr_expect_eq(ss_halfspace_profiles_run(&pp, &w, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "albedo 0") != NULL, "%s", err.message);
  cr_expect_null(w);
}
