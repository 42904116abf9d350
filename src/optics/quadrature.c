/* Fixed Gauss-Legendre panels (quadrature.h). */
#include "subsurf/quadrature.h"

#include "subsurf/sampling.h"

#include <math.h>

const double ss_gl8_x[SS_GL8_N] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                   -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                   0.7966664774136267,  0.9602898564975363};
const double ss_gl8_w[SS_GL8_N] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                   0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                   0.2223810344533745, 0.1012285362903763};

double ss_gl_integrate(ss_scalar_fn f, void *ctx, double a, double b, int panels) {
  double h = (b - a) / panels, sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    double mid = a + (p + 0.5) * h, half = 0.5 * h;
    for (int k = 0; k < SS_GL8_N; ++k) {
      sum += ss_gl8_w[k] * half * f(ctx, mid + half * ss_gl8_x[k]);
    }
  }
  return sum;
}

void ss_gauss_legendre(int n, double *x, double *w) {
  for (int i = 0; i < n; ++i) {
    /* The three-term recurrence of P_n and P_n' = n (z P_n - P_{n-1}) / (z^2 - 1). */
    double z = cos(SS_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      double dz = p1 / dp;
      z -= dz;
      if (fabs(dz) < 1e-16) {
        break;
      }
    }
    x[i] = z;
    w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}
