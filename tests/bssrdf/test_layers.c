#include "bssrdf/bssrdf_test_util.h"
#include "subsurf/bssrdf_layers.h"

/* Params whose "layers" option is the given stack, written as text. */
static ss_bssrdf_params stack_params(int n, const ss_bssrdf_layer *layers) {
  ss_bssrdf_layer_stack s;
  memset(&s, 0, sizeof s);
  s.layer_count = n;
  memcpy(s.layers, layers, (size_t)n * sizeof *layers);
  char text[SS_OPTION_TEXT];
  cr_assert(ss_bssrdf_layer_stack_format(&s, text, sizeof text) < (int)sizeof text);
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_error err;
  cr_assert_eq(
      ss_bssrdf_params_set_option(&p, ss_bssrdf_model_find("layers"), "layers", text, &err), SS_OK,
      "%s", err.message);
  return p;
}

static ss_bssrdf *make_stack(int n, const ss_bssrdf_layer *layers) {
  ss_bssrdf_params p = stack_params(n, layers);
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("layers", &p, &b, &err), SS_OK, "%s", err.message);
  return b;
}

static ss_bssrdf_layer gray_layer(double ss, double sa, double eta, double d) {
  ss_bssrdf_layer l;
  for (int c = 0; c < 3; ++c) {
    l.sigma_s[c] = ss;
    l.sigma_a[c] = sa;
    l.g[c] = 0.0;
  }
  l.eta = eta;
  l.thickness = d;
  return l;
}

/* One layer is the multipole itself: same totals exactly, profile within the
 * grid's resolution. */
Test(layers, one_layer_is_the_multipole) {
  ss_bssrdf_layer l = gray_layer(0.9, 0.1, 1.3, 2.0);
  ss_bssrdf *b = make_stack(1, &l);
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, 0.9, 0.1, 0.0);
  cr_assert_eq(
      ss_bssrdf_params_set_option(&p, ss_bssrdf_model_find("multipole"), "thickness", "2", NULL),
      SS_OK);
  ss_bssrdf *m = NULL;
  cr_assert_eq(ss_bssrdf_create("multipole", &p, &m, NULL), SS_OK);
  double r1[3], r2[3];
  ss_bssrdf_rd(b, r1);
  ss_bssrdf_rd(m, r2);
  cr_expect(fabs(r1[0] - r2[0]) < 1e-9, "%g vs %g", r1[0], r2[0]);
  ss_bssrdf_total_transmittance(b, 1.0, r1);
  ss_bssrdf_total_transmittance(m, 1.0, r2);
  cr_expect(fabs(r1[0] - r2[0]) < 1e-9, "%g vs %g", r1[0], r2[0]);
  for (double r = 0.2; r < 8.0; r *= 2.0) {
    ss_bssrdf_profile_value a, c;
    ss_bssrdf_profile(b, 0, r, &a);
    ss_bssrdf_profile(m, 0, r, &c);
    cr_expect(fabs(a.value - c.value) < 0.03 * c.value, "r %g: %g vs %g", r, a.value, c.value);
  }
  ss_bssrdf_destroy(b);
  ss_bssrdf_destroy(m);
}

/* DonnerJensen2005's skin (Table 3, the default stack): every channel reflects a plausible,
 * energy-conserving amount, red most and blue least (blood absorbs blue). */
