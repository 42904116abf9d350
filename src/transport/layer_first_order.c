/* First-order light of a layered surface in closed form (layer.h):
 * Blinn1982's single scattering in each layer, evaluated inside at the refracted
 * directions behind the dielectric top face as HanrahanKrueger1993 do
 * (their f_r = R f_r,s + (1 - R) f_r,v), with the beam and the view bounced
 * specularly between the two faces of a slab, plus the single reflection at
 * a Lambertian base.
 *
 * In optical depth t from the top (total tau), a beam of unit normal
 * irradiance just inside scatters albedo p per unit t and steradian; the
 * radiance it sends to the top along mu' is the integral over t of that
 * source times the attenuation of both legs, / mu'. Outside, radiance / n^2
 * is conserved across a face and the incident solid angle refracts, so
 * f = T12(theta_i) T21(theta_o) / (eta^2 mu_i' mu_o') x (that integral),
 * the n^2 factors of entry and exit cancelling. */
#include "subsurf/layer.h"

#include "subsurf/fresnel.h"
#include "subsurf/quadrature.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <string.h>

/* int_t0^t1 exp(-alpha t - beta (tau - t)) dt without overflow or
 * cancellation. */
static double segment(double alpha, double beta, double tau, double t0, double t1) {
  double gamma = alpha - beta, len = t1 - t0;
  double e0 = alpha * t0 + beta * (tau - t0), e1 = alpha * t1 + beta * (tau - t1);
  if (fabs(gamma) * len < 1e-12) {
    return len * exp(-e0);
  }
  return gamma > 0.0 ? exp(-e0) * -expm1(-gamma * len) / gamma
                     : exp(-e1) * -expm1(gamma * len) / -gamma;
}

typedef struct {
  const ss_layer_params *p;
  double tau;        /* of the whole stack */
  double mu_i;       /* the beam inside */
  double a, g_i;     /* 1 / mu_i, the beam's bounce series */
  double r_top_i;    /* internal reflectance of the top face at mu_i */
  double r_bottom_i; /* specular reflectance of the bottom at mu_i */
} beam;

static double inside_cosine(double mu, double eta) {
  double s2 = (1.0 - mu * mu) / (eta * eta);
  return s2 < 1.0 ? sqrt(1.0 - s2) : -1.0;
}

static double top_reflectance(const ss_layer_params *p, double mu) {
  return ss_fresnel_dielectric(-mu, p->eta);
}

static double bottom_reflectance(const ss_layer_params *p, double mu) {
  return p->bottom == SS_LAYER_BOTTOM_SAME ? ss_fresnel_dielectric(-mu, p->eta) : 0.0;
}

/* 1 / (1 - R_top R_bottom exp(-2 tau / mu)): the images of a direction
 * bounced between the faces. */
static double bounces(const ss_layer_params *p, double tau, double mu) {
  return 1.0 / (1.0 - top_reflectance(p, mu) * bottom_reflectance(p, mu) * exp(-2.0 * tau / mu));
}

/* The phase function between the beam (propagating down, or up when
 * `beam_up`) and a view direction of cosine mu propagating up or down, at
 * azimuth dphi between the propagation directions. */
static double phase_between(const ss_phase *ph, double mu_i, int beam_up, double mu, int view_up,
                            double cos_dphi) {
  double c = (beam_up == view_up ? 1.0 : -1.0) * mu_i * mu +
             sqrt(fmax(0.0, 1.0 - mu_i * mu_i)) * sqrt(fmax(0.0, 1.0 - mu * mu)) * cos_dphi;
  return ss_phase_eval(ph, c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c));
}

/* The inside radiance x mu' leaving the top (reflect) or the bottom along
 * mu, per unit normal irradiance of the beam, summed over the four pairings
 * of the beam's and the view's legs (down or after a bounce at the far face)
 * and over the layers. */
static double single_scattering(const beam *b, double mu, int reflect, double cos_dphi) {
  const ss_layer_params *p = b->p;
  double tau = b->tau, a = b->a, c = 1.0 / mu;
  double rb_i = b->r_bottom_i, r_far = reflect ? bottom_reflectance(p, mu) : top_reflectance(p, mu);
  double sum = 0.0, t0 = 0.0;
  for (int l = 0; l < p->n_layers; ++l) {
    const ss_layer_medium *m = &p->layers[l];
    double t1 = t0 + m->tau, v = 0.0;
    const ss_phase *ph = &m->phase;
    if (reflect) {
      /* Blinn1982: beam down, view up: exp(-t (a + c)). */
      v += phase_between(ph, b->mu_i, 0, mu, 1, cos_dphi) * segment(a + c, 0.0, tau, t0, t1);
      v += phase_between(ph, b->mu_i, 0, mu, 0, cos_dphi) * r_far * exp(-tau * c) *
           segment(a, c, tau, t0, t1);
      v += phase_between(ph, b->mu_i, 1, mu, 1, cos_dphi) * rb_i * exp(-tau * a) *
           segment(c, a, tau, t0, t1);
      v += phase_between(ph, b->mu_i, 1, mu, 0, cos_dphi) * rb_i * r_far * exp(-tau * (a + c)) *
           segment(0.0, a + c, tau, t0, t1);
    } else {
      /* Blinn1982: beam down, view down: exp(-t a - (tau - t) c). */
      v += phase_between(ph, b->mu_i, 0, mu, 0, cos_dphi) * segment(a, c, tau, t0, t1);
      v += phase_between(ph, b->mu_i, 0, mu, 1, cos_dphi) * r_far * exp(-tau * c) *
           segment(a + c, 0.0, tau, t0, t1);
      v += phase_between(ph, b->mu_i, 1, mu, 0, cos_dphi) * rb_i * exp(-tau * a) *
           segment(0.0, a + c, tau, t0, t1);
      v += phase_between(ph, b->mu_i, 1, mu, 1, cos_dphi) * rb_i * r_far * exp(-tau * (a + c)) *
           segment(c, a, tau, t0, t1);
    }
    sum += m->albedo * v;
    t0 = t1;
  }
  return sum * b->g_i * bounces(p, tau, mu) * c;
}

