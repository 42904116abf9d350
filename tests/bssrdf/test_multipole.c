#include "bssrdf/bssrdf_test_util.h"
#include "bssrdf/multipole.h"

static ss_bssrdf *make_slab(double alpha, double eta, double d) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, alpha, 1.0 - alpha, 0.0);
  p.eta = eta;
  ss_error err;
  cr_assert_eq(ss_bssrdf_params_set_option_number(&p, ss_bssrdf_model_find("multipole"),
                                                  "thickness", d, &err),
               SS_OK, "%s", err.message);
  ss_bssrdf *b = NULL;
  cr_assert_eq(ss_bssrdf_create("multipole", &p, &b, &err), SS_OK, "%s", err.message);
  return b;
}

/* Raw totals R and T per unit power entering (Fresnel factors divided out). */
static void raw_totals(ss_bssrdf *b, double eta, double *R, double *T) {
  double rd[3], t[3];
  ss_bssrdf_rd(b, rd);
  ss_bssrdf_total_transmittance(b, 1.0, t);
  *R = rd[0];
  *T = t[0] / ((1.0 - ss_fresnel_dielectric(1.0, eta)) * ss_fresnel_transmission_out(eta));
}

/* Donner & Jensen 2005, eq. 12: the i = 0 pair alone is the dipole. */
Test(multipole, single_pair_is_the_dipole) {
  ss_bssrdf *dip = make_gray("dipole", 0.9, 1.0, 1.3, 0.0);
  ss_bssrdf_coeffs k = ss_bssrdf_coeffs_make(0.9, 0.1, 0.0);
  ss_multipole m;
  ss_multipole_setup(&m, k, 3.0, ss_fresnel_A(1.3), ss_fresnel_A(1.3), 100);
  cr_assert_gt(m.n, 0);
  m.n = 0;
  for (double r = 0.0; r < 10.0; r += 0.37) {
    ss_bssrdf_profile_value v;
    ss_bssrdf_profile(dip, 0, r, &v);
    double mp = ss_multipole_reflectance(&m, r);
    cr_expect(fabs(mp - v.value) <= 1e-13 * v.value, "r %g: %g vs %g", r, mp, v.value);
  }
  ss_bssrdf_destroy(dip);
}

Test(multipole, half_space_is_the_dipole) {
  ss_bssrdf *dip = make_gray("dipole", 0.95, 1.0, 1.4, 0.0);
  ss_bssrdf *mp = make_slab(0.95, 1.4, INFINITY);
  double a[3], b[3];
  ss_bssrdf_rd(dip, a);
  ss_bssrdf_rd(mp, b);
  cr_expect(fabs(a[0] - b[0]) < 1e-14);
  ss_bssrdf_total_transmittance(mp, 1.0, b);
  cr_expect_eq(b[0], 0.0);
  ss_bssrdf_destroy(dip);
  ss_bssrdf_destroy(mp);
}

Test(multipole, profile_integrates_to_the_closed_form_totals) {
  ss_bssrdf *b = make_slab(0.99, 1.3, 2.5);
  double R, T, sr = 0.0, st = 0.0;
  raw_totals(b, 1.3, &R, &T);
  /* midpoint rule in r on a fine grid; the profile varies on scale 1 */
  for (double r = 0.0005; r < 400.0; r += 0.001) {
    ss_bssrdf_profile_value v;
    ss_bssrdf_profile(b, 0, r, &v);
    sr += 2.0 * SS_PI * r * v.value * 0.001;
    st += 2.0 * SS_PI * r * v.t * 0.001;
  }
  cr_expect(fabs(sr - R) < 1e-4 * R, "R %.6f vs %.6f", sr, R);
  cr_expect(fabs(st - T) < 1e-4 * T, "T %.6f vs %.6f", st, T);
  ss_bssrdf_destroy(b);
}

/* Thick limit: the slab becomes the half-space (R -> dipole, T -> 0); thin
 * limit: light leaks through, so R falls below the dipole and T grows as d
 * shrinks toward the source depth. */
