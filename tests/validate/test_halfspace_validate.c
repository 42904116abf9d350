/* Slow validation of the reference itself (make validate): Chandrasekhar's
 * exact half-space albedo and exitant radiance over a grid of albedos and
 * angles, at ten times the precision of the unit tests. */
#include "subsurf/halfspace.h"
#include "subsurf/sampling.h"

#include "transport/chandrasekhar.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#define DEG (SS_PI / 180.0)

Test(halfspace_validate, albedo_and_radiance_match_chandrasekhar_on_a_grid) {
  const double albedos[] = {0.5, 0.8, 0.95, 0.99, 0.999};
  const double thetas[] = {0.0, 30.0, 60.0, 80.0};
  printf("%8s %6s %10s %10s %10s %8s\n", "albedo", "theta", "R (MC)", "stderr", "exact", "dev/err");
  for (int a = 0; a < 5; ++a) {
    h_function hf;
    h_solve(&hf, albedos[a]);
    for (int t = 0; t < 4; ++t) {
      ss_halfspace_params p;
      ss_halfspace_params_default(&p);
      p.medium.sigma_s = ss_rgb_gray(albedos[a]);
      p.medium.sigma_a = ss_rgb_gray(1.0 - albedos[a]);
      p.theta_i = thetas[t] * DEG;
      p.paths = 4000000;
      p.threads = 2;
      p.seed = (uint64_t)(a * 10 + t);
      p.n_theta_o = 2;
      p.theta_o[0] = 0.0;
      p.theta_o[1] = 70.0 * DEG;
      p.xmin = -2000.0;
      p.xmax = 2000.0;
      p.xbins = 1;
      ss_halfspace_result *r = NULL;
      ss_error err;
      cr_assert_eq(ss_halfspace_run(&p, &r, &err), SS_OK, "%s", err.message);
      double exact = h_albedo(&hf, cos(p.theta_i));
      double dev = (r->reflectance.value - exact) / r->reflectance.error;
      printf("%8g %6g %10.6f %10.6f %10.6f %8.2f\n", albedos[a], thetas[t], r->reflectance.value,
             r->reflectance.error, exact, dev);
      cr_expect(fabs(dev) < 3.5, "albedo %g theta %g: %.2f standard errors off", albedos[a],
                thetas[t], dev);
      for (int k = 0; k < 2; ++k) {
        double got = r->directions[k].value * 4000.0, e = r->directions[k].error * 4000.0;
        double want = h_radiance(&hf, cos(p.theta_o[k]), cos(p.theta_i));
        cr_expect(fabs(got - want) < 3.5 * e + 1e-5 * want,
                  "albedo %g theta_i %g theta_o %g: %.6f +- %.6f vs %.6f", albedos[a], thetas[t],
                  p.theta_o[k] / DEG, got, e, want);
      }
      ss_halfspace_result_destroy(r);
    }
  }
}
