/* The forward scattering propagator (Frederickx & Dutré 2017, eq. 9-18):
 * finite positive coefficients over 1e-6 <= ps <= 1e4, the closed forms,
 * normalisation by quadrature, reciprocity, the ps << 1 and ps >> 1 limits
 * (eq. 10, 11) and the planar source (eq. 17). */
#include "bssrdf/fwddip_propagator.h"

#include "subsurf/quadrature.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>

#define MAX_GL 64

static const double PS_MIN = 1e-6, PS_MAX = 1e4;

Test(fwddip_propagator, coefficients_are_finite_and_positive_from_1e_6_to_1e4) {
  for (int i = 0; i <= 400; ++i) {
    double ps = PS_MIN * pow(PS_MAX / PS_MIN, i / 400.0);
    ss_fwddip_coeffs k;
    ss_fwddip_coeffs_make(ps, &k);
    const double v[] = {k.A, k.B, k.D, k.E, k.F};
    for (int j = 0; j < 5; ++j) {
      cr_assert(isfinite(v[j]) && v[j] > 0.0, "ps %g coefficient %d = %g", ps, j, v[j]);
    }
    cr_assert(isfinite(k.Z) && k.Z >= 0.0, "ps %g Z %g", ps, k.Z);
    cr_assert(isfinite(k.log_norm) && isfinite(k.log_planar), "ps %g", ps);
  }
}

/* Eq. 9's coefficients straight from their definitions in long double, where
 * the extra precision covers the cancellation in ps - tanh(ps). */
static void coeffs_direct(long double x, long double *c) {
  long double th = tanhl(x), A = 1.0L / (x - th), B = th / 2.0L;
  long double D = 3.0L * A * B * B - 3.0L / (2.0L * sinhl(2.0L * x));
  long double E = 3.0L * A * B, F = 1.5L * A, Z = E * E / F - 2.0L * D;
  c[0] = A;
  c[1] = D;
  c[2] = E;
  c[3] = F;
  c[4] = Z;
  c[5] = 1.5L * logl(F) + logl(Z / expm1l(Z)) - D - logl(4.0L * powl(acosl(-1.0L), 2.5L));
}

Test(fwddip_propagator, coefficients_match_their_definitions_and_z_is_6t_over_1_minus_t2) {
  for (int i = 0; i <= 200; ++i) {
    double ps = 0.02 * pow(1000.0, i / 200.0); /* 0.02 .. 20 */
    ss_fwddip_coeffs k;
    ss_fwddip_coeffs_make(ps, &k);
    long double ref[6];
    coeffs_direct(ps, ref);
    const double got[] = {k.A, k.D, k.E, k.F, k.Z, k.log_norm};
    for (int j = 0; j < 6; ++j) {
      double tol = 1e-12 * fmax(1.0, fabs((double)ref[j]));
      cr_expect(fabs(got[j] - (double)ref[j]) <= tol, "ps %g coefficient %d: %.17g vs %.17Lg", ps,
                j, got[j], ref[j]);
    }
    double t = exp(-2.0 * ps);
    cr_expect(fabs(k.Z - 6.0 * t / (1.0 - t * t)) <= 1e-13 * k.Z, "ps %g", ps);
  }
}

/* A grid of positions and directions around the ballistic path and far off
 * it: G_f is a finite, non-negative number everywhere. */
Test(fwddip_propagator, gf_is_finite_and_non_negative_over_ps_and_angles) {
  ss_fwddip_medium m = ss_fwddip_medium_make(1.0, 0.01);
  ss_vec3 wp = ss_vec3_make(0, 0, 1);
  for (int i = 0; i <= 100; ++i) {
    double ps = PS_MIN * pow(PS_MAX / PS_MIN, i / 100.0), s = ps / m.p;
    for (int a = 0; a <= 24; ++a) {
      double cos_t = cos(SS_PI * pow(a / 24.0, 3.0));
      ss_vec3 w = ss_spherical_direction(cos_t, 0.3 * a);
      for (int d = 0; d <= 12; ++d) {
        double scale = s * pow(10.0, -4.0 + 5.0 * d / 12.0);
        ss_vec3 xs[] = {ss_vec3_scale(w, scale), ss_vec3_scale(ss_vec3_add(w, wp), 0.5 * s),
                        ss_vec3_make(scale, -scale, 0.5 * scale)};
        for (int j = 0; j < 3; ++j) {
          double g = ss_fwddip_gf(&m, s, xs[j], w, ss_vec3_make(0, 0, 0), wp);
          cr_assert(isfinite(g) && g >= 0.0, "ps %g angle %d dist %d: %g", ps, a, d, g);
        }
      }
    }
  }
}

/* int_{S^2} dw int_{R^3} d^3x G_f(s, x, w, 0, z) by quadrature: for each w
 * the x-integrand is a Gaussian, integrated by a tensor rule over +-8 of its
 * widths about its centre; w runs over geometric panels in 1 - cos. */
