/* The samplers of the forward scattering dipole (subsurf/fwddip.h): each
 * passes a chi-square test against its own pdf, and the estimators they
 * drive converge to the quantities they estimate. */
#include "bssrdf/bssrdf_test_util.h"
#include "bssrdf/fwddip_model.h"
#include "subsurf/fwddip.h"

typedef struct {
  const ss_bssrdf *b;
  ss_vec3 w_i;
} brdf_ctx;

static int brdf_sample(void *vctx, double u1, double u2, double u3, ss_vec3 *dir) {
  brdf_ctx *c = vctx;
  double pdf;
  (void)u3;
  return ss_fwddip_brdf_sample(c->b, c->w_i, u1, u2, dir, &pdf);
}

static double brdf_pdf(void *vctx, ss_vec3 dir) {
  brdf_ctx *c = vctx;
  return ss_fwddip_brdf_pdf(c->b, c->w_i, dir);
}

static ss_vec3 incidence(double deg) {
  double t = deg * SS_PI / 180.0;
  return ss_vec3_make(-sin(t), 0.0, cos(t));
}

Test(fwddip_sample, brdf_sampler_passes_chi_square_against_its_pdf) {
  ss_bssrdf *b = make_gray("fwddip-brdf", 1.0 / 1.01, 1.01, 1.0, 0.9);
  const double angles[] = {0.0, 45.0, 80.0};
  for (int i = 0; i < 3; ++i) {
    brdf_ctx c = {b, incidence(angles[i])};
    ss_chi2_sphere_options o;
    ss_chi2_sphere_options_default(&o);
    o.seed = 80 + (uint64_t)i;
    ss_chi2_result res;
    ss_chi2_test_sphere(brdf_sample, brdf_pdf, &c, &o, &res);
    cr_expect(res.p_value > ss_chi2_sidak_alpha(0.01, 3), "%g deg: %s (p %g)", angles[i],
              res.message, res.p_value);
    cr_expect(fabs(res.pdf_integral - 1.0) < 1e-3, "pdf integrates to %g", res.pdf_integral);
  }
  ss_bssrdf_destroy(b);
}

/* E[f_r cos / pdf] is the albedo (total reflectance), to 4 standard errors. */
Test(fwddip_sample, brdf_sampler_estimates_the_albedo) {
  ss_bssrdf *b = make_gray("fwddip-brdf", 1.0 / 1.01, 1.01, 1.33, 0.9);
  const double angles[] = {0.0, 80.0};
  ss_rng rng;
  ss_rng_seed(&rng, 8, 6);
  for (int i = 0; i < 2; ++i) {
    ss_vec3 w_i = incidence(angles[i]);
    double sum = 0.0, sum2 = 0.0;
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
      ss_vec3 w_o;
      double pdf, f[3], v = 0.0;
      if (ss_fwddip_brdf_sample(b, w_i, ss_rng_uniform(&rng), ss_rng_uniform(&rng), &w_o, &pdf) &&
          w_o.z > 0.0) {
        ss_bssrdf_brdf(b, w_i, w_o, f);
        v = f[0] * w_o.z / pdf;
      }
      sum += v;
      sum2 += v * v;
    }
    double mean = sum / n, se = sqrt((sum2 / n - mean * mean) / n), total[3];
    ss_bssrdf_total_reflectance(b, w_i.z, total);
    cr_expect(fabs(mean - total[0]) < 4.0 * se + 2e-3 * total[0], "%g deg: %g +- %g vs %g",
              angles[i], mean, se, total[0]);
  }
  ss_bssrdf_destroy(b);
}

typedef struct {
  const ss_bssrdf *b;
  double dist;
} length_ctx;

static int length_sample(void *vctx, double u1, double u2, double *x) {
  length_ctx *c = vctx;
  double pdf;
  return ss_fwddip_sample_length(c->b, 0, c->dist, u1, u2, x, &pdf);
}

static double length_pdf(void *vctx, double x) {
  length_ctx *c = vctx;
  return ss_fwddip_pdf_length(c->b, 0, c->dist, x);
}

/* The length sampler against its pdf over 60 log-spaced cells of s, for an
 * entry at the exit point, one and ten reduced mean free paths away, with
 * and without absorption (then the long-path law is Levy's). */
