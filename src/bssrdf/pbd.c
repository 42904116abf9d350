#include "subsurf/pbd.h"

#include "subsurf/fresnel.h"
#include "subsurf/sampling.h"

#include <gsl/gsl_integration.h>
#include <math.h>

/* Beam depths beyond this many reduced mean free paths past the closest
 * approach carry less than e^-36 of the integrand. */
#define PBD_DEPTH_CUTOFF 36.0
/* Radii in log space: panel width and the smallest radius integrated. */
#define PBD_LOG_PANEL 1.0
#define PBD_R_MIN 1e-7
/* Azimuth points on [0, pi] for the radial energy. */
#define PBD_PHI_POINTS 64

ss_status ss_pbd_init(ss_pbd *p, double sigma_s, double sigma_a, double g, double eta, int nodes,
                      ss_error *err) {
  if (!(isfinite(sigma_s) && sigma_s >= 0.0) || !(isfinite(sigma_a) && sigma_a >= 0.0) ||
      !(sigma_s + sigma_a > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "pbd: sigma_s = %g, sigma_a = %g: expected finite values >= 0 with "
                        "sigma_s + sigma_a > 0",
                        sigma_s, sigma_a);
  }
  if (!(eta > 0.0) || !isfinite(eta)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "pbd: eta = %g: expected > 0", eta);
  }
  if (nodes < 2 || nodes > SS_PBD_MAX_NODES) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "pbd: %d beam quadrature nodes: expected 2..%d", nodes, SS_PBD_MAX_NODES);
  }
  ss_status st = ss_phase_init(&p->phase, SS_PHASE_HG, g, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "pbd: ");
    return st;
  }
  p->g = g;
  p->eta = eta;
  /* Fresnel moments of light meeting the boundary from inside. */
  p->c1 = ss_fresnel_moment(1, eta);
  p->c2 = ss_fresnel_moment(2, eta);
  p->c_phi = 0.25 * (1.0 - 2.0 * p->c1);
  p->c_e = 0.5 * (1.0 - 3.0 * p->c2);
  ss_pbd_set_albedo(p, sigma_s, sigma_a);
  p->nodes = nodes;
  gsl_integration_glfixed_table *tab = gsl_integration_glfixed_table_alloc((size_t)nodes);
  if (!tab) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "pbd: Gauss-Legendre table");
  }
  for (int i = 0; i < nodes; ++i) {
    gsl_integration_glfixed_point(0.0, 1.0, (size_t)i, &p->gl_x[i], &p->gl_w[i], tab);
  }
  gsl_integration_glfixed_table_free(tab);
  return SS_OK;
}

void ss_pbd_set_albedo(ss_pbd *p, double sigma_s, double sigma_a) {
  p->sigma_s = sigma_s;
  p->sigma_a = sigma_a;
  p->sigma_t = sigma_s + sigma_a;
  p->rho = sigma_s / p->sigma_t;
  /* Ferrier2016, appendix table 4 (material constants). */
  double sigma_s_p = sigma_s * (1.0 - p->g);
  p->sigma_t_p = sigma_s_p + sigma_a;
  p->rho_p = sigma_s_p / p->sigma_t_p;
  p->D_g = (2.0 * sigma_a + sigma_s_p) / (3.0 * p->sigma_t_p * p->sigma_t_p);
  p->sigma_tr = sqrt(sigma_a / p->D_g);
  p->z_b = 2.0 * p->D_g * (1.0 + 3.0 * p->c2) / (1.0 - 2.0 * p->c1);
}

ss_pbd_beam ss_pbd_beam_make(const ss_pbd *p, double theta) {
  /* Snell: sin(theta') = sin(theta)/eta (Ferrier2016, table 4). */
  ss_pbd_beam b;
  b.sin_t = sin(theta) / p->eta;
  if (b.sin_t > 1.0) {
    b.sin_t = 1.0;
  }
  b.cos_t = sqrt(fmax(0.0, 1.0 - b.sin_t * b.sin_t));
  return b;
}

/* PBD's point source (Ferrier2016, table 4): (R_phi^d + R_E^d) kappa, the
 * exitance of the dipole with its real source at depth z_r (squared distance
 * d2 = lambda^2 + z_r^2 from the exit point) and its image at z_r + 2 z_b
 * above the surface, per unit power scattered at z_r. */
