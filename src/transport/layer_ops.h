/* The discrete operators of adding-doubling (layer.h), internal to transport.
 *
 * Nodes: one list shared by the two index spaces, the outside (space 0,
 * index 1) and the layers' medium (space 1, index eta). Node k has a cosine
 * mu[s][k] in each space where it exists (present[s][k]); a node present in
 * both spaces is one direction and its refraction (Snell), so that a smooth
 * face maps node k to node k. Its weight w[s][k] is the quadrature weight of
 * the etendue n^2 mu dmu, which is the same on both sides of a smooth face,
 * so that one weight serves every operator whatever space its light comes
 * from. The requested directions are extra nodes of weight 0: they take no
 * part in any integral but every operator is exact at them.
 *
 * An operator maps the Fourier mode m of downward (or upward) radiance at
 * the nodes to outgoing radiance: L_o(k) = d[k] L(k) + sum_j s[k][j] w[j] L(j).
 * d is the part that keeps the direction (unscattered beams, specular faces),
 * s the smooth kernel c_m f^m(mu_k, mu_j) / n_j^2 with c_0 = 2 pi, c_m = pi,
 * n_j the index where the light comes from, and f = sum_m f^m cos(m dphi)
 * in the azimuth dphi between the propagation directions. */
#ifndef SUBSURF_TRANSPORT_LAYER_OPS_H
#define SUBSURF_TRANSPORT_LAYER_OPS_H

#include "subsurf/layer.h"

enum { LAYER_OUT = 0, LAYER_MED = 1 };

typedef struct {
  int n;
  double *mu[2], *w[2];
  unsigned char *present[2];
  double eta;
  int incident;                             /* the node of theta_i (outside) */
  int reflected[SS_LAYER_MAX_DIRECTIONS];   /* theta_o in the outside */
  int transmitted[SS_LAYER_MAX_DIRECTIONS]; /* theta_o below the stack */
} layer_nodes;

typedef struct {
  double *d; /* n */
  double *s; /* n x n, row-major */
} layer_op;

/* A slab seen from above (r, t) and from below (rs, ts). */
typedef struct {
  layer_op r, t, rs, ts;
} layer_slab;

/* Scratch for the operator algebra of one mode: n x n matrices. */
typedef struct {
  int n;
  double *lu;
  layer_op y, x, q, t;
} layer_work;

/* Builds the node list for `base` Gauss-Legendre nodes per hemisphere. */
int layer_nodes_init(layer_nodes *nodes, const ss_layer_params *p, int base);
void layer_nodes_free(layer_nodes *nodes);

int layer_op_alloc(layer_op *op, int n);
void layer_op_free(layer_op *op);
void layer_op_zero(layer_op *op, int n);
void layer_op_copy(layer_op *dst, const layer_op *src, int n);
int layer_slab_alloc(layer_slab *s, int n);
void layer_slab_free(layer_slab *s);
int layer_work_alloc(layer_work *w, int n);
void layer_work_free(layer_work *w);

/* out = a o b (b acts first) with the inner integral weighted by w. */
void layer_op_compose(layer_op *out, const layer_op *a, const layer_op *b, const double *w,
                      layer_work *ws);
/* out = (I - q)^-1 (the series I + q + q^2 + ...); returns 0 if singular. */
int layer_op_inverse_series(layer_op *out, const layer_op *q, const double *w, layer_work *ws);

/* Adding equations (PharrHanrahan2000 sec. 3.4): `out` = a over b,
 * whose common face lies in the space with weights w. `symmetric`: a and b
 * are each their own mirror image (r = rs, t = ts), so is out. out may not
 * alias a or b. Returns 0 if an inverse is singular. */
int layer_add(layer_slab *out, const layer_slab *a, const layer_slab *b, const double *w,
              int symmetric, layer_work *ws);

/* A smooth dielectric face between the outside and the medium: `top` (the
 * outside above) or the bottom face (the medium above). */
void layer_face(layer_slab *s, const layer_nodes *nodes, int top);
/* A Lambertian base of albedo a under the medium, for mode m. */
void layer_lambert(layer_slab *s, const layer_nodes *nodes, double albedo, int m);

/* The azimuthal Fourier coefficients of a phase function between node
 * directions: coeff[((sign * n + k) * n + j) * modes + m] =
 * int_0^2pi p(cos Theta) cos(m dphi) dphi with cos Theta = +-mu_k mu_j +
 * sin_k sin_j cos dphi (sign 0: same hemisphere, +; 1: opposite, -), in
 * the medium's space. */
double *layer_phase_modes(const ss_phase *phase, const layer_nodes *nodes, int modes);
/* The modes whose grazing coefficient exceeds accuracy x the zeroth. */
int layer_phase_mode_count(const ss_phase *phase, double accuracy);

/* Blinn1982's single-scattering depth factors of a layer of optical depth
 * tau from incidence cosine mu0 into mu, without albedo and phase:
 * reflection [1 - exp(-tau (1/mu + 1/mu0))] / (mu + mu0) and transmission
 * [exp(-tau/mu) - exp(-tau/mu0)] / (mu - mu0). */
double layer_blinn_reflect(double tau, double mu, double mu0);
double layer_blinn_transmit(double tau, double mu, double mu0);

/* A homogeneous layer for mode m by doubling from a thin layer of single
 * scattering: `coeff` from layer_phase_modes. Returns the doublings done,
 * -1 when out of memory, -2 if an inverse is singular or -3 when *cancel
 * (may be NULL) became non-zero. */
int layer_slab_build(layer_slab *s, const layer_nodes *nodes, const ss_layer_medium *medium,
                     const double *coeff, int modes, int m, double thin_tau, layer_work *ws,
                     const volatile sig_atomic_t *cancel);

#endif