/* f for an outgoing direction of cosine mu_out in its own space (outside,
 * or the medium below an open bottom), 0 if no light reaches it. */
static double first_order_f(const beam *b, double mu_out, int reflect, double cos_dphi) {
  const ss_layer_params *p = b->p;
  int outside = reflect || p->bottom == SS_LAYER_BOTTOM_SAME;
  if (!reflect && p->bottom == SS_LAYER_BOTTOM_DIFFUSE) {
    return 0.0;
  }
  double mu = outside ? inside_cosine(mu_out, p->eta) : mu_out;
  if (mu <= 0.0) {
    return 0.0;
  }
  double t_in = 1.0 - ss_fresnel_dielectric(cos(p->theta_i), p->eta);
  double t_out = outside ? 1.0 - ss_fresnel_dielectric(mu_out, p->eta) : 1.0;
  double n2 = outside ? p->eta * p->eta : 1.0; /* (n_medium / n_where it leaves)^2 */
  double f = t_in * t_out / (n2 * b->mu_i) * single_scattering(b, mu, reflect, cos_dphi);
  if (reflect && p->bottom == SS_LAYER_BOTTOM_DIFFUSE) {
    /* The Lambertian base lit by the attenuated beam, seen through the stack. */
    f += t_in * t_out / n2 * (p->bottom_albedo * SS_INV_PI) * exp(-b->tau * (b->a + 1.0 / mu));
  }
  return f;
}

/* int f mu dw over the hemisphere of leaving light, by Gauss-Legendre in mu
 * (split at the critical angle, where f starts to vanish) and the trapezoid
 * rule in the azimuth. */
static double hemisphere_total(const beam *b, int reflect) {
  enum { NMU = 48, NPHI = 64 };
  double x[NMU], w[NMU];
  ss_gauss_legendre(NMU, x, w);
  const ss_layer_params *p = b->p;
  int outside = reflect || p->bottom == SS_LAYER_BOTTOM_SAME;
  double mu_c = outside && p->eta < 1.0 ? sqrt(1.0 - p->eta * p->eta) : 0.0;
  double total = 0.0;
  for (int i = 0; i < NMU; ++i) {
    double mu = mu_c + 0.5 * (1.0 - mu_c) * (x[i] + 1.0), wi = 0.5 * (1.0 - mu_c) * w[i];
    double s = 0.0;
    for (int k = 0; k < NPHI; ++k) {
      s += first_order_f(b, mu, reflect, cos(SS_PI * (k + 0.5) / NPHI));
    }
    total += wi * mu * (2.0 * SS_PI * s / NPHI);
  }
  return total;
}

ss_status ss_layer_first_order(const ss_layer_params *p, ss_layer_result *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  ss_status st = ss_layer_validate(p, err);
  if (st != SS_OK) {
    return st;
  }
  double mu0 = cos(p->theta_i);
  out->specular = ss_fresnel_dielectric(mu0, p->eta);
  beam b = {p, 0.0, inside_cosine(mu0, p->eta), 0.0, 0.0, 0.0, 0.0};
  for (int l = 0; l < p->n_layers; ++l) {
    b.tau += p->layers[l].tau;
  }
  if (b.mu_i <= 0.0) {
    out->absorbed = 1.0 - out->specular;
    return SS_OK; /* the beam does not enter */
  }
  b.a = 1.0 / b.mu_i;
  b.r_top_i = top_reflectance(p, b.mu_i);
  b.r_bottom_i = bottom_reflectance(p, b.mu_i);
  b.g_i = bounces(p, b.tau, b.mu_i);
  for (int k = 0; k < p->n_theta_o; ++k) {
    double cos_dphi = p->theta_o[k] < 0.0 ? -1.0 : 1.0, mu = cos(p->theta_o[k]);
    out->brdf[k] = first_order_f(&b, mu, 1, cos_dphi);
    out->btdf[k] = first_order_f(&b, mu, 0, cos_dphi);
  }
  double t_in = 1.0 - out->specular;
  double beam_down = t_in * exp(-b.tau * b.a) * b.g_i;
  int diffuse = p->bottom == SS_LAYER_BOTTOM_DIFFUSE;
  /* The unscattered beam: out through the bottom, or back up through the top. */
  out->transmittance_unscattered =
      diffuse ? 0.0 : beam_down * (p->bottom == SS_LAYER_BOTTOM_SAME ? 1.0 - b.r_bottom_i : 1.0);
  out->reflectance_unscattered = beam_down * b.r_bottom_i * exp(-b.tau * b.a) * (1.0 - b.r_top_i);
  out->reflectance = hemisphere_total(&b, 1);
  out->transmittance = hemisphere_total(&b, 0);
  out->absorbed = 1.0 - (out->specular + out->reflectance + out->reflectance_unscattered +
                         out->transmittance + out->transmittance_unscattered);
  return SS_OK;
}
