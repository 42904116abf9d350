/* The exact half-space profile table: reading with its checksum, evaluation
 * between its bins and curves, and the shipped table against the
 * half-space reference. */
#include "subsurf/bssrdf.h"
#include "subsurf/halfspace.h"
#include "subsurf/profile_fit.h"
#include "subsurf/profile_table.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#define N_U 4
#define N_BINS 24

static const double grid_u[N_U] = {0.1, 0.2, 0.3, 0.5};

static ss_bssrdf *dipole(double alpha_prime) {
  ss_bssrdf_params bp;
  ss_bssrdf_params_default(&bp);
  ss_bssrdf_params_set_gray(&bp, alpha_prime, 1.0 - alpha_prime, 0.0);
  bp.eta = 1.3;
  ss_bssrdf *b;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("dipole", &bp, &b, &err), SS_OK, "%s", err.message);
  return b;
}

/* A table in the shipped format whose curves are the dipole's own annulus
 * averages over wide log bins from 0.1 to 50 mean free paths, with its
 * checksum; malloc'd. */
static char *dipole_table_text(size_t *size) {
  size_t cap = 64 * 1024, len = 0;
  char *t = malloc(cap);
  cr_assert_not_null(t);
  len +=
      (size_t)snprintf(t + len, cap - len,
                       "# a test table\nsubsurf-profile-table 1\neta 1.3\ng 0\npaths 1\nu %d", N_U);
  for (int k = 0; k < N_U; ++k) {
    len += (size_t)snprintf(t + len, cap - len, " %g", grid_u[k]);
  }
  double edges[N_BINS + 1];
  len += (size_t)snprintf(t + len, cap - len, "\nrho %d", N_BINS + 1);
  for (int i = 0; i <= N_BINS; ++i) {
    edges[i] = 0.1 * pow(500.0, (double)i / N_BINS);
    len += (size_t)snprintf(t + len, cap - len, " %.17g", edges[i]);
  }
  for (int k = 0; k < N_U; ++k) {
    ss_bssrdf *b = dipole(1.0 - grid_u[k] * grid_u[k]);
    double m[N_BINS][SS_BSSRDF_CHANNELS];
    len += (size_t)snprintf(t + len, cap - len, "\ncurve %g", grid_u[k]);
    for (int i = 0; i < N_BINS; ++i) {
      ss_bssrdf_radial_average(b, 1.0, edges[i], edges[i + 1], m[i]);
      len += (size_t)snprintf(t + len, cap - len, " %.17g", m[i][0]);
    }
    for (int i = 0; i < N_BINS; ++i) {
      len += (size_t)snprintf(t + len, cap - len, " %.17g", 1e-3 * m[i][0]);
    }
    ss_bssrdf_destroy(b);
  }
  len += (size_t)snprintf(t + len, cap - len, "\n");
  uLong crc = crc32(crc32(0L, Z_NULL, 0), (const Bytef *)t, (uInt)len);
  len += (size_t)snprintf(t + len, cap - len, "crc32 %08lx\n", crc);
  cr_assert_lt(len, cap);
  *size = len;
  return t;
}

/* A table of the dipole's annulus averages evaluates to the dipole's point
 * values, on a curve and between curves, where a bin spans several
 * diffusion lengths (dividing the bins by the dipole's value at their
 * centres instead of its average over them is off by a factor 2 there). */
