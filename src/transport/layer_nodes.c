/* The node sets of adding-doubling in the two index spaces (layer_ops.h).
 *
 * The sparser space (lower index) gets `base` Gauss-Legendre nodes on
 * mu in [0, 1]. The denser space gets their images under Snell's law, which
 * cover [mu_c, 1] (mu_c the cosine of the critical angle), with the weights
 * of the same quadrature in the new variable, plus `base` Gauss-Legendre
 * nodes on [0, mu_c] that only light trapped by total internal reflection
 * reaches. So a smooth face maps nodes onto nodes, and both rules have a
 * break exactly at the critical angle, where the radiance inside has a kink
 * (Jakob2014 sec. 5, on the refraction of node sets). */
#include "transport/layer_ops.h"

#include "subsurf/quadrature.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Snell's law in cosines: 1 - mu_out^2 = eta^2 (1 - mu_med^2). Returns -1
 * when the direction has no image (it meets the face beyond the critical
 * angle). */
static double image_cosine(double mu, double eta, int from) {
  double sin2 = from == LAYER_OUT ? (1.0 - mu * mu) / (eta * eta) : (1.0 - mu * mu) * eta * eta;
  return sin2 <= 1.0 ? sqrt(1.0 - sin2) : -1.0;
}

/* w: the weight of the quadrature in mu, stored as the etendue weight
 * n^2 mu w, which a direction and its image share. */
static void set_node(layer_nodes *nd, int k, int space, double mu, double w) {
  nd->mu[space][k] = mu;
  nd->w[space][k] = (space == LAYER_MED ? nd->eta * nd->eta : 1.0) * mu * w;
  nd->present[space][k] = 1;
}

/* Adds node k at cosine mu of `space` (weight w) and its image, if any.
 * Solid angles: mu_out dmu_out = eta^2 mu_med dmu_med. */
static void add_node(layer_nodes *nd, int k, int space, double mu, double w) {
  set_node(nd, k, space, mu, w);
  double eta = nd->eta;
  double im = image_cosine(mu, eta, space);
  if (im > 0.0) {
    double jac = space == LAYER_OUT ? mu / (eta * eta * im) : eta * eta * mu / im;
    set_node(nd, k, 1 - space, im, w * jac);
  }
}

/* Gauss-Legendre nodes on [a, b] of `space` from node k on. */
static int add_rule(layer_nodes *nd, int k, int space, int n, double a, double b, double *x,
                    double *w) {
  ss_gauss_legendre(n, x, w);
  for (int i = 0; i < n; ++i) {
    add_node(nd, k++, space, a + 0.5 * (b - a) * (x[i] + 1.0), 0.5 * (b - a) * w[i]);
  }
  return k;
}

int layer_nodes_init(layer_nodes *nd, const ss_layer_params *p, int base) {
  memset(nd, 0, sizeof *nd);
  nd->eta = p->eta;
  int dense_extra = p->eta != 1.0 ? base : 0;
  int n = base + dense_extra + 1 + 2 * p->n_theta_o;
  for (int s = 0; s < 2; ++s) {
    nd->mu[s] = calloc((size_t)n, sizeof *nd->mu[s]);
    nd->w[s] = calloc((size_t)n, sizeof *nd->w[s]);
    nd->present[s] = calloc((size_t)n, 1);
  }
  double *x = malloc((size_t)base * sizeof *x), *w = malloc((size_t)base * sizeof *w);
  if (!nd->mu[0] || !nd->mu[1] || !nd->w[0] || !nd->w[1] || !nd->present[0] || !nd->present[1] ||
      !x || !w) {
    free(x);
    free(w);
    layer_nodes_free(nd);
    return 0;
  }
  int sparse = p->eta >= 1.0 ? LAYER_OUT : LAYER_MED;
  int k = add_rule(nd, 0, sparse, base, 0.0, 1.0, x, w);
  if (dense_extra) {
    double ratio = p->eta >= 1.0 ? 1.0 / p->eta : p->eta;
    double mu_c = sqrt(1.0 - ratio * ratio);
    k = add_rule(nd, k, 1 - sparse, dense_extra, 0.0, mu_c, x, w);
  }
  free(x);
  free(w);
  nd->incident = k;
  add_node(nd, k++, LAYER_OUT, cos(p->theta_i), 0.0);
  int exit = p->bottom == SS_LAYER_BOTTOM_MATCHED ? LAYER_MED : LAYER_OUT;
  for (int i = 0; i < p->n_theta_o; ++i) {
    nd->reflected[i] = k;
    add_node(nd, k++, LAYER_OUT, cos(p->theta_o[i]), 0.0);
    nd->transmitted[i] = k;
    add_node(nd, k++, exit, cos(p->theta_o[i]), 0.0);
  }
  nd->n = k;
  return 1;
}

void layer_nodes_free(layer_nodes *nd) {
  for (int s = 0; s < 2; ++s) {
    free(nd->mu[s]);
    free(nd->w[s]);
    free(nd->present[s]);
    nd->mu[s] = nd->w[s] = NULL;
    nd->present[s] = NULL;
  }
}
