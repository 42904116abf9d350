#include "subsurf/microfacet.h"

#include "subsurf/sampling.h"

#include <gsl/gsl_cdf.h>
#include <math.h>
#include <strings.h>

ss_status ss_microfacet_init_anisotropic(ss_microfacet *m, ss_microfacet_type type, double alpha_u,
                                         double alpha_v, ss_error *err) {
  if (type != SS_MICROFACET_BECKMANN && type != SS_MICROFACET_GGX) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "microfacet: unknown distribution %d",
                        (int)type);
  }
  const double a[2] = {alpha_u, alpha_v};
  for (int k = 0; k < 2; ++k) {
    if (!(a[k] >= 1e-4 && a[k] <= 4.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "microfacet: alpha = %g out of range (expected 1e-4 to 4)", a[k]);
    }
  }
  m->type = type;
  m->alpha = alpha_u;
  m->alpha_v = alpha_v;
  return SS_OK;
}

ss_status ss_microfacet_init(ss_microfacet *m, ss_microfacet_type type, double alpha,
                             ss_error *err) {
  return ss_microfacet_init_anisotropic(m, type, alpha, alpha, err);
}

int ss_microfacet_type_from_name(const char *name, ss_microfacet_type *type) {
  if (strcasecmp(name, "beckmann") == 0) {
    *type = SS_MICROFACET_BECKMANN;
    return 1;
  }
  if (strcasecmp(name, "ggx") == 0) {
    *type = SS_MICROFACET_GGX;
    return 1;
  }
  return 0;
}

const char *ss_microfacet_type_name(ss_microfacet_type type) {
  return type == SS_MICROFACET_GGX ? "ggx" : "beckmann";
}

double ss_microfacet_d(const ss_microfacet *m, ss_vec3 wm) {
  double c2 = wm.z * wm.z;
  if (wm.z <= 0.0) {
    return 0.0;
  }
  double au = m->alpha, av = ss_microfacet_alpha_v(m);
  /* tan^2(theta) (cos^2(phi) / alpha_u^2 + sin^2(phi) / alpha_v^2): the
   * slope's squared length in the unit-roughness configuration. */
  double t2 = (wm.x * wm.x / (au * au) + wm.y * wm.y / (av * av)) / c2;
  if (m->type == SS_MICROFACET_BECKMANN) {
    /* Walter et al. 2007, eq. 25, stretched to alpha_u, alpha_v (Heitz2014). */
    return exp(-t2) / (SS_PI * au * av * c2 * c2);
  }
  /* Walter et al. 2007, eq. 33, stretched likewise. */
  double s = 1.0 + t2;
  return 1.0 / (SS_PI * au * av * c2 * c2 * s * s);
}

double ss_microfacet_lambda(const ss_microfacet *m, ss_vec3 w) {
  double sin2 = w.x * w.x + w.y * w.y, c = fabs(w.z);
  if (sin2 <= 0.0) {
    return 0.0;
  }
  if (c <= 0.0) {
    return INFINITY;
  }
  /* alpha tan(theta) with the roughness of w's azimuth, alpha^2 =
   * cos^2(phi) alpha_u^2 + sin^2(phi) alpha_v^2 (Heitz2014, by stretching). */
  double av = ss_microfacet_alpha_v(m);
  double at = sqrt(m->alpha * m->alpha * w.x * w.x + av * av * w.y * w.y) / c;
  if (m->type == SS_MICROFACET_BECKMANN) {
    /* Heitz 2014, eq. 72, with a = 1 / (alpha tan theta). */
    double a = 1.0 / at;
    return 0.5 * (erf(a) - 1.0) + exp(-a * a) / (2.0 * a * sqrt(SS_PI));
  }
  /* Heitz 2014, eq. 86. */
  return 0.5 * (-1.0 + sqrt(1.0 + at * at));
}

double ss_microfacet_g1(const ss_microfacet *m, ss_vec3 w, ss_vec3 wm) {
  if (ss_vec3_dot(w, wm) * w.z <= 0.0) {
    return 0.0;
  }
  return 1.0 / (1.0 + ss_microfacet_lambda(m, w));
}

/* Height-correlated Smith masking-shadowing (Heitz 2014, eq. 99). */
double ss_microfacet_g(const ss_microfacet *m, ss_vec3 wo, ss_vec3 wi, ss_vec3 wm) {
  if (ss_vec3_dot(wo, wm) * wo.z <= 0.0 || ss_vec3_dot(wi, wm) * wi.z <= 0.0) {
    return 0.0;
  }
  return 1.0 / (1.0 + ss_microfacet_lambda(m, wo) + ss_microfacet_lambda(m, wi));
}

/* Heitz 2018, "Sampling the GGX Distribution of Visible Normals", listing 1:
 * a uniform point on the projected hemisphere of the stretched configuration,
 * warped towards the visible half-disk. */
