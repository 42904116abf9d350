/* The measured presets are the papers' numbers: every Jensen et al. 2001 row
 * reproduces the paper's Rd column through the paper's own closed form, except
 * the rows listed below, and names are found case-insensitively. */
#include "subsurf/fresnel.h"
#include "subsurf/media.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

/* Jensen et al. 2001, eq. 11 (total diffuse reflectance of the dipole):
 * Rd = alpha'/2 (1 + exp(-(4/3) A sqrt(3 (1 - alpha')))) exp(-sqrt(3 (1 - alpha'))). */
static double dipole_rd(double sigma_s_prime, double sigma_a, double eta) {
  double alpha = sigma_s_prime / (sigma_s_prime + sigma_a);
  double s = sqrt(3.0 * (1.0 - alpha));
  return 0.5 * alpha * (1.0 + exp(-4.0 / 3.0 * ss_fresnel_A(eta) * s)) * exp(-s);
}

typedef struct {
  const char *name;
  double rd[3]; /* the paper's Rd column, two decimals */
} paper_rd;

/* Jensen2001 Fig. 5. */
static const paper_rd jensen_rd[] = {
    {"Apple", {0.85, 0.84, 0.53}},      {"Chicken1", {0.31, 0.15, 0.10}},
    {"Chicken2", {0.32, 0.16, 0.10}},   {"Cream", {0.98, 0.90, 0.73}},
    {"Ketchup", {0.16, 0.01, 0.00}},    {"Marble", {0.83, 0.79, 0.75}},
    {"Potato", {0.77, 0.62, 0.21}},     {"Skimmilk", {0.81, 0.81, 0.69}},
    {"Skin1", {0.44, 0.22, 0.13}},      {"Skin2", {0.63, 0.44, 0.34}},
    {"Spectralon", {1.00, 1.00, 1.00}}, {"Wholemilk", {0.91, 0.88, 0.76}},
};

/* The paper's values carry two decimals (rounding 0.005) and its own rounding
 * of Fdr; 0.01 allows both. */
#define RD_TOLERANCE 0.01

/* Rows that do not reproduce at eta 1.3, found by this test:
 * - Marble, all channels: the dipole gives 0.867 0.834 0.801 at eta 1.3
 *   against the paper's 0.83 0.79 0.75, and 0.830 0.791 0.753 at eta 1.5,
 *   the index Mitsuba stores for marble: the paper used 1.5 for this row.
 * - Chicken1, blue: its coefficients give Rd = 0.126 at eta 1.3 (0.123 at
 *   1.5) against the paper's 0.10; no index in [1, 2] reaches 0.10, so the
 *   printed coefficient or Rd has a typo. */
static int is_expected_exception(const char *name, int channel) {
  return !strcmp(name, "Marble") || (!strcmp(name, "Chicken1") && channel == 2);
}

Test(media, jensen_presets_reproduce_the_papers_rd_at_eta_1_3) {
  for (size_t i = 0; i < sizeof jensen_rd / sizeof jensen_rd[0]; ++i) {
    const ss_medium_preset *m = ss_medium_preset_find(jensen_rd[i].name);
    cr_assert_not_null(m, "%s missing", jensen_rd[i].name);
    cr_assert_eq(m->eta, 1.3, "%s: Jensen et al. measured with eta 1.3", m->name);
    for (int c = 0; c < 3; ++c) {
      double rd = dipole_rd(m->sigma_s_prime[c], m->sigma_a[c], 1.3);
      double diff = fabs(rd - jensen_rd[i].rd[c]);
      if (is_expected_exception(m->name, c)) {
        cr_assert_gt(diff, RD_TOLERANCE, "%s channel %d now matches (%.3f): update the list",
                     m->name, c, rd);
      } else {
        cr_assert_leq(diff, RD_TOLERANCE, "%s channel %d: dipole Rd %.4f, paper %.2f", m->name, c,
                      rd, jensen_rd[i].rd[c]);
      }
    }
  }
}