static double normalisation_by_quadrature(const ss_fwddip_medium *m, double s) {
  static double gx[MAX_GL], gw[MAX_GL];
  const int nx = 40, nm = 12;
  ss_gauss_legendre(nx, gx, gw);
  double mx[MAX_GL], mw[MAX_GL];
  ss_gauss_legendre(nm, mx, mw);
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(m->p * s, &k);
  ss_vec3 wp = ss_vec3_make(0, 0, 1), o = ss_vec3_make(0, 0, 0);
  double a = 0.5 * k.Z + 1.0; /* the directional rate after the x integral */
  double width = 8.0 / (m->p * sqrt(2.0 * k.F));
  double total = 0.0;
  for (double v0 = 0.0, v1 = fmin(2.0, 0.05 / a); v0 < 2.0; v0 = v1, v1 = fmin(2.0, 2.0 * v1)) {
    for (int im = 0; im < nm; ++im) {
      double v = 0.5 * (v0 + v1) + 0.5 * (v1 - v0) * mx[im], dv = 0.5 * (v1 - v0) * mw[im];
      ss_vec3 w = ss_spherical_direction(1.0 - v, 0.0);
      ss_vec3 c = ss_vec3_scale(ss_vec3_add(w, wp), k.E / (2.0 * k.F * m->p));
      double inner = 0.0;
      for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < nx; ++j) {
          for (int l = 0; l < nx; ++l) {
            ss_vec3 x = ss_vec3_add(c, ss_vec3_make(width * gx[i], width * gx[j], width * gx[l]));
            inner += gw[i] * gw[j] * gw[l] * exp(ss_fwddip_log_gf(m, &k, s, x, w, o, wp));
          }
        }
      }
      total += 2.0 * SS_PI * dv * inner * width * width * width;
    }
  }
  return total;
}

Test(fwddip_propagator, integral_over_position_and_direction_is_exp_minus_sigma_a_s) {
  ss_fwddip_medium m = ss_fwddip_medium_make(1.0, 0.01);
  const double ps[] = {1e-6, 1e-4, 0.006, 0.1, 0.2499, 0.2501, 1.0, 3.0, 20.0, 400.0, 1e4};
  for (size_t i = 0; i < sizeof ps / sizeof ps[0]; ++i) {
    double s = ps[i] / m.p, want = exp(-m.sigma_a * s);
    double got = normalisation_by_quadrature(&m, s);
    cr_expect(fabs(got - want) <= 1e-7 * want, "ps %g: %.12g vs %.12g", ps[i], got, want);
  }
}

static ss_vec3 random_direction(ss_rng *r) {
  return ss_sample_uniform_sphere(ss_rng_uniform(r), ss_rng_uniform(r));
}

static ss_vec3 random_point(ss_rng *r, double scale) {
  return ss_vec3_make(scale * (2.0 * ss_rng_uniform(r) - 1.0),
                      scale * (2.0 * ss_rng_uniform(r) - 1.0),
                      scale * (2.0 * ss_rng_uniform(r) - 1.0));
}

/* Eq. 9 is invariant under (x, w, x', w') -> (x', -w', x, -w). */
Test(fwddip_propagator, gf_is_reciprocal) {
  ss_fwddip_medium m = ss_fwddip_medium_make(0.7, 0.05);
  ss_rng r;
  ss_rng_seed(&r, 8, 1);
  for (int i = 0; i < 2000; ++i) {
    double s = 0.01 * pow(1e4, ss_rng_uniform(&r));
    ss_vec3 x = random_point(&r, 0.5 * s), xp = random_point(&r, 0.5 * s);
    ss_vec3 w = random_direction(&r), wp = random_direction(&r);
    double a = ss_fwddip_gf(&m, s, x, w, xp, wp);
    double b = ss_fwddip_gf(&m, s, xp, ss_vec3_neg(wp), x, ss_vec3_neg(w));
    cr_assert(fabs(a - b) <= 1e-10 * fmax(a, b) + 1e-300, "%d: %g vs %g", i, a, b);
  }
}

/* On a plane (n_i = n_o, x_o - x_i tangent) G^b_f is reciprocal for a source
 * into the medium and an exit out of it; eq. 15 is reciprocal everywhere. */
