#include "bssrdf/bssrdf_util.h"

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

/* The x >= 0 with (1 + x) e^{-x} = 1 - u, the inverse of the Gamma(2) cdf:
 * phi(x) = x - log(1 + x) = t with t = -log(1 - u) (x = -1 - W_{-1}(-(1 - u)/e)
 * in Lambert's W). The start is the inverse series phi^{-1}(t) = p + p^2/3 +
 * p^3/36 - p^4/270 in p = sqrt(2 t) for small t and t + log(1 + t + log(1 + t))
 * (from x = t + log(1 + x)) for large t; Halley steps on phi(x) - t, with
 * phi' = x/(1 + x) and phi'' = 1/(1 + x)^2, polish it. */
double ss_gamma2_inverse(double u) {
  if (!(u > 0.0)) {
    return 0.0;
  }
  double t = -log1p(-fmin(u, 1.0 - 0x1p-53)), p = sqrt(2.0 * t);
  double x = p * (1.0 + p * (1.0 / 3.0 + p * (1.0 / 36.0 - p / 270.0)));
  if (p < 1e-3) {
    return x; /* series error ~ p^5 / 4320 */
  }
  if (t > 2.0) {
    x = t + log1p(t + log1p(t));
  }
  /* Halley converges cubically: a step below 1e-6 x leaves an error below
   * ~1e-18 x, so the loop stops there (one to three steps). */
  for (int i = 0; i < 3; ++i) {
    double f = x - log1p(x) - t, d1 = x / (1.0 + x), d2 = 1.0 / ((1.0 + x) * (1.0 + x));
    double dx = f / (d1 - 0.5 * f * d2 / d1);
    x -= dx;
    if (fabs(dx) < 1e-6 * x) {
      break;
    }
  }
  return fmax(x, 0.0);
}

void ss_radial_mix_sample(const ss_radial_mix *m, double u1, double u2, ss_bssrdf_entry *e) {
  int k = 0;
  double acc = 0.0;
  while (k < m->n - 1 && u1 >= acc + m->weight[k]) {
    acc += m->weight[k];
    ++k;
  }
  double u = fmin((u1 - acc) / m->weight[k], 1.0 - 0x1p-53);
  e->r = ss_gamma2_inverse(fmax(u, 0.0)) / m->sigma[k];
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

ss_status ss_bssrdf_params_check_medium(const ss_bssrdf_params *p, const char *model,
                                        ss_error *err) {
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

ss_status ss_bssrdf_params_check(const ss_bssrdf_params *p, const char *model, ss_error *err) {
  ss_status st = ss_bssrdf_params_check_medium(p, model, err);
  if (st != SS_OK) {
    return st;
  }
  if (p->medium.flakes.type != SS_FLAKE_NONE) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "flakes: model %s does not take micro-flake media", model);
  }
  return SS_OK;
}