Test(fwddip_sample, length_sampler_passes_chi_square_against_its_pdf) {
  const double sigma_a[] = {0.01, 0.0}, dist[] = {0.0, 10.0, 100.0};
  for (int a = 0; a < 2; ++a) {
    ss_bssrdf *b = make_gray("fwddip", 1.0, 1.0 + sigma_a[a], 1.0, 0.9);
    for (int d = 0; d < 3; ++d) {
      length_ctx c = {b, dist[d]};
      enum { N = 60 };
      double edges[N + 1];
      for (int i = 0; i <= N; ++i) {
        edges[i] = 1e-5 * pow(1e19, (double)i / N); /* Levy tails reach far */
      }
      ss_chi2_result res;
      ss_chi2_test_1d(length_sample, length_pdf, &c, edges, N, 200000, 90 + 3 * a + d, &res);
      cr_expect(res.p_value > ss_chi2_sidak_alpha(0.01, 6), "sigma_a %g dist %g: %s (p %g)",
                sigma_a[a], dist[d], res.message, res.p_value);
      cr_expect(fabs(res.pdf_integral - 1.0) < 2e-3, "pdf integrates to %g", res.pdf_integral);
    }
    ss_bssrdf_destroy(b);
  }
}

typedef struct {
  const ss_bssrdf *b;
  double s;
  ss_vec3 x_o, wo_e;
} direction_ctx;

static int direction_sample(void *vctx, double u1, double u2, double u3, ss_vec3 *dir) {
  direction_ctx *c = vctx;
  double pdf;
  (void)u3;
  return ss_fwddip_sample_direction(c->b, 0, c->s, c->x_o, c->wo_e, ss_vec3_make(0, 0, 0), u1, u2,
                                    dir, &pdf);
}

static double direction_pdf(void *vctx, ss_vec3 dir) {
  direction_ctx *c = vctx;
  return ss_fwddip_pdf_direction(c->b, 0, c->s, c->x_o, c->wo_e, ss_vec3_make(0, 0, 0), dir);
}

/* The entry direction sampler against its pdf, from a broad lobe (long
 * path) to a narrow one (short path along the displacement). */
Test(fwddip_sample, direction_sampler_passes_chi_square_against_its_pdf) {
  ss_bssrdf *b = make_gray("fwddip", 1.0 / 1.01, 1.01, 1.0, 0.9);
  const double s[] = {50.0, 5.0, 1.2};
  for (int i = 0; i < 3; ++i) {
    direction_ctx c = {b, s[i], ss_vec3_make(1.0, 0.0, 0.0),
                       ss_vec3_normalize(ss_vec3_make(1.0, 0.0, 0.3))};
    ss_chi2_sphere_options o;
    ss_chi2_sphere_options_default(&o);
    o.seed = 95 + (uint64_t)i;
    ss_chi2_result res;
    ss_chi2_test_sphere(direction_sample, direction_pdf, &c, &o, &res);
    cr_expect(res.p_value > ss_chi2_sidak_alpha(0.01, 3), "s %g: %s (p %g)", s[i], res.message,
              res.p_value);
    cr_expect(fabs(res.pdf_integral - 1.0) < 1e-3, "pdf integrates to %g", res.pdf_integral);
  }
  ss_bssrdf_destroy(b);
}

/* int ds int dw' G_f(s, x_o, w_o, 0, w') with the w' integral in closed form
 * (int e^{w'.h} dw' = 4 pi sinh|h|/|h|), as a function of s. */
typedef struct {
  ss_fwddip_medium m;
  ss_vec3 x_o, w_o;
} marginal_ctx;

static double log_marginal(const marginal_ctx *c, const ss_fwddip_coeffs *k, double s) {
  ss_vec3 r = ss_vec3_scale(c->x_o, c->m.p);
  ss_vec3 h = ss_vec3_sub(ss_vec3_scale(r, k->E), ss_vec3_scale(c->w_o, k->D));
  double kappa = ss_vec3_length(h);
  double log_sinhc = kappa > 1e-8 ? kappa + log1p(-exp(-2.0 * kappa)) - log(2.0 * kappa) : 0.0;
  return c->m.log_p3 + k->log_norm - c->m.sigma_a * s + k->E * ss_vec3_dot(r, c->w_o) -
         k->F * ss_vec3_length2(r) + log(4.0 * SS_PI) + log_sinhc;
}

static double marginal(void *vctx, const ss_fwddip_coeffs *k, double s) {
  return exp(log_marginal(vctx, k, s));
}

/* The estimator of eq. 16's inner integrals, G_f / (pdf_s pdf_w') with s
 * and w' drawn by the samplers, converges to the quadrature (4 standard
 * errors), for an exit one and five reduced mean free paths away. */
