/* The rough dielectric boundary of the forward scattering dipole models
 * (fwddip_model.h): a fixed rule over microfacet normals that turns the
 * rough dielectric BTDF of src/optics (Walter et al. 2007) into a weighted
 * set of transmitted directions at the entry and at the exit.
 *
 * The power that light arriving along -w carries into the directions
 * t(m) = refract(w, m) of the other side, over the normals m visible from
 * w (Heitz 2014, eq. 38: D_w(m) = G1(w, m) |w.m| D(m) / |w.n|), is
 *     int f(t, w) |t.n| g(t) dt = int D_w(m) (1 - Fr(w.m)) G2(w, t, m) / G1(w, m) g(t(m)) dm
 * (Walter et al. 2007, eq. 21 with the Jacobian of eq. 17: the weight of the
 * visible-normal sampler of bsdf_dielectric.c's transmission lobe). The
 * rule maps a fixed grid of its two uniform variables through that sampler
 * (ss_microfacet_sample_visible): Gauss-Legendre in u1 (N nodes), the
 * midpoint rule in u2 (2N), so the weights are bounded functions of a smooth
 * map and no heavy tail of GGX is cut off. As alpha -> 0 every node tends
 * to the macro normal and the rule to the smooth boundary's single refracted
 * direction with weight 1 - Fr. */
#include "bssrdf/fwddip_model.h"

#include "subsurf/fresnel.h"
#include "subsurf/quadrature.h"

#include <math.h>

ss_status ss_fwddip_rough_init(ss_fwddip_rough *r, const ss_fwddip_config *cfg, double eta,
                               const char *model, ss_error *err) {
  r->on = cfg->alpha >= 1e-3 && eta != 1.0; /* ss_bsdf_rough_dielectric_init's rule */
  r->n = 0;
  if (!r->on) {
    return SS_OK;
  }
  ss_microfacet_type type = cfg->distribution ? SS_MICROFACET_GGX : SS_MICROFACET_BECKMANN;
  if (ss_microfacet_init(&r->mf, type, cfg->alpha, err) != SS_OK) {
    ss_error_prefix(err, "%s: alpha: ", model);
    return SS_ERR_INVALID_ARGUMENT;
  }
  int n1 = cfg->rough_nodes, n2 = 2 * cfg->rough_nodes;
  double x[SS_FWDDIP_ROUGH_MAX_NODES], w[SS_FWDDIP_ROUGH_MAX_NODES];
  ss_gauss_legendre(n1, x, w);
  for (int a = 0; a < n1; ++a) {
    for (int b = 0; b < n2; ++b) {
      r->u1[r->n] = 0.5 * (1.0 - x[a]); /* on [0, 1] */
      r->u2[r->n] = (b + 0.5) / n2;
      r->w[r->n] = 0.5 * w[a] / n2;
      ++r->n;
    }
  }
  return SS_OK;
}

/* The rule from the local direction w (either side, pointing away from the
 * surface): transmitted directions t (pointing away, on the other side) and
 * weights (1 - Fr(w.m)) G2 / G1 x the rule's weight. */
static int transmit(const ss_fwddip_rough *r, double eta, ss_vec3 w, ss_vec3 *t, double *weight) {
  int n = 0;
  for (int k = 0; k < r->n; ++k) {
    ss_vec3 m = ss_microfacet_sample_visible(&r->mf, w, r->u1[k], r->u2[k]);
    double d = ss_vec3_dot(w, m), g1 = ss_microfacet_g1(&r->mf, w, m);
    if (!(g1 > 0.0) || !ss_refract(w, m, eta, &t[n]) || !(t[n].z * w.z < 0.0)) {
      continue;
    }
    double g2 = ss_microfacet_g(&r->mf, w, t[n], m);
    weight[n] = r->w[k] * (1.0 - ss_fresnel_dielectric(d, eta)) * g2 / g1;
    n += weight[n] > 0.0;
  }
  return n;
}

void ss_fwddip_rough_enter(const ss_fwddip_rough *r, double eta, ss_vec3 w, ss_vec3 n, double scale,
                           ss_fwddip_nodes *out) {
  ss_frame f = ss_frame_from_normal(n);
  ss_vec3 t[SS_FWDDIP_ROUGH_MAX];
  out->n = transmit(r, eta, ss_frame_to_local(f, w), t, out->w);
  for (int k = 0; k < out->n; ++k) {
    out->d[k] = ss_frame_to_world(f, t[k]);
    out->w[k] *= scale;
  }
}

void ss_fwddip_rough_leave(const ss_fwddip_rough *r, double eta, ss_vec3 w_o, ss_vec3 n,
                           ss_fwddip_nodes *out) {
  /* f(w_o, t) = f(t, w_o) / eta^2 (generalised reciprocity, bsdf.h); the
   * light travels along -t toward the surface. */
  ss_fwddip_rough_enter(r, eta, w_o, n, 1.0 / (eta * eta), out);
  for (int k = 0; k < out->n; ++k) {
    out->d[k] = ss_vec3_neg(out->d[k]);
  }
}

double ss_fwddip_rough_leaving_share(const ss_fwddip_rough *r, double eta, double cos_t) {
  ss_vec3 t[SS_FWDDIP_ROUGH_MAX];
  double weight[SS_FWDDIP_ROUGH_MAX], sum = 0.0;
  int n =
      transmit(r, eta, ss_vec3_make(sqrt(fmax(0.0, 1.0 - cos_t * cos_t)), 0.0, -cos_t), t, weight);
  for (int k = 0; k < n; ++k) {
    sum += weight[k];
  }
  return sum;
}
