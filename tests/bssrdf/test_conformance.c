/* The contract of ss_bssrdf_ops, checked for every model in models.def (one
 * parameterised test per model, so a new model is tested by its line in the
 * registry): eval is finite and non-negative; sample_entry draws (r, phi)
 * with the density pdf_entry claims (chi-square over radius x azimuth cells,
 * and the pdf it returns is pdf_entry's); max_radius leaves at most 1e-4 of
 * the samples outside; the total reflectance at normal incidence equals the
 * exitance integrated over the plane; any radius, NaN, infinite, 1e300 or
 * negative included, is answered without reading outside a table, and
 * finitely where it is finite. Model-specific identities stay in each model's own test.
 * Some models are tested a second time with options set (option_sets).
 *
 * One known exception, measured and named below rather than skipped: the
 * `layers` model (see layered_tolerance). */
#include "bssrdf/bssrdf_test_util.h"

#include <criterion/parameterized.h>

typedef struct {
  const ss_bssrdf *b;
  int channel;
  ss_bssrdf_sample_ctx ctx;
} entry_ctx;

static int entry_sample(void *vctx, double u1, double u2, double u3, double *r, double *phi) {
  (void)u3;
  entry_ctx *c = vctx;
  ss_bssrdf_entry e;
  if (!ss_bssrdf_sample_entry(c->b, &c->ctx, c->channel, u1, u2, &e)) {
    return 0;
  }
  *r = e.r;
  *phi = e.phi;
  return 1;
}

/* Density per unit r x phi: r times the density per unit area. */
static double entry_pdf(void *vctx, double r, double phi) {
  entry_ctx *c = vctx;
  return r * ss_bssrdf_pdf_entry(c->b, &c->ctx, c->channel, r, phi);
}

/* The known end seen from a direction at polar angle theta (toward +x). */
static ss_bssrdf_sample_ctx ctx_at(double theta) {
  ss_bssrdf_sample_ctx c = default_sample_ctx();
  c.w = ss_vec3_make(sin(theta), 0.0, cos(theta));
  return c;
}

/* Models tested again with options set: {model, name, value, ..., NULL}
 * (the rough dielectric boundary of the forward scattering dipoles, with
 * a coarse rule to keep the exitance integral quick; the coarsest, one
 * u1 node, breaks the radial symmetry at normal incidence by 1e-2). */
#define MAX_OPTION_WORDS 8
static const char *const option_sets[][MAX_OPTION_WORDS] = {
    {"fwddip", "alpha", "0.3", "distribution", "ggx", "rough_nodes", "2", NULL},
    {"fwddip-brdf", "alpha", "0.3", "rough_nodes", "2", NULL},
};
#define N_OPTION_SETS (sizeof option_sets / sizeof option_sets[0])

/* A chromatic medium behind eta 1.33: albedo 0.9, 0.8 and 0.7 and
 * extinction 1, 1.5 and 0.7 per channel (the layers model carries its own skin
 * stack and ignores it); micro-flakes for the models that take them;
 * `options` as in option_sets without the model, or NULL. */
static ss_bssrdf *make_model(const ss_bssrdf_ops *ops, const char *const *options) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  p.medium.sigma_s = ss_rgb_make(0.9, 1.2, 0.49);
  p.medium.sigma_a = ss_rgb_make(0.1, 0.3, 0.21);
  p.eta = 1.33;
  if (ops->flags & SS_BSSRDF_FLAKES) {
    /* an oriented medium: fibre-like flakes about an axis tilted out of the
     * surface, so that the footprint is elliptical and off-centre */
    p.medium.flakes = (ss_medium_flakes){.type = SS_FLAKE_FIBER, .p = 20.0, .axis = {1, 0.5, 0.7}};
  }
  ss_bssrdf *b = NULL;
  ss_error err;
  for (; options && *options; options += 2) {
    cr_assert_eq(ss_bssrdf_params_set_option(&p, ops, options[0], options[1], &err), SS_OK,
                 "%s: %s", ops->name, err.message);
  }
  cr_assert_eq(ss_bssrdf_create_ops(ops, &p, &b, &err), SS_OK, "%s: %s", ops->name, err.message);
  return b;
}

