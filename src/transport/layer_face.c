/* The boundaries of a stack as adding-doubling operators (layer_ops.h): a
 * smooth dielectric face and a Lambertian base. */
#include "transport/layer_ops.h"

#include "subsurf/fresnel.h"

#include <math.h>
#include <stddef.h>

/* A smooth face keeps directions (all of it is in d) and maps node k of one
 * space onto node k of the other. Radiance / n^2 is conserved across it, so
 * transmitted radiance gains eta^2 going in and loses it going out. */
void layer_face(layer_slab *s, const layer_nodes *nd, int top) {
  int n = nd->n;
  layer_op *ops[4] = {&s->r, &s->t, &s->rs, &s->ts};
  for (int i = 0; i < 4; ++i) {
    layer_op_zero(ops[i], n);
  }
  double eta2 = nd->eta * nd->eta;
  for (int k = 0; k < n; ++k) {
    double f_out = nd->present[LAYER_OUT][k] ? ss_fresnel_dielectric(nd->mu[LAYER_OUT][k], nd->eta)
                                             : 1.0; /* never reached from outside */
    double f_med =
        nd->present[LAYER_MED][k] ? ss_fresnel_dielectric(-nd->mu[LAYER_MED][k], nd->eta) : 1.0;
    int both = nd->present[LAYER_OUT][k] && nd->present[LAYER_MED][k];
    double in = both ? (1.0 - f_out) * eta2 : 0.0, out = both ? (1.0 - f_med) / eta2 : 0.0;
    double r_out = nd->present[LAYER_OUT][k] ? f_out : 0.0;
    double r_med = nd->present[LAYER_MED][k] ? f_med : 0.0;
    /* The top face has the outside above it, the bottom face below it. */
    s->r.d[k] = top ? r_out : r_med;
    s->t.d[k] = top ? in : out;
    s->rs.d[k] = top ? r_med : r_out;
    s->ts.d[k] = top ? out : in;
  }
}

/* f = albedo / pi for m = 0: s = 2 pi f / eta^2; nothing below. */
void layer_lambert(layer_slab *s, const layer_nodes *nd, double albedo, int m) {
  int n = nd->n;
  layer_op *ops[4] = {&s->r, &s->t, &s->rs, &s->ts};
  for (int i = 0; i < 4; ++i) {
    layer_op_zero(ops[i], n);
  }
  if (m != 0) {
    return;
  }
  double value = 2.0 * albedo / (nd->eta * nd->eta);
  for (int k = 0; k < n; ++k) {
    if (!nd->present[LAYER_MED][k]) {
      continue;
    }
    for (int j = 0; j < n; ++j) {
      if (nd->present[LAYER_MED][j]) {
        s->r.s[(size_t)k * (size_t)n + (size_t)j] = value;
      }
    }
  }
}