Test(media, marble_reproduces_the_papers_rd_at_eta_1_5) {
  const ss_medium_preset *m = ss_medium_preset_find("Marble");
  cr_assert_not_null(m);
  cr_assert_not_null(strstr(m->source, "1.5"), "the source notes eta 1.5: '%s'", m->source);
  for (int c = 0; c < 3; ++c) {
    double rd = dipole_rd(m->sigma_s_prime[c], m->sigma_a[c], 1.5);
    cr_assert_leq(fabs(rd - jensen_rd[5].rd[c]), RD_TOLERANCE, "channel %d: %.4f vs %.2f", c, rd,
                  jensen_rd[5].rd[c]);
  }
}

Test(media, chicken1_blue_is_inconsistent_at_every_index) {
  const ss_medium_preset *m = ss_medium_preset_find("Chicken1");
  cr_assert_not_null(m);
  for (double eta = 1.0; eta <= 2.0; eta += 0.05) {
    double rd = dipole_rd(m->sigma_s_prime[2], m->sigma_a[2], eta);
    cr_assert_gt(rd - 0.10, RD_TOLERANCE, "eta %.2f gives %.4f", eta, rd);
  }
}

Test(media, lookup_is_case_insensitive) {
  const ss_medium_preset *a = ss_medium_preset_find("Skin1");
  cr_assert_not_null(a);
  cr_assert_eq(ss_medium_preset_find("skin1"), a);
  cr_assert_eq(ss_medium_preset_find("SKIN1"), a);
  cr_assert_eq(ss_medium_preset_find("sKiN1"), a);
  const ss_medium_preset *milk = ss_medium_preset_find("Lowfat Milk");
  cr_assert_not_null(milk);
  cr_assert_eq(ss_medium_preset_find("lowfat milk"), milk);
  cr_assert_eq(ss_medium_preset_find("LOWFAT_MILK"), milk, "'_' stands for a space");
  cr_assert_eq(ss_medium_preset_find("lowfat-milk"), milk, "'-' stands for a space");
}

Test(media, unknown_names_give_null) {
  cr_assert_null(ss_medium_preset_find("Unobtainium"));
  cr_assert_null(ss_medium_preset_find(""));
  cr_assert_null(ss_medium_preset_find("Skin"), "no prefix matches");
  cr_assert_null(ss_medium_preset_find("Skin12"), "no extension matches");
  cr_assert_null(ss_medium_preset_find("LowfatMilk"), "the space is not optional");
  cr_assert_null(ss_medium_preset_find(NULL));
}

Test(media, table_is_complete_and_physical) {
  size_t n = ss_medium_preset_count();
  cr_assert_eq(n, 12u + 35u, "12 Jensen et al. 2001 rows and 35 Narasimhan et al. 2006 media");
  for (size_t i = 0; i < n; ++i) {
    const ss_medium_preset *m = ss_medium_preset_at(i);
    cr_assert_not_null(m);
    cr_assert_eq(ss_medium_preset_find(m->name), m, "%s is found by its own name", m->name);
    cr_assert(m->eta > 1.0 && m->eta < 2.0, "%s eta %g", m->name, m->eta);
    cr_assert(m->source && strlen(m->source) > 20, "%s cites its source", m->name);
    for (int c = 0; c < 3; ++c) {
      cr_assert(m->sigma_s_prime[c] >= 0.0 && m->sigma_a[c] >= 0.0, "%s channel %d", m->name, c);
      cr_assert_gt(m->sigma_s_prime[c] + m->sigma_a[c], 0.0, "%s channel %d", m->name, c);
    }
  }
  cr_assert_null(ss_medium_preset_at(n));
}

/* Spot checks of Narasimhan et al. 2006 values (mm^-1) against the table. */
Test(media, narasimhan_values_are_the_measurements) {
  const ss_medium_preset *m = ss_medium_preset_find("Regular Milk");
  cr_assert_not_null(m);
  cr_assert_float_eq(m->sigma_s_prime[0], 4.5513, 1e-12);
  cr_assert_float_eq(m->sigma_a[2], 0.019933, 1e-12);
  m = ss_medium_preset_find("Espresso");
  cr_assert_not_null(m);
  cr_assert_float_eq(m->sigma_a[0], 4.7984, 1e-12);
  cr_assert_not_null(strstr(m->source, "Narasimhan"));
}