static void expect_eval_finite_and_nonnegative(const ss_bssrdf *b) {
  ss_rng rng;
  ss_rng_seed(&rng, 3, 1);
  double scale = ss_bssrdf_max_radius(b, 0);
  for (int i = 0; i < 2000; ++i) {
    ss_bssrdf_query q;
    double r = scale * pow(ss_rng_uniform(&rng), 3.0), phi = 2.0 * SS_PI * ss_rng_uniform(&rng);
    q.x_i = ss_vec3_make(0, 0, 0);
    q.x_o = ss_vec3_make(r * cos(phi), r * sin(phi), 0.0);
    q.n_i = q.n_o = ss_vec3_make(0, 0, 1);
    q.w_i = ss_sample_uniform_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    q.w_o = ss_sample_uniform_hemisphere(ss_rng_uniform(&rng), ss_rng_uniform(&rng));
    double s[3];
    ss_bssrdf_eval(b, &q, s);
    for (int c = 0; c < 3; ++c) {
      cr_assert(isfinite(s[c]) && s[c] >= 0.0, "%s: S[%d] = %g at r %g", ss_bssrdf_name(b), c, s[c],
                r);
    }
  }
}

/* Radii whose ratio to any table's cell overflows an int, that square to
 * infinity, or that are not numbers: every entry point that takes a radius or
 * a position answers them finitely and without a cast or read outside a table
 * (which UBSan's float-cast-overflow and ASan see), and the tail (NaN, or not
 * below SS_BSSRDF_TAIL_RADIUS) with 0. */
static void expect_any_radius_is_answered(const ss_bssrdf *b) {
  const double radii[] = {NAN,  INFINITY, -INFINITY, 1e300, -1e300, 0.99 * SS_BSSRDF_TAIL_RADIUS,
                          1e12, -1e12,    -1.0,      0.0,   1e-300};
  ss_bssrdf_sample_ctx ctx = ctx_at(0.3);
  for (size_t i = 0; i < sizeof radii / sizeof radii[0]; ++i) {
    double r = radii[i], v[6][3];
    ss_bssrdf_profile_value prof;
    ss_bssrdf_profile(b, 0, r, &prof);
    ss_bssrdf_exitance(b, 1.0, r, 0.0, v[0]);
    ss_bssrdf_exitance(b, 0.6, 0.5, r, v[1]);
    ss_bssrdf_query q = ss_bssrdf_halfspace_query(1.0, r, 0.0, ss_vec3_make(0, 0, 1));
    ss_bssrdf_eval(b, &q, v[2]);
    ss_bssrdf_radiance_line(b, 0.8, r, ss_vec3_make(0.6, 0, 0.8), v[3]);
    ss_bssrdf_point_source_exitance(b, 0.5, r, v[4]);
    for (int c = 0; c < 3; ++c) {
      v[5][c] = ss_bssrdf_pdf_entry(b, &ctx, c, r, 1.0);
    }
    double sum = prof.value;
    for (int k = 0; k < 6; ++k) {
      for (int c = 0; c < 3; ++c) {
        cr_expect(isfinite(v[k][c]) && v[k][c] >= 0.0, "%s at r %g: answer %d channel %d is %g",
                  ss_bssrdf_name(b), r, k, c, v[k][c]);
        sum += fabs(v[k][c]);
      }
    }
    cr_expect(isfinite(prof.value), "%s at r %g: profile %g", ss_bssrdf_name(b), r, prof.value);
    if (!(fabs(r) < SS_BSSRDF_TAIL_RADIUS)) {
      cr_expect(sum == 0.0, "%s at r %g: the tail is not 0", ss_bssrdf_name(b), r);
    }
  }
}

/* Radius cells: [0, r0), then log-spaced to twice max_radius; 32 azimuth
 * cells of equal width, narrow enough for the 5-point rule of the harness to
 * integrate fwddip's wrapped-Cauchy azimuth about an oblique direction. */
static void expect_entry_density_is_pdf_entry(const ss_bssrdf *b, int channel, double theta,
                                              uint64_t seed) {
  enum { NR = 30, NPHI = 32 };
  entry_ctx c = {b, channel, ctx_at(theta)};
  double rmax = ss_bssrdf_max_radius(b, channel), r_edges[NR + 1], phi_edges[NPHI + 1];
  double r0 = rmax * 1e-4;
  r_edges[0] = 0.0;
  for (int i = 1; i <= NR; ++i) {
    r_edges[i] = r0 * pow(2.0 * rmax / r0, (double)(i - 1) / (NR - 1));
  }
  for (int j = 0; j <= NPHI; ++j) {
    phi_edges[j] = 2.0 * SS_PI * j / NPHI;
  }
  ss_chi2_result res;
  ss_chi2_test_2d(entry_sample, entry_pdf, &c, r_edges, NR, phi_edges, NPHI, 150000, seed, &res);
  /* a family of 3 tests (one per channel) per model, at 1% */
  cr_expect(res.p_value > ss_chi2_sidak_alpha(0.01, 3), "%s channel %d theta %g: %s (p %g)",
            ss_bssrdf_name(b), channel, theta, res.message, res.p_value);
  cr_expect(fabs(res.pdf_integral - 1.0) < 2e-3, "%s channel %d: pdf integrates to %g",
            ss_bssrdf_name(b), channel, res.pdf_integral);
}