Test(fwddip_propagator, gbf_is_reciprocal_on_a_plane_and_eq15_everywhere) {
  ss_fwddip_medium m = ss_fwddip_medium_make(1.0, 0.01);
  ss_rng r;
  ss_rng_seed(&r, 8, 2);
  ss_vec3 n = ss_vec3_make(0, 0, 1);
  for (int i = 0; i < 2000; ++i) {
    double s = 0.01 * pow(1e3, ss_rng_uniform(&r)), z_v = 0.3;
    ss_fwddip_coeffs k;
    ss_fwddip_coeffs_make(m.p * s, &k);
    ss_vec3 x_i = ss_vec3_make(ss_rng_uniform(&r), ss_rng_uniform(&r), 0.0);
    ss_vec3 x_o = ss_vec3_make(ss_rng_uniform(&r), ss_rng_uniform(&r), 0.0);
    ss_vec3 w_i = random_direction(&r), w_o = random_direction(&r);
    w_i.z = -fabs(w_i.z);
    w_o.z = fabs(w_o.z);
    double a = ss_fwddip_gbf(&m, &k, s, x_o, w_o, x_i, n, w_i, z_v);
    double b = ss_fwddip_gbf(&m, &k, s, x_i, ss_vec3_neg(w_i), x_o, n, ss_vec3_neg(w_o), z_v);
    double scale = 1e-10 * (fabs(a) + fabs(b)) + 1e-300;
    cr_assert(fabs(a - b) <= scale, "planar %d: %g vs %g", i, a, b);
    /* Curved: different normals and a point off the plane. */
    ss_vec3 n_i = ss_vec3_normalize(ss_vec3_add(n, ss_vec3_scale(random_direction(&r), 0.4)));
    ss_vec3 n_o = ss_vec3_normalize(ss_vec3_add(n, ss_vec3_scale(random_direction(&r), 0.4)));
    x_o.z = -0.2 * ss_rng_uniform(&r);
    double c = ss_fwddip_gbf_reciprocal(&m, &k, s, x_o, n_o, w_o, x_i, n_i, w_i, z_v);
    double d = ss_fwddip_gbf_reciprocal(&m, &k, s, x_i, n_i, ss_vec3_neg(w_i), x_o, n_o,
                                        ss_vec3_neg(w_o), z_v);
    cr_assert(fabs(c - d) <= 1e-12 * (fabs(c) + fabs(d)) + 1e-300, "eq. 15 %d: %g vs %g", i, c, d);
  }
}

/* Eq. 10: for ps << 1, G_f approaches the unscattered Gaussian; near the
 * ballistic peak the relative difference is O(ps^2) (measured 1.8 ps^2). */
static double eq10(double p, double s, ss_vec3 R, ss_vec3 w, ss_vec3 wp) {
  double ps = p * s;
  ss_vec3 d = ss_vec3_sub(ss_vec3_scale(R, 1.0 / s), ss_vec3_scale(ss_vec3_add(w, wp), 0.5));
  ss_vec3 dw = ss_vec3_sub(w, wp);
  double pre = p * p * p * 81.0 * sqrt(2.0) / (32.0 * pow(SS_PI, 2.5) * pow(ps, 5.5));
  return pre * exp(-4.5 / ps * ss_vec3_length2(d) - 3.0 / (8.0 * ps) * ss_vec3_length2(dw));
}

Test(fwddip_propagator, short_paths_approach_eq10) {
  ss_fwddip_medium m = ss_fwddip_medium_make(2.0, 0.0);
  ss_vec3 wp = ss_vec3_make(0, 0, 1), o = ss_vec3_make(0, 0, 0);
  const double ps[] = {1e-3, 1e-4, 1e-5};
  for (int i = 0; i < 3; ++i) {
    double s = ps[i] / m.p, spread = sqrt(ps[i]), worst = 0.0;
    for (int a = 0; a <= 4; ++a) {
      ss_vec3 w = ss_spherical_direction(cos(spread * a * 0.5), 0.0);
      for (int b = -2; b <= 2; ++b) {
        ss_vec3 R = ss_vec3_scale(ss_vec3_add(w, wp), 0.5 * s);
        R = ss_vec3_add(R, ss_vec3_make(0.3 * b * s * spread, 0.2 * b * s * spread, 0.0));
        double g = ss_fwddip_gf(&m, s, R, w, o, wp), ref = eq10(m.p, s, R, w, wp);
        worst = fmax(worst, fabs(g / ref - 1.0));
      }
    }
    cr_expect(worst <= 5.0 * ps[i] * ps[i] + 1e-9, "ps %g: worst relative difference %g", ps[i],
              worst);
  }
}

/* The fluence of an isotropic point source, (1/4pi) int int G_f dw dw', with
 * the w integral in closed form (int e^{w.h} dw = 4 pi sinh|h|/|h|) and w'
 * by quadrature over its angle to r. */
