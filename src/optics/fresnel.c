#include "subsurf/fresnel.h"

#include "subsurf/quadrature.h"

#include <math.h>

/* Fresnel equations for unpolarised light (Born & Wolf, sec. 1.5.3). */
double ss_fresnel_dielectric(double cos_theta_i, double eta) {
  if (cos_theta_i < 0.0) {
    eta = 1.0 / eta;
    cos_theta_i = -cos_theta_i;
  }
  if (cos_theta_i > 1.0) {
    cos_theta_i = 1.0;
  }
  double sin2_t = (1.0 - cos_theta_i * cos_theta_i) / (eta * eta);
  if (sin2_t >= 1.0) {
    return 1.0;
  }
  double cos_t = sqrt(1.0 - sin2_t);
  double r_parl = (eta * cos_theta_i - cos_t) / (eta * cos_theta_i + cos_t);
  double r_perp = (cos_theta_i - eta * cos_t) / (cos_theta_i + eta * cos_t);
  return 0.5 * (r_parl * r_parl + r_perp * r_perp);
}

/* Snell's law in vector form. */
int ss_refract(ss_vec3 w_i, ss_vec3 n, double eta, ss_vec3 *w_t) {
  double cos_i = ss_vec3_dot(w_i, n);
  if (cos_i < 0.0) {
    eta = 1.0 / eta;
    cos_i = -cos_i;
    n = ss_vec3_neg(n);
  }
  double sin2_t = fmax(0.0, 1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) {
    return 0;
  }
  double cos_t = sqrt(1.0 - sin2_t);
  *w_t = ss_vec3_add(ss_vec3_scale(w_i, -1.0 / eta), ss_vec3_scale(n, cos_i / eta - cos_t));
  return 1;
}

/* Egan & Hilgeman 1979 fit, as given in Jensen et al. 2001 (sec. 2.3) and
 * Donner & Jensen 2005. */
double ss_fresnel_diffuse_reflectance(double eta) {
  if (eta < 1.0) {
    return -0.4399 + 0.7099 / eta - 0.3319 / (eta * eta) + 0.0636 / (eta * eta * eta);
  }
  return -1.4399 / (eta * eta) + 0.7099 / eta + 0.6681 + 0.0636 * eta;
}

/* Jensen et al. 2001, sec. 2.3 (rounded coefficients). */
double ss_fresnel_diffuse_reflectance_jensen(double eta) {
  if (eta < 1.0) {
    return ss_fresnel_diffuse_reflectance(eta);
  }
  return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

/* Jensen et al. 2001, eq. 7 context: A = (1 + Fdr) / (1 - Fdr). */
double ss_fresnel_A(double eta) {
  double fdr = ss_fresnel_diffuse_reflectance(eta);
  return (1.0 + fdr) / (1.0 - fdr);
}

typedef struct {
  int n;
  double eta, mu_c;
} moment_params;

/* Fr(-mu) mu^n with mu = mu_c + (1 - mu_c) s^2 and its Jacobian: the
 * square-root behaviour of Fr at the critical cosine becomes smooth in s. */
static double moment_integrand(void *p, double s) {
  const moment_params *m = p;
  double width = 1.0 - m->mu_c, mu = m->mu_c + width * s * s;
  return ss_fresnel_dielectric(-mu, m->eta) * pow(mu, m->n) * 2.0 * width * s;
}

double ss_fresnel_moment(int n, double eta) {
  /* Below the critical cosine (grazing light from inside) Fr = 1 exactly:
   * that part integrates in closed form, the smooth rest by 8 fixed
   * Gauss-Legendre panels (no adaptive integrator, no global error state). */
  double mu_c = eta > 1.0 ? sqrt(1.0 - 1.0 / (eta * eta)) : 0.0;
  moment_params params = {n, eta, mu_c};
  return pow(mu_c, n + 1) / (n + 1) + ss_gl_integrate(moment_integrand, &params, 0.0, 1.0, 8);
}

/* d'Eon & Irving 2011, "A quantized-diffusion model for rendering
 * translucent materials", eq. 17 (fit of 2 C1). */
double ss_fresnel_moment1_fit(double eta) {
  double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
  double two_c1;
  if (eta < 1.0) {
    two_c1 = 0.919317 - 3.4793 * eta + 6.75335 * e2 - 7.80989 * e3 + 4.98554 * e4 - 1.36881 * e5;
  } else {
    two_c1 = -9.23372 + 22.2272 * eta - 20.9292 * e2 + 10.2291 * e3 - 2.54396 * e4 + 0.254913 * e5;
  }
  return 0.5 * two_c1;
}

/* d'Eon & Irving 2011, eq. 18 (fit of 3 C2). */
double ss_fresnel_moment2_fit(double eta) {
  double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
  double three_c2;
  if (eta < 1.0) {
    three_c2 =
        0.828421 - 2.62051 * eta + 3.36231 * e2 - 1.95284 * e3 + 0.236494 * e4 + 0.145787 * e5;
  } else {
    three_c2 = -1641.1 + 135.926 / e3 - 656.175 / e2 + 1376.53 / eta + 1213.67 * eta -
               568.556 * e2 + 164.798 * e3 - 27.0181 * e4 + 1.91826 * e5;
  }
  return three_c2 / 3.0;
}

/* d'Eon & Irving 2011, eq. 16. */
double ss_fresnel_c_phi(double eta) { return 0.25 * (1.0 - 2.0 * ss_fresnel_moment(1, eta)); }
double ss_fresnel_c_e(double eta) { return 0.5 * (1.0 - 3.0 * ss_fresnel_moment(2, eta)); }