/* u1 stratified over n values: the radius is monotone in u1 within each
 * mixture component, so the count beyond max_radius is the sampler's own
 * tail mass times n, up to one per component. */
static void expect_max_radius_covers_the_samples(const ss_bssrdf *b, int channel, double theta) {
  enum { N = 100000 };
  ss_bssrdf_sample_ctx ctx = ctx_at(theta);
  double rmax = ss_bssrdf_max_radius(b, channel);
  int beyond = 0, bad_pdf = 0;
  for (int i = 0; i < N; ++i) {
    double u1 = (i + 0.5) / N, u2 = fmod(0.6180339887498949 * i, 1.0);
    ss_bssrdf_entry e;
    if (!ss_bssrdf_sample_entry(b, &ctx, channel, u1, u2, &e)) {
      continue;
    }
    beyond += e.r > rmax;
    if (i % 100 == 0) {
      double p = ss_bssrdf_pdf_entry(b, &ctx, channel, e.r, e.phi);
      bad_pdf += !(fabs(e.pdf - p) <= 1e-9 * p);
    }
  }
  cr_expect(beyond <= 1e-4 * N + SS_RADIAL_MIX_MAX, "%s channel %d: %d of %d beyond %g",
            ss_bssrdf_name(b), channel, beyond, N, rmax);
  cr_expect_eq(bad_pdf, 0, "%s channel %d: %d of 1000 samples whose pdf is not pdf_entry's",
               ss_bssrdf_name(b), channel, bad_pdf);
}

/* `layers` tabulates its profile on the annuli of its FFT grid up to the
 * grid's inscribed circle, while its total is the grid's DC term: the
 * exitance misses the corners' share, 0.9 / 7.3 / 4.6 % per channel for the
 * skin stack (a defect of the model, reported). Its sampling density is
 * constant on those annuli, which the harness's Gauss-Legendre cells
 * integrate exactly only on aligned edges: test_layers.c tests it there. */
static int is_layers(const ss_bssrdf *b) { return !strcmp(ss_bssrdf_name(b), "layers"); }

static double layered_tolerance(const ss_bssrdf *b) { return is_layers(b) ? 0.08 : 1e-3; }

static void expect_total_is_the_integrated_exitance(const ss_bssrdf *b, double cos_i) {
  double total[3], integral[3];
  ss_bssrdf_total_reflectance(b, cos_i, total);
  integrate_exitance(b, cos_i, integral);
  for (int c = 0; c < 3; ++c) {
    cr_expect(isfinite(total[c]) && total[c] >= 0.0 && total[c] < 1.0, "%s: total %g",
              ss_bssrdf_name(b), total[c]);
    cr_expect(fabs(total[c] - integral[c]) <= layered_tolerance(b) * total[c] + 1e-12,
              "%s channel %d cos_i %g: total %.7g vs integrated exitance %.7g", ss_bssrdf_name(b),
              c, cos_i, total[c], integral[c]);
  }
}

/* Index i < the model count: model i with its defaults; beyond: the option
 * sets above. */
ParameterizedTestParameters(conformance, every_registered_model_keeps_the_interface_contract) {
  static size_t index[64];
  size_t n = ss_bssrdf_model_count() + N_OPTION_SETS;
  cr_assert(n <= sizeof index / sizeof index[0]);
  for (size_t i = 0; i < n; ++i) {
    index[i] = i;
  }
  return cr_make_param_array(size_t, index, n);
}

ParameterizedTest(size_t *i, conformance, every_registered_model_keeps_the_interface_contract) {
  size_t models = ss_bssrdf_model_count();
  const char *const *options = *i < models ? NULL : option_sets[*i - models];
  const ss_bssrdf_ops *ops = options ? ss_bssrdf_model_find(options[0]) : ss_bssrdf_model_at(*i);
  cr_assert_not_null(ops);
  ss_bssrdf *b = make_model(ops, options ? options + 1 : NULL);
  expect_eval_finite_and_nonnegative(b);
  expect_any_radius_is_answered(b);
  /* one direction at the known end per channel: normal, 40 and 75 degrees */
  const double thetas[3] = {0.0, 0.7, 1.3};
  if (!(ops->flags & SS_BSSRDF_BRDF)) {
    for (int c = 0; c < 3; ++c) {
      if (!is_layers(b)) {
        expect_entry_density_is_pdf_entry(b, c, thetas[c], 100 * *i + c);
      }
      expect_max_radius_covers_the_samples(b, c, thetas[c]);
    }
  }
  /* at normal incidence: oblique beams make the exitance of angular models a
   * 2D quadrature (fwddip: 100 s), left to the models' own tests */
  expect_total_is_the_integrated_exitance(b, 1.0);
  ss_bssrdf_destroy(b);
}
