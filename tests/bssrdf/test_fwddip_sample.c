/* The samplers of the forward scattering dipole (subsurf/fwddip.h): each
 * passes a chi-square test against its own pdf, and the estimators they
 * drive converge to the quantities they estimate. */
#include "bssrdf/bssrdf_test_util.h"
#include "subsurf/fwddip.h"

typedef struct {
  const ss_bssrdf *b;
  ss_vec3 w_i;
} brdf_ctx;

static int brdf_sample(void *vctx, double u1, double u2, double u3, ss_vec3 *dir) {
  brdf_ctx *c = vctx;
  double pdf;
  (void)u3;
  return ss_fwddip_brdf_sample(c->b, c->w_i, u1, u2, dir, &pdf);
}

static double brdf_pdf(void *vctx, ss_vec3 dir) {
  brdf_ctx *c = vctx;
  return ss_fwddip_brdf_pdf(c->b, c->w_i, dir);
}

static ss_vec3 incidence(double deg) {
  double t = deg * SS_PI / 180.0;
  return ss_vec3_make(-sin(t), 0.0, cos(t));
}

Test(fwddip_sample, brdf_sampler_passes_chi_square_against_its_pdf) {
  ss_bssrdf *b = make_gray("fwddip-brdf", 1.0 / 1.01, 1.01, 1.0, 0.9);
  const double angles[] = {0.0, 45.0, 80.0};
  for (int i = 0; i < 3; ++i) {
    brdf_ctx c = {b, incidence(angles[i])};
    ss_chi2_sphere_options o;
    ss_chi2_sphere_options_default(&o);
    o.seed = 80 + (uint64_t)i;
    ss_chi2_result res;
    ss_chi2_test_sphere(brdf_sample, brdf_pdf, &c, &o, &res);
    cr_expect(res.p_value > ss_chi2_sidak_alpha(0.01, 3), "%g deg: %s (p %g)", angles[i],
              res.message, res.p_value);
    cr_expect(fabs(res.pdf_integral - 1.0) < 1e-3, "pdf integrates to %g", res.pdf_integral);
  }
  ss_bssrdf_destroy(b);
}

/* E[f_r cos / pdf] is the albedo (total reflectance), to 4 standard errors. */
Test(fwddip_sample, brdf_sampler_estimates_the_albedo) {
  ss_bssrdf *b = make_gray("fwddip-brdf", 1.0 / 1.01, 1.01, 1.33, 0.9);
  const double angles[] = {0.0, 80.0};
  ss_rng rng;
  ss_rng_seed(&rng, 8, 6);
  for (int i = 0; i < 2; ++i) {
    ss_vec3 w_i = incidence(angles[i]);
    double sum = 0.0, sum2 = 0.0;
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
      ss_vec3 w_o;
      double pdf, f[3], v = 0.0;
      if (ss_fwddip_brdf_sample(b, w_i, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &w_o, &pdf) &&
          w_o.z > 0.0) {
        ss_bssrdf_brdf(b, w_i, w_o, f);
        v = f[0] * w_o.z / pdf;
      }
      sum += v;
      sum2 += v * v;
    }
    double mean = sum / n, se = sqrt((sum2 / n - mean * mean) / n), total[3];
    ss_bssrdf_total_reflectance(b, w_i.z, total);
    cr_expect(fabs(mean - total[0]) < 4.0 * se + 2e-3 * total[0], "%g deg: %g +- %g vs %g",
              angles[i], mean, se, total[0]);
  }
  ss_bssrdf_destroy(b);
}
