/* The BSSRDF handle (private to src/bssrdf): a model's operations, its state
 * and the length scales the generic quadratures of observe.c use. */
#ifndef SUBSURF_BSSRDF_HANDLE_H
#define SUBSURF_BSSRDF_HANDLE_H

#include "subsurf/bssrdf.h"

struct ss_bssrdf {
  const ss_bssrdf_ops *ops;
  void *state;
  ss_bssrdf_params params;
  double small_scale; /* below the smallest structure of any profile */
  double large_scale; /* beyond which every profile is negligible */
  double t_out;       /* models with a point source: 1 - 2 C1(1/eta), their exit lobe's
                         part (0 when built for one path vertex: computed per call) */
};

/* Sets the quadrature scales once the model's state exists. */
void ss_bssrdf_observe_init(ss_bssrdf *b);

/* A callback filling three channels at abscissa x. */
typedef void (*ss_vec_fn)(void *ctx, double x, double out[SS_BSSRDF_CHANNELS]);

/* Vector version of the Gauss-Legendre panel rule of bssrdf_util.h. */
void ss_vec_integrate(ss_vec_fn f, void *ctx, double a, double b, int panels,
                      double out[SS_BSSRDF_CHANNELS]);
/* Integral over [0, inf) of a function with structure at scales from `small`
 * to `large`: [0, small], then panels doubling in width up to 64 * large (f
 * must have decayed there). */
void ss_vec_integrate_halfline(ss_vec_fn f, void *ctx, double small, double large,
                               double out[SS_BSSRDF_CHANNELS]);
/* Geometric panels over [a, b] (a may be 0: then [0, b/64] is the first). */
void ss_vec_integrate_log(ss_vec_fn f, void *ctx, double a, double b,
                          double out[SS_BSSRDF_CHANNELS]);

#endif