static ss_vec3 ggx_sample_visible(double au, double av, ss_vec3 w, double u1, double u2) {
  ss_vec3 vh = ss_vec3_normalize(ss_vec3_make(au * w.x, av * w.y, w.z));
  double lensq = vh.x * vh.x + vh.y * vh.y;
  ss_vec3 t1 = lensq > 0.0 ? ss_vec3_scale(ss_vec3_make(-vh.y, vh.x, 0.0), 1.0 / sqrt(lensq))
                           : ss_vec3_make(1.0, 0.0, 0.0);
  ss_vec3 t2 = ss_vec3_cross(vh, t1);
  double r = sqrt(u1), phi = 2.0 * SS_PI * u2;
  double p1 = r * cos(phi), p2 = r * sin(phi);
  double s = 0.5 * (1.0 + vh.z);
  p2 = (1.0 - s) * sqrt(fmax(0.0, 1.0 - p1 * p1)) + s * p2;
  ss_vec3 nh = ss_vec3_add(ss_vec3_add(ss_vec3_scale(t1, p1), ss_vec3_scale(t2, p2)),
                           ss_vec3_scale(vh, sqrt(fmax(0.0, 1.0 - p1 * p1 - p2 * p2))));
  return ss_vec3_normalize(ss_vec3_make(au * nh.x, av * nh.y, fmax(1e-12, nh.z)));
}

/* Heitz & d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the
 * Distribution of Visible Normals", sec. 4 for Beckmann at unit roughness:
 * for a direction at angle theta (phi = 0) the visible slope density is
 * proportional to max(0, cot(theta) - x) exp(-x^2 - y^2), so y ~ N(0, 1/2)
 * independently and x has the cdf
 *   F(x) = a sqrt(pi)/2 erfc(-x) + exp(-x^2)/2,  a = cot(theta), x <= a,
 * inverted here by safeguarded Newton iterations. */
static double beckmann_sample_slope_x(double cot_theta, double u) {
  const double sqrt_pi_2 = 0.5 * sqrt(SS_PI);
  double a = cot_theta;
  double total = a * sqrt_pi_2 * erfc(-a) + 0.5 * exp(-a * a);
  double target = u * total;
  double lo = -8.0, hi = a, x = fmin(0.0, a);
  for (int it = 0; it < 100; ++it) {
    double f = a * sqrt_pi_2 * erfc(-x) + 0.5 * exp(-x * x) - target;
    if (f > 0.0) {
      hi = x;
    } else {
      lo = x;
    }
    double df = (a - x) * exp(-x * x);
    double next = df > 0.0 ? x - f / df : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) {
      next = 0.5 * (lo + hi);
    }
    if (fabs(next - x) < 1e-13 * (1.0 + fabs(x))) {
      return next;
    }
    x = next;
  }
  return x;
}

static ss_vec3 beckmann_sample_visible(double au, double av, ss_vec3 w, double u1, double u2) {
  ss_vec3 ws = ss_vec3_normalize(ss_vec3_make(au * w.x, av * w.y, w.z));
  double sin_t = sqrt(ws.x * ws.x + ws.y * ws.y);
  double cos_phi = 1.0, sin_phi = 0.0;
  double x;
  if (sin_t < 1e-9) {
    /* Normal incidence: the slope density is the Gaussian itself. */
    x = sqrt(0.5) * gsl_cdf_ugaussian_Pinv(fmin(fmax(u1, 1e-15), 1.0 - 1e-15));
  } else {
    cos_phi = ws.x / sin_t;
    sin_phi = ws.y / sin_t;
    x = beckmann_sample_slope_x(ws.z / sin_t, u1);
  }
  double y = sqrt(0.5) * gsl_cdf_ugaussian_Pinv(fmin(fmax(u2, 1e-15), 1.0 - 1e-15));
  /* Rotate back to the direction's azimuth, then unstretch the slopes. */
  double sx = au * (cos_phi * x - sin_phi * y);
  double sy = av * (sin_phi * x + cos_phi * y);
  return ss_vec3_normalize(ss_vec3_make(-sx, -sy, 1.0));
}

ss_vec3 ss_microfacet_sample_visible(const ss_microfacet *m, ss_vec3 w, double u1, double u2) {
  if (w.z < 0.0) {
    w = ss_vec3_neg(w);
  }
  double av = ss_microfacet_alpha_v(m);
  if (m->type == SS_MICROFACET_GGX) {
    return ggx_sample_visible(m->alpha, av, w, u1, u2);
  }
  return beckmann_sample_visible(m->alpha, av, w, u1, u2);
}

/* Heitz 2014, eq. 38: D_w(wm) = G1(w, wm) max(0, w.wm) D(wm) / cos(theta). */
double ss_microfacet_pdf_visible(const ss_microfacet *m, ss_vec3 w, ss_vec3 wm) {
  if (w.z < 0.0) {
    w = ss_vec3_neg(w);
  }
  double c = w.z;
  if (c <= 0.0) {
    return 0.0;
  }
  double dot = ss_vec3_dot(w, wm);
  if (dot <= 0.0) {
    return 0.0;
  }
  return ss_microfacet_g1(m, w, wm) * dot * ss_microfacet_d(m, wm) / c;
}