static double point_source(const ss_pbd *p, double z_r, double d2) {
  double h_min = 1e-9 / p->sigma_t_p;
  d2 = fmax(d2, h_min * h_min);
  double d_r = sqrt(d2);
  double z_v = z_r + 2.0 * p->z_b; /* height of the virtual source above the surface */
  double lambda2 = fmax(0.0, d2 - z_r * z_r);
  double d_v = sqrt(lambda2 + z_v * z_v);
  double e_r = exp(-p->sigma_tr * d_r), e_v = exp(-p->sigma_tr * d_v);
  /* Fluence and vector irradiance of the dipole (d'Eon & Irving 2011). */
  double r_phi = p->rho_p * p->c_phi / (4.0 * SS_PI * p->D_g) * (e_r / d_r - e_v / d_v);
  double r_e = p->rho_p * p->c_e / (4.0 * SS_PI) *
               (z_r * (1.0 + p->sigma_tr * d_r) * e_r / (d2 * d_r) +
                z_v * (1.0 + p->sigma_tr * d_v) * e_v / (d_v * d_v * d_v));
  /* PBD's correction for sources near the boundary. */
  double kappa = -expm1(-2.0 * p->sigma_t_p * (d_r + z_r));
  return (r_phi + r_e) * kappa;
}

double ss_pbd_point_source(const ss_pbd *p, double z, double r) {
  return point_source(p, z, r * r + z * z);
}

/* The PBD integrand at beam depth t (Habel2013; Ferrier2016 Table 4): the
 * point source at depth z_r = t cos(theta') times Q(t) = rho' sigma_t'
 * e^{-sigma_t' t}, the power first scattered at t. */
static double ms_integrand(const ss_pbd *p, double t, double z_r, double d2) {
  double q = p->rho_p * p->sigma_t_p * exp(-p->sigma_t_p * t);
  return point_source(p, z_r, d2) * q;
}

/* Gauss-Legendre over s in [s_a, s_b] of the integrand at t = t0 + h sinh(s). */
static double ms_piece(const ss_pbd *p, const ss_pbd_beam *beam, double t0, double h, double s_a,
                       double s_b) {
  double width = s_b - s_a, sum = 0.0;
  for (int k = 0; k < p->nodes; ++k) {
    double s = s_a + width * p->gl_x[k];
    double sh = sinh(s), ch = sqrt(1.0 + sh * sh);
    double t = t0 + h * sh;
    double dt = t - t0;
    double d2 = dt * dt + h * h;
    sum += p->gl_w[k] * ms_integrand(p, t, t * beam->cos_t, d2) * h * ch;
  }
  return sum * width;
}

double ss_pbd_ms(const ss_pbd *p, const ss_pbd_beam *beam, double r, double phi) {
  /* The beam point closest to the exit point (t*, the projection on the
   * beam) and the distance h there: d_r^2 = (t - t*)^2 + h^2. */
  double t_star = r * cos(phi) * beam->sin_t;
  double h2 = r * r - t_star * t_star;
  double h_min = 1e-9 / p->sigma_t_p;
  double h = sqrt(fmax(h2, h_min * h_min));
  double t_max = fmax(t_star, 0.0) + PBD_DEPTH_CUTOFF / p->sigma_t_p;
  double s_lo = asinh(-t_star / h), s_hi = asinh((t_max - t_star) / h);
  if (s_lo < 0.0) {
    return ms_piece(p, beam, t_star, h, s_lo, 0.0) + ms_piece(p, beam, t_star, h, 0.0, s_hi);
  }
  return ms_piece(p, beam, t_star, h, s_lo, s_hi);
}

/* Single scattering of the normally incident beam at depth t seen from the
 * exit point at radius r (pbrt-v3 BeamDiffusionSS; Jensen et al. 2001 eq. 3
 * geometry): attenuation in, scattering toward the exit, attenuation out,
 * Fresnel transmission, and the solid-angle-to-area factor cos_o / d^2. */
static double ss_integrand(const ss_pbd *p, double r, double t) {
  double d2 = r * r + t * t, d = sqrt(d2);
  double cos_o = t / d;
  double tr = 1.0 - ss_fresnel_dielectric(-cos_o, p->eta);
  if (tr <= 0.0) {
    return 0.0;
  }
  return p->sigma_t * p->rho * exp(-p->sigma_t * (t + d)) * ss_phase_eval(&p->phase, -cos_o) * tr *
         cos_o / d2;
}

