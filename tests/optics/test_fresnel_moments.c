/* The Fresnel moments by fixed Gauss-Legendre panels against GSL's adaptive
 * integrator, which they replace (no global error handler toggled per call). */
#include "subsurf/fresnel.h"

#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>

typedef struct {
  int n;
  double eta;
} moment;

static double integrand(double mu, void *p) {
  const moment *m = p;
  return ss_fresnel_dielectric(-mu, m->eta) * pow(mu, m->n);
}

/* The former implementation: closed form below the critical cosine, QAGS to
 * 1e-12 relative above it. */
static double adaptive_moment(int n, double eta) {
  moment m = {n, eta};
  gsl_function f = {integrand, &m};
  double mu_c = eta > 1.0 ? sqrt(1.0 - 1.0 / (eta * eta)) : 0.0, result = 0.0, abserr = 0.0;
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(256);
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_integration_qags(&f, mu_c, 1.0, 0.0, 1e-12, 256, ws, &result, &abserr);
  gsl_set_error_handler(old);
  gsl_integration_workspace_free(ws);
  return pow(mu_c, n + 1) / (n + 1) + result;
}

Test(fresnel_moments, equal_the_adaptive_integral_for_every_index) {
  const double etas[] = {0.5, 0.75, 0.9, 0.99, 1.0, 1.01, 1.1, 1.2, 1.3, 1.33, 1.4, 1.5, 2.0, 3.0};
  for (size_t i = 0; i < sizeof etas / sizeof etas[0]; ++i) {
    for (int n = 0; n <= 3; ++n) {
      double v = ss_fresnel_moment(n, etas[i]), ref = adaptive_moment(n, etas[i]);
      cr_expect(fabs(v - ref) <= 1e-12 * fmax(ref, 1e-3), "eta %g n %d: %.17g vs %.17g", etas[i], n,
                v, ref);
    }
  }
}