Test(fwddip_sample, sampled_length_and_direction_estimate_the_propagator_integral) {
  ss_bssrdf *b = make_gray("fwddip", 1.0 / 1.01, 1.01, 1.0, 0.9);
  marginal_ctx c = {.m = ss_fwddip_medium_make(0.1, 0.01)};
  const double dist[] = {10.0, 50.0};
  ss_rng rng;
  ss_rng_seed(&rng, 8, 7);
  for (int d = 0; d < 2; ++d) {
    c.x_o = ss_vec3_make(dist[d], 0.0, 0.0);
    c.w_o = ss_vec3_normalize(ss_vec3_make(1.0, 0.0, 0.5));
    double want = ss_fwddip_integrate_s(&c.m, marginal, &c, dist + d, 1, 1e-8);
    double sum = 0.0, sum2 = 0.0;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
      double s, ps, pw;
      ss_vec3 w;
      double v = 0.0;
      if (ss_fwddip_sample_length(b, 0, dist[d], ss_rng_uniform(&rng), ss_rng_uniform(&rng), &s,
                                  &ps) &&
          ss_fwddip_sample_direction(b, 0, s, c.x_o, c.w_o, ss_vec3_make(0, 0, 0),
                                     ss_rng_uniform(&rng), ss_rng_uniform(&rng), &w, &pw)) {
        v = ss_fwddip_gf(&c.m, s, c.x_o, c.w_o, ss_vec3_make(0, 0, 0), w) / (ps * pw);
      }
      sum += v;
      sum2 += v * v;
    }
    double mean = sum / n, se = sqrt((sum2 / n - mean * mean) / n);
    cr_expect(fabs(mean - want) < 4.0 * se, "dist %g: %g +- %g vs %g", dist[d], mean, se, want);
    cr_expect(se < 0.05 * want, "dist %g: relative standard error %g", dist[d], se / want);
  }
  ss_bssrdf_destroy(b);
}

typedef struct {
  const ss_bssrdf *b;
  ss_bssrdf_sample_ctx ctx;
} entry_ctx;

static int entry_sample(void *vctx, double u1, double u2, double u3, double *r, double *phi) {
  entry_ctx *c = vctx;
  ss_bssrdf_entry e;
  (void)u3;
  if (!ss_bssrdf_sample_entry(c->b, &c->ctx, 0, u1, u2, &e)) {
    return 0;
  }
  *r = e.r;
  *phi = e.phi;
  return 1;
}

/* Density per unit r and phi: the area density times r. */
static double entry_pdf(void *vctx, double r, double phi) {
  entry_ctx *c = vctx;
  return r * ss_bssrdf_pdf_entry(c->b, &c->ctx, 0, r, phi);
}

/* The entry sampler in (r, phi) for a known oblique exit direction (the
 * azimuth leans upstream) and for normal exit (uniform azimuth). */
Test(fwddip_sample, entry_sampler_passes_chi_square_in_radius_and_azimuth) {
  ss_bssrdf *b = make_gray("fwddip", 1.0 / 1.01, 1.01, 1.33, 0.9);
  const double theta[] = {80.0, 30.0, 0.0};
  for (int i = 0; i < 3; ++i) {
    entry_ctx c = {b, default_sample_ctx()};
    c.ctx.w = ss_vec3_make(sin(theta[i] * SS_PI / 180.0), 0.0, cos(theta[i] * SS_PI / 180.0));
    enum { NR = 30, NP = 36 };
    double r_edges[NR + 1], p_edges[NP + 1], rmax = ss_bssrdf_max_radius(b, 0);
    for (int k = 0; k <= NR; ++k) {
      r_edges[k] = k == 0 ? 0.0 : 1e-4 * rmax * pow(2e4, (k - 1.0) / (NR - 1));
    }
    for (int k = 0; k <= NP; ++k) {
      p_edges[k] = 2.0 * SS_PI * k / NP;
    }
    ss_chi2_result res;
    ss_chi2_test_2d(entry_sample, entry_pdf, &c, r_edges, NR, p_edges, NP, 400000, 99 + i, &res);
    cr_expect(res.p_value > ss_chi2_sidak_alpha(0.01, 3), "theta %g: %s (p %g)", theta[i],
              res.message, res.p_value);
    cr_expect(fabs(res.pdf_integral - 1.0) < 2e-3, "pdf integrates to %g", res.pdf_integral);
    ss_bssrdf_entry e;
    for (int k = 0; k < 50; ++k) {
      double u1 = (k + 0.5) / 50.0, u2 = fmod(0.618034 * k, 1.0);
      cr_assert(ss_bssrdf_sample_entry(b, &c.ctx, 0, u1, u2, &e));
      double p = ss_bssrdf_pdf_entry(b, &c.ctx, 0, e.r, e.phi);
      cr_expect(fabs(e.pdf - p) <= 1e-9 * p, "sample pdf %g vs pdf_entry %g", e.pdf, p);
    }
  }
  ss_bssrdf_destroy(b);
}