Test(profile_table, evaluates_point_values_of_annulus_averaged_curves) {
  size_t size;
  char *text = dipole_table_text(&size);
  ss_profile_table *t;
  ss_error err;
  cr_assert_eq(ss_profile_table_parse(text, size, "test", &t, &err), SS_OK, "%s", err.message);
  const double us[] = {0.3, 0.25, 0.42};
  for (int k = 0; k < 3; ++k) {
    double ap = 1.0 - us[k] * us[k];
    ss_bssrdf *b = dipole(ap);
    for (double rho = 0.3; rho < 40.0; rho *= 1.37) {
      double got, want[SS_BSSRDF_CHANNELS];
      ss_profile_table_eval(t, ap, &rho, 1, &got);
      ss_bssrdf_exitance(b, 1.0, rho, 0.0, want);
      cr_expect(fabs(got / want[0] - 1.0) < 2e-3, "u %g, rho %g: %g against the dipole's %g", us[k],
                rho, got, want[0]);
    }
    ss_bssrdf_destroy(b);
  }
  double lo, hi;
  ss_profile_table_albedo_range(t, &lo, &hi);
  cr_expect(fabs(lo - 0.75) < 1e-12 && fabs(hi - 0.99) < 1e-12, "range %g %g", lo, hi);
  ss_profile_table_destroy(t);
  free(text);
}

static void expect_parse_error(const char *text, size_t size, const char *needle) {
  ss_profile_table *t;
  ss_error err;
  cr_expect_eq(ss_profile_table_parse(text, size, "t.txt", &t, &err), SS_ERR_PARSE, "'%s'", needle);
  cr_expect(strstr(err.message, needle) != NULL, "'%s' lacks '%s'", err.message, needle);
  cr_expect_null(t);
}

/* A changed byte, a cut file and a bad line are refused, naming the file
 * (and the line where the checksum holds). */
Test(profile_table, refuses_corrupt_tables) {
  size_t size;
  char *text = dipole_table_text(&size);
  char *bad = malloc(size + 64);
  memcpy(bad, text, size);
  char *eta = strstr(bad, "eta 1.3");
  eta[6] = '4';
  expect_parse_error(bad, size, "t.txt: checksum mismatch");
  expect_parse_error(text, size - 20, "t.txt: truncated or not a table");
  /* a valid checksum over a table whose eta line is bad */
  memcpy(bad, text, size);
  eta = strstr(bad, "eta 1.3");
  eta[4] = 'x';
  size_t body = (size_t)(strstr(bad, "crc32 ") - bad);
  uLong crc = crc32(crc32(0L, Z_NULL, 0), (const Bytef *)bad, (uInt)body);
  snprintf(bad + body, 64, "crc32 %08lx\n", crc);
  expect_parse_error(bad, strlen(bad), "t.txt:3: expected 'eta X'");
  free(bad);
  free(text);
}

/* The shipped table, averaged over the reference's bins, against a
 * half-space reference run of a medium between its curves (alpha' 0.95,
 * eta 1.3, g 0) from 0.3 to 10 mean free paths: within 4 combined standard
 * errors plus 2 % (the table's interpolation). */
Test(profile_table, shipped_table_matches_the_reference) {
  const double sigma_s = 1.9, sigma_a = 0.1; /* alpha' 0.95, sigma_t' 2 */
  ss_halfspace_params hp;
  ss_halfspace_params_default(&hp);
  hp.medium = ss_medium_optics_gray(sigma_s, sigma_a, 0.0, SS_PHASE_HG);
  hp.eta = 1.3;
  hp.paths = 200000;
  hp.seed = 7;
  hp.rmin = 0.15;
  hp.rmax = 5.0;
  hp.rbins = 21;
  hp.xbins = hp.ybins = 1;
  ss_halfspace_result *h;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(&hp, &h, &err), SS_OK, "%s", err.message);
  ss_fit_params p;
  ss_fit_params_default(&p);
  int compared = 0;
  for (int i = 1; i < hp.rbins; ++i) {
    double r = sqrt(h->r_lo[i] * h->r_hi[i]), m;
    cr_assert_eq(ss_fit_eval(&p, sigma_a, sigma_s, 1.0, &r, &h->r_lo[i], &h->r_hi[i], 1, &m, &err),
                 SS_OK, "%s", err.message);
    double ref = h->radial[i].value, e = h->radial[i].error;
    cr_expect(fabs(m - ref) < 4.0 * e + 0.02 * ref, "r %g: table %g, reference %g +- %g", r, m, ref,
              e);
    compared++;
  }
  cr_expect_eq(compared, 20);
  ss_halfspace_result_destroy(h);
}