Test(layers, skin_totals_conserve_energy) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("layers", &p, &b, &err), SS_OK, "%s", err.message);
  /* the default stack, restated to derive the sampler's grid below */
  const ss_bssrdf_layer skin[3] = {
      {{48.0, 60.0, 65.0}, {2.1, 2.1, 5.0}, {0.0, 0.0, 0.0}, 1.4, 0.03},
      {{32.0, 40.0, 46.0}, {0.16, 0.19, 0.30}, {0.25, 0.25, 0.25}, 1.34, 0.05},
      {{4.5, 4.7, 4.8}, {0.085, 1.0, 25.0}, {0.8, 0.8, 0.8}, 1.4, INFINITY},
  };
  double R[3], T[3], tot[3];
  ss_bssrdf_rd(b, R);
  ss_bssrdf_total_transmittance(b, 1.0, T);
  ss_bssrdf_total_reflectance(b, 1.0, tot);
  for (int c = 0; c < 3; ++c) {
    cr_expect(R[c] > 0.05 && R[c] + T[c] <= 1.0, "channel %d: R %g T %g", c, R[c], T[c]);
    cr_expect(T[c] == 0.0, "semi-infinite bottom transmits %g", T[c]);
    cr_expect(tot[c] < 1.0 - ss_fresnel_dielectric(1.0, 1.4));
  }
  cr_expect(R[0] > R[1] && R[1] > R[2], "R %g %g %g", R[0], R[1], R[2]);
  for (int c = 0; c < 3; ++c) {
    /* The sampler's density is constant on the annuli [(k - 1/2) h, (k + 1/2) h)
     * of layers.c's grid, h = 24 / (512 rate) with rate the slowest layer's
     * max(sigma_tr, 1e-3 sigma_t'); bin edges on those boundaries make the
     * harness's integral of the density exact. */
    double rate = INFINITY;
    for (int k = 0; k < 3; ++k) {
      ss_bssrdf_coeffs co =
          ss_bssrdf_coeffs_make(skin[k].sigma_s[c], skin[k].sigma_a[c], skin[k].g[c]);
      rate = fmin(rate, fmax(co.sigma_tr, 1e-3 * co.sigma_t_prime));
    }
    double h = 24.0 / (512.0 * rate), edges[61];
    int n = 0;
    edges[0] = 0.0;
    for (int k = 0; n < 60 && k < 256; k += 1 + k / 8) {
      edges[++n] = (k + 0.5) * h;
    }
    expect_radius_chi2_edges(b, c, 51 + c, edges, n);
  }
  ss_bssrdf_destroy(b);
}

/* Two non-absorbing slabs: everything that enters leaves through one of the
 * faces, as for each slab alone (multipole: to a few per cent). */
Test(layers, non_absorbing_stack_conserves_energy) {
  ss_bssrdf_layer l[2] = {gray_layer(2.0, 2e-7, 1.3, 1.0), gray_layer(1.0, 1e-7, 1.5, 3.0)};
  ss_bssrdf *b = make_stack(2, l);
  double R[3], T[3];
  ss_bssrdf_rd(b, R);
  ss_bssrdf_total_transmittance(b, 1.0, T);
  double t = T[0] / ((1.0 - ss_fresnel_dielectric(1.0, 1.3)) * ss_fresnel_transmission_out(1.3));
  cr_expect(fabs(R[0] + t - 1.0) < 0.05, "R %.4f T %.4f", R[0], t);
  ss_bssrdf_destroy(b);
}

Test(layers, bad_layers_are_rejected) {
  ss_bssrdf_layer l[2] = {gray_layer(1.0, 0.1, 1.3, INFINITY), gray_layer(1.0, 0.1, 1.3, 1.0)};
  ss_bssrdf_params p = stack_params(2, l);
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_expect_eq(ss_bssrdf_create("layers", &p, &b, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "layer 0") != NULL, "%s", err.message);
}

/* A layer exactly one reduced mean free path thick holds its multipole
 * source on its bottom face: the stack is the limit of slightly thicker
 * ones (half that source's flux goes down into the next layer). */
Test(layers, a_layer_at_its_source_depth_is_the_limit_of_thicker_ones) {
  ss_bssrdf_layer at[2] = {gray_layer(0.9, 0.1, 1.4, 1.0), gray_layer(2.0, 0.05, 1.3, 3.0)};
  ss_bssrdf_layer above[2] = {gray_layer(0.9, 0.1, 1.4, 1.0 + 1e-12), at[1]};
  ss_bssrdf *a = make_stack(2, at), *b = make_stack(2, above);
  double ra[3], rb[3], ta[3], tb[3];
  ss_bssrdf_rd(a, ra);
  ss_bssrdf_rd(b, rb);
  ss_bssrdf_total_transmittance(a, 1.0, ta);
  ss_bssrdf_total_transmittance(b, 1.0, tb);
  cr_expect(fabs(ra[0] - rb[0]) < 1e-9, "R %.12f vs limit %.12f", ra[0], rb[0]);
  cr_expect(fabs(ta[0] - tb[0]) < 1e-9, "T %.12f vs limit %.12f", ta[0], tb[0]);
  ss_bssrdf_destroy(a);
  ss_bssrdf_destroy(b);
}
