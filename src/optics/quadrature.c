/* Fixed Gauss-Legendre panels (quadrature.h). */
#include "subsurf/quadrature.h"

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