typedef struct {
  const ss_bssrdf *b;
  ss_vec3 x_o, w;
} directed_ctx;

static int directed_sample(void *vctx, double u1, double u2, double *x) {
  directed_ctx *c = vctx;
  double pdf;
  return ss_fwddip_sample_length_directed(c->b, 0, c->x_o, c->w, ss_vec3_make(0, 0, 0), c->w, u1,
                                          u2, x, &pdf);
}

static double directed_pdf(void *vctx, double x) {
  directed_ctx *c = vctx;
  return ss_fwddip_pdf_length_directed(c->b, 0, c->x_o, c->w, ss_vec3_make(0, 0, 0), c->w, x);
}

typedef struct {
  ss_fwddip_medium m;
  ss_vec3 x_o, w;
} fixed_ctx;

static double fixed_directions(void *vctx, const ss_fwddip_coeffs *k, double s) {
  fixed_ctx *c = vctx;
  return exp(ss_fwddip_log_gf(&c->m, k, s, c->x_o, c->w, ss_vec3_make(0, 0, 0), c->w));
}

/* The next-event length sampler: chi-square against its pdf, and for both
 * directions 5.7 deg off a short displacement (p |R| = 0.01) its estimator
 * of int G_f ds matches quadrature (4 standard errors); the undirected
 * sampler's variance is reported beside it in the message. */
Test(fwddip_sample, directed_length_sampler_passes_chi_square_and_estimates_the_integral) {
  ss_bssrdf *b = make_gray("fwddip", 1.0 / 1.01, 1.01, 1.0, 0.9);
  ss_vec3 w = ss_vec3_normalize(ss_vec3_make(1.0, 0.0, 0.1));
  directed_ctx c = {b, ss_vec3_make(0.2, 0.0, 0.0), w};
  enum { N = 60 };
  double edges[N + 1];
  for (int i = 0; i <= N; ++i) {
    edges[i] = 1e-5 * pow(1e19, (double)i / N);
  }
  ss_chi2_result res;
  ss_chi2_test_1d(directed_sample, directed_pdf, &c, edges, N, 200000, 97, &res);
  cr_expect(res.p_value > 0.01, "%s (p %g)", res.message, res.p_value);
  cr_expect(fabs(res.pdf_integral - 1.0) < 2e-3, "pdf integrates to %g", res.pdf_integral);

  fixed_ctx f = {ss_fwddip_medium_make(0.1, 0.01), c.x_o, w};
  double peak_s = 0.2, want = ss_fwddip_integrate_s(&f.m, fixed_directions, &f, &peak_s, 1, 1e-9);
  ss_rng rng;
  ss_rng_seed(&rng, 8, 9);
  double mean[2], var[2];
  const int n = 20000;
  for (int j = 0; j < 2; ++j) {
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
      double s, pdf, u1 = ss_rng_uniform(&rng), u2 = ss_rng_uniform(&rng), v = 0.0;
      int ok = j == 0 ? ss_fwddip_sample_length_directed(b, 0, c.x_o, w, ss_vec3_make(0, 0, 0), w,
                                                         u1, u2, &s, &pdf)
                      : ss_fwddip_sample_length(b, 0, 0.2, u1, u2, &s, &pdf);
      if (ok) {
        v = ss_fwddip_gf(&f.m, s, c.x_o, w, ss_vec3_make(0, 0, 0), w) / pdf;
      }
      sum += v;
      sum2 += v * v;
    }
    mean[j] = sum / n;
    var[j] = sum2 / n - mean[j] * mean[j];
  }
  double se = sqrt(var[0] / n);
  cr_expect(fabs(mean[0] - want) < 4.0 * se,
            "directed: %g +- %g vs %g (variance per sample %g; undirected %g)", mean[0], se, want,
            var[0], var[1]);
  ss_bssrdf_destroy(b);
}