Test(multipole, thick_and_thin_slab_limits) {
  ss_bssrdf *dip = make_gray("dipole", 0.99, 1.0, 1.3, 0.0);
  double rd[3];
  ss_bssrdf_rd(dip, rd);
  double sigma_tr = sqrt(3.0 * 0.01);
  double R, T;
  ss_bssrdf *thick = make_slab(0.99, 1.3, 60.0 / sigma_tr);
  raw_totals(thick, 1.3, &R, &T);
  cr_expect(fabs(R - rd[0]) < 1e-6, "thick R %.8f vs dipole %.8f", R, rd[0]);
  cr_expect(T < 1e-6, "thick T %g", T);
  ss_bssrdf_destroy(thick);
  const double ds[] = {20.0, 10.0, 5.0, 3.0, 2.0};
  double prev_R = rd[0], prev_T = 0.0;
  for (int i = 0; i < 5; ++i) {
    ss_bssrdf *b = make_slab(0.99, 1.3, ds[i]);
    raw_totals(b, 1.3, &R, &T);
    cr_expect(R < prev_R && T > prev_T, "d %g: R %.5f (prev %.5f) T %.5f (prev %.5f)", ds[i], R,
              prev_R, T, prev_T);
    cr_expect(R + T <= 1.0 + 0.02, "d %g: R + T = %.5f", ds[i], R + T);
    prev_R = R;
    prev_T = T;
    ss_bssrdf_destroy(b);
  }
  ss_bssrdf_destroy(dip);
}

/* Without absorption everything entering leaves through one face; the
 * diffusion approximation keeps R + T = 1 to a few per cent. */
Test(multipole, non_absorbing_slab_conserves_energy) {
  const double ds[] = {1.5, 3.0, 10.0, 30.0};
  const double etas[] = {1.0, 1.4};
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 4; ++i) {
      ss_bssrdf *b = make_slab(1.0 - 1e-7, etas[j], ds[i]);
      double R, T;
      raw_totals(b, etas[j], &R, &T);
      cr_expect(fabs(R + T - 1.0) < 0.03, "eta %g d %g: R %.4f T %.4f sum %.4f", etas[j], ds[i], R,
                T, R + T);
      ss_bssrdf_destroy(b);
    }
  }
}

/* At d = 1/sigma_t' the real source lies on the bottom face: half of its
 * flux crosses it, as in the limit d -> 1/sigma_t' from above (T must not
 * jump; it fell from 0.45 to 0.036 when the face source was dropped). */
Test(multipole, slab_at_the_source_depth_is_the_limit_from_thicker_slabs) {
  const double d = 1.0; /* sigma_t' = 0.9 + 0.1 */
  double R, T, R_lim, T_lim;
  ss_bssrdf *at = make_slab(0.9, 1.33, d);
  ss_bssrdf *above = make_slab(0.9, 1.33, d * (1.0 + 1e-12));
  raw_totals(at, 1.33, &R, &T);
  raw_totals(above, 1.33, &R_lim, &T_lim);
  cr_expect(fabs(T - T_lim) <= 1e-9, "T %.12f vs limit %.12f", T, T_lim);
  cr_expect(fabs(R - R_lim) <= 1e-9, "R %.12f vs limit %.12f", R, R_lim);
  cr_expect(T > 0.45, "T %.6f: the source's transmitted half is missing", T);
  ss_bssrdf_destroy(at);
  ss_bssrdf_destroy(above);
}

Test(multipole, too_thin_slab_is_rejected) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  ss_bssrdf_params_set_gray(&p, 0.9, 0.1, 0.0);
  const ss_bssrdf_ops *ops = ss_bssrdf_model_find("multipole");
  ss_error err;
  cr_assert_eq(ss_bssrdf_params_set_option(&p, ops, "thickness", "0.5", &err), SS_OK);
  ss_bssrdf *b = NULL;
  cr_expect_eq(ss_bssrdf_create("multipole", &p, &b, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "thickness") != NULL, "%s", err.message);
  cr_expect_eq(ss_bssrdf_params_set_option(&p, ops, "thickness", "-1", &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "multipole: option thickness") != NULL, "%s", err.message);
}
