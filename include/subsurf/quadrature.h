/* Fixed Gauss-Legendre quadrature: no adaptivity, no allocation and no
 * global error state, so it is safe from any thread. */
#ifndef SUBSURF_QUADRATURE_H
#define SUBSURF_QUADRATURE_H

/* 8-point Gauss-Legendre rule on [-1, 1] (nodes of P_8, Abramowitz & Stegun
 * table 25.4). */
#define SS_GL8_N 8
extern const double ss_gl8_x[SS_GL8_N];
extern const double ss_gl8_w[SS_GL8_N];

/* The n-point Gauss-Legendre rule on [-1, 1] (n >= 1): nodes x (descending)
 * and weights w, by Newton's iteration on the Legendre polynomial P_n. */
void ss_gauss_legendre(int n, double *x, double *w);

typedef double (*ss_scalar_fn)(void *ctx, double x);

/* Integral of f over [a, b] with `panels` equal 8-point panels. */
double ss_gl_integrate(ss_scalar_fn f, void *ctx, double a, double b, int panels);

#endif