double ss_pbd_ss(const ss_pbd *p, double r) {
  /* Below t_crit the exit direction is totally internally reflected. */
  double r_eff = fmax(r, 1e-9 / p->sigma_t);
  double t_crit = p->eta > 1.0 ? r * sqrt(p->eta * p->eta - 1.0) : 0.0;
  double t_max = t_crit + PBD_DEPTH_CUTOFF / p->sigma_t;
  /* t = r_eff sinh(s) resolves the 1/d^2 peak of width r; s = s_c + v^2
   * removes the square-root onset of Fresnel transmission at t_crit. */
  double s_c = asinh(t_crit / r_eff), s_hi = asinh(t_max / r_eff);
  double v_max = sqrt(s_hi - s_c), sum = 0.0;
  for (int k = 0; k < p->nodes; ++k) {
    double v = v_max * p->gl_x[k];
    double s = s_c + v * v;
    double sh = sinh(s);
    double t = r_eff * sh;
    sum += p->gl_w[k] * ss_integrand(p, r, t) * r_eff * sqrt(1.0 + sh * sh) * 2.0 * v;
  }
  return sum * v_max;
}

/* int_0^inf f(r) dr by Gauss-Legendre panels in ln r, plus the tail beyond
 * r_max estimated from a 1/r^2 decay of f (the non-absorbing diffusion
 * limit; negligible whenever sigma_tr r_max is large). */
typedef double (*radial_fn)(const ss_pbd *p, const void *ctx, double r);

static double integrate_radius(const ss_pbd *p, radial_fn f, const void *ctx) {
  double r_min = PBD_R_MIN / p->sigma_t_p;
  double r_max = 1e4 / p->sigma_t_p;
  if (p->sigma_tr > 0.0) {
    r_max = fmin(r_max, fmax(60.0 / p->sigma_tr, 60.0 / p->sigma_t_p));
  }
  double x0 = log(r_min), x1 = log(r_max);
  int panels = (int)ceil((x1 - x0) / PBD_LOG_PANEL);
  double width = (x1 - x0) / panels, sum = 0.0;
  for (int i = 0; i < panels; ++i) {
    for (int k = 0; k < p->nodes; ++k) {
      double r = exp(x0 + width * (i + p->gl_x[k]));
      sum += p->gl_w[k] * width * f(p, ctx, r) * r;
    }
  }
  return sum + f(p, ctx, r_max) * r_max;
}

static double profile_fn(const ss_pbd *p, const void *ctx, double r) {
  const ss_pbd_beam *beam = ctx;
  return 2.0 * SS_PI * r * (ss_pbd_ms(p, beam, r, 0.0) + ss_pbd_ss(p, r));
}

double ss_pbd_effective_albedo(const ss_pbd *p) {
  ss_pbd_beam beam = ss_pbd_beam_make(p, 0.0);
  return integrate_radius(p, profile_fn, &beam);
}

double ss_pbd_ms_radial(const ss_pbd *p, const ss_pbd_beam *beam, double r) {
  if (beam->sin_t == 0.0) {
    return 2.0 * SS_PI * r * ss_pbd_ms(p, beam, r, 0.0);
  }
  /* Trapezoid rule on the even periodic integrand: spectrally accurate. */
  double sum = 0.5 * (ss_pbd_ms(p, beam, r, 0.0) + ss_pbd_ms(p, beam, r, SS_PI));
  for (int k = 1; k < PBD_PHI_POINTS; ++k) {
    sum += ss_pbd_ms(p, beam, r, SS_PI * k / PBD_PHI_POINTS);
  }
  return 2.0 * r * sum * SS_PI / PBD_PHI_POINTS;
}

static double radial_fn_ms(const ss_pbd *p, const void *ctx, double r) {
  return ss_pbd_ms_radial(p, ctx, r);
}

double ss_pbd_ms_albedo(const ss_pbd *p, double theta) {
  ss_pbd_beam beam = ss_pbd_beam_make(p, theta);
  return integrate_radius(p, radial_fn_ms, &beam);
}