static double fluence(const ss_fwddip_medium *m, double s, double R) {
  double gx[MAX_GL], gw[MAX_GL];
  const int n = 48;
  ss_gauss_legendre(n, gx, gw);
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(m->p * s, &k);
  double r = m->p * R, sum = 0.0;
  for (int i = 0; i < n; ++i) {
    double mu = gx[i];
    double h = sqrt(fmax(0.0, k.E * k.E * r * r - 2.0 * k.E * k.D * r * mu + k.D * k.D));
    double sinhc = h > 1e-8 ? sinh(h) / h : 1.0;
    sum += gw[i] * 2.0 * SS_PI * exp(k.E * r * mu) * 4.0 * SS_PI * sinhc;
  }
  return exp(m->log_p3 + k.log_norm - k.F * r * r - m->sigma_a * s) * sum / (4.0 * SS_PI);
}

/* Eq. 11: for ps >> 1 and s >> |x - x'| the fluence is the diffusion
 * Gaussian (3p/(2 pi s))^{3/2} exp(-3p R^2/(2s) - sigma_a s), to O(1/ps) (measured 2.2/ps). */
Test(fwddip_propagator, long_paths_approach_eq11) {
  ss_fwddip_medium m = ss_fwddip_medium_make(1.0, 0.001);
  const double ps[] = {1e2, 1e3, 1e4};
  for (int i = 0; i < 3; ++i) {
    double s = ps[i] / m.p, worst = 0.0;
    for (int j = 0; j <= 4; ++j) {
      double R = 0.5 * j * sqrt(s / m.p);
      double want =
          pow(3.0 * m.p / (2.0 * SS_PI * s), 1.5) * exp(-1.5 * m.p * R * R / s - m.sigma_a * s);
      worst = fmax(worst, fabs(fluence(&m, s, R) / want - 1.0));
    }
    cr_expect(worst <= 3.0 / ps[i], "ps %g: worst relative difference %g", ps[i], worst);
  }
}

/* Eq. 17 equals the integral of eq. 9 over the source plane at offset h. */
Test(fwddip_propagator, planar_source_is_gf_integrated_over_the_plane) {
  ss_fwddip_medium m = ss_fwddip_medium_make(1.0, 0.02);
  double gx[MAX_GL], gw[MAX_GL];
  const int n = 40;
  ss_gauss_legendre(n, gx, gw);
  ss_rng r;
  ss_rng_seed(&r, 8, 3);
  ss_vec3 nrm = ss_vec3_make(0, 0, 1), x = ss_vec3_make(0, 0, 0);
  for (int i = 0; i < 20; ++i) {
    double s = 0.05 * pow(400.0, ss_rng_uniform(&r)), h = -ss_rng_uniform(&r) * s;
    ss_vec3 w = random_direction(&r), wp = random_direction(&r);
    ss_fwddip_coeffs k;
    ss_fwddip_coeffs_make(m.p * s, &k);
    /* The in-plane Gaussian: centre -E (w + w')_t/(2 F p), width 1/(p sqrt(2F)). */
    ss_vec3 u = ss_vec3_add(w, wp);
    double cx = -k.E * u.x / (2.0 * k.F * m.p), cy = -k.E * u.y / (2.0 * k.F * m.p);
    double width = 9.0 / (m.p * sqrt(2.0 * k.F)), sum = 0.0;
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        ss_vec3 xp = ss_vec3_make(cx + width * gx[a], cy + width * gx[b], -h);
        sum += gw[a] * gw[b] * exp(ss_fwddip_log_gf(&m, &k, s, x, w, xp, wp));
      }
    }
    sum *= width * width;
    double gp = ss_fwddip_gpf(&m, &k, s, h, w, wp, nrm);
    cr_expect(fabs(gp - sum) <= 1e-9 * gp + 1e-300, "%d: s %g h %g: %g vs %g", i, s, h, gp, sum);
  }
}

/* Eq. 18 is the difference of its two planes and vanishes for a source
 * pointing out of the medium. */
Test(fwddip_propagator, planar_dipole_is_real_minus_image_plane) {
  ss_fwddip_medium m = ss_fwddip_medium_make(1.0, 0.01);
  ss_vec3 n = ss_vec3_make(0, 0, 1);
  ss_fwddip_coeffs k;
  ss_fwddip_coeffs_make(m.p * 2.0, &k);
  ss_vec3 w_i = ss_vec3_normalize(ss_vec3_make(0.3, 0.1, -0.9));
  ss_vec3 w_o = ss_vec3_normalize(ss_vec3_make(0.5, -0.2, 0.8));
  ss_vec3 w_v = ss_vec3_make(w_i.x, w_i.y, -w_i.z);
  double want =
      ss_fwddip_gpf(&m, &k, 2.0, 0.0, w_o, w_i, n) - ss_fwddip_gpf(&m, &k, 2.0, -0.4, w_o, w_v, n);
  double got = ss_fwddip_gpbf(&m, &k, 2.0, w_o, w_i, n, 0.4);
  cr_expect(fabs(got - want) <= 1e-13 * fabs(want));
  cr_expect(ss_fwddip_gpbf(&m, &k, 2.0, w_o, ss_vec3_neg(w_i), n, 0.4) == 0.0);
}
