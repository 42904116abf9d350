#include "bssrdf/bssrdf_util.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_lambert.h>

const double ss_gl8_x[SS_GL8_N] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                   -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                   0.7966664774136267,  0.9602898564975363};
const double ss_gl8_w[SS_GL8_N] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                   0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                   0.2223810344533745, 0.1012285362903763};

double ss_gl_integrate(ss_scalar_fn f, void *ctx, double a, double b, int panels) {
  double h = (b - a) / panels, sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    double mid = a + (p + 0.5) * h, half = 0.5 * h;
    for (int k = 0; k < SS_GL8_N; ++k) {
      sum += ss_gl8_w[k] * half * f(ctx, mid + half * ss_gl8_x[k]);
    }
  }
  return sum;
}

typedef struct {
  double eta;
} ft_ctx;

static double ft_out_integrand(void *ctx, double mu) {
  const ft_ctx *c = ctx;
  return 2.0 * ss_ft_outside(mu, c->eta) * mu;
}

double ss_fresnel_transmission_out(double eta) {
  ft_ctx c = {eta};
  return ss_gl_integrate(ft_out_integrand, &c, 0.0, 1.0, 16);
}

void ss_radial_mix_init(ss_radial_mix *m, int n, const double *sigma, const double *weight) {
  double total = 0.0;
  m->n = 0;
  for (int k = 0; k < n && m->n < SS_RADIAL_MIX_MAX; ++k) {
    if (isfinite(sigma[k]) && sigma[k] > 0.0 && weight[k] > 0.0) {
      m->sigma[m->n] = sigma[k];
      m->weight[m->n] = weight[k];
      total += weight[k];
      m->n++;
    }
  }
  for (int k = 0; k < m->n; ++k) {
    m->weight[k] /= total;
  }
}

void ss_radial_mix_init_diffusion(ss_radial_mix *m, double sigma_tr, double sigma_t_prime) {
  double rates[2] = {fmax(sigma_tr, 1e-3 * sigma_t_prime), sigma_t_prime};
  double weights[2] = {0.75, 0.25};
  ss_radial_mix_init(m, 2, rates, weights);
}

/* Inverse of the Gamma(2) cdf 1 - (1 + x) e^{-x} = u through the lower
 * branch of Lambert's W: with y = -(1 + x), y e^y = -(1 - u)/e. */
static double gamma2_inverse(double u) {
  double v = 1.0 - u;
  if (v >= 1.0) {
    return 0.0;
  }
  if (v <= 0.0) {
    v = 0x1p-53;
  }
  gsl_sf_result res;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int st = gsl_sf_lambert_Wm1_e(-v * 0.36787944117144233, &res);
  gsl_set_error_handler(old);
  if (st != GSL_SUCCESS && !isfinite(res.val)) {
    return 0.0;
  }
  return fmax(0.0, -1.0 - res.val);
}

void ss_radial_mix_sample(const ss_radial_mix *m, double u1, double u2, ss_bssrdf_entry *e) {
  int k = 0;
  double acc = 0.0;
  while (k < m->n - 1 && u1 >= acc + m->weight[k]) {
    acc += m->weight[k];
    ++k;
  }
  double u = fmin((u1 - acc) / m->weight[k], 1.0 - 0x1p-53);
  e->r = gamma2_inverse(fmax(u, 0.0)) / m->sigma[k];
  e->phi = 2.0 * SS_PI * u2;
  e->pdf = ss_radial_mix_pdf(m, e->r);
}

double ss_radial_mix_pdf(const ss_radial_mix *m, double r) {
  if (r < 0.0) {
    return 0.0;
  }
  double p = 0.0;
  for (int k = 0; k < m->n; ++k) {
    p += m->weight[k] * m->sigma[k] * m->sigma[k] * exp(-m->sigma[k] * r);
  }
  return p / (2.0 * SS_PI);
}

double ss_radial_mix_max_radius(const ss_radial_mix *m) {
  /* (1 + x) e^{-x} = 1e-4 at x = 11.63 for every Gamma(2) component. */
  double smin = INFINITY;
  for (int k = 0; k < m->n; ++k) {
    smin = fmin(smin, m->sigma[k]);
  }
  return 11.63 / smin;
}

ss_status ss_bssrdf_params_check(const ss_bssrdf_params *p, const char *model, ss_error *err) {
  ss_status st = ss_medium_optics_check(&p->medium, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "%s: ", model);
    return st;
  }
  if (!isfinite(p->eta) || !(p->eta > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: eta must be finite and > 0, got %g",
                        model, p->eta);
  }
  return SS_OK;
}
