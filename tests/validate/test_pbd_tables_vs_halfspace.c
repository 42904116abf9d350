/* Photon beam diffusion and its two tables against the exact half-space
 * Monte Carlo reference, on the grid of
 * test_models_vs_halfspace.c (same reference runs). Prints the table
 * docs/models.md quotes (set SUBSURF_VALIDATE_OUT to also write it to a
 * file) and asserts the regime claims made there.
 *
 * Conventions: `pbd` and `table-radial` carry multiple and single scattering
 * (pbrt-v3's profile), so they are compared with the whole reference.
 * `table-gwc` is multiple scattering only (Ferrier2016): it is compared
 * twice, (a) with the exact single scattering of the `single` model added
 * ("table-gwc+single") against the whole reference, and (b) alone against
 * the reference's multiple scattering, reference minus `single` (the
 * `single` model is the reference's exact first order). At normal incidence
 * pbd minus `single` is pbd's multiple scattering, compared the same way.
 * Ferrier's table is
 * defined for eta > 1 only: index matched, the model refuses to be created,
 * and the test checks that it does. */
#include "validate/halfspace_grid.h"

#include "subsurf/table_file.h"
#include "subsurf/table_gwc.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { PBD, RADIAL, GWC_SS, GWC_MS, PBD_MS, N_MODELS };
/* PBD_MS is not a model: pbd minus `single`, pbd's multiple scattering at
 * normal incidence, where its single scattering (pbrt-v3's profile) is
 * exactly the `single` model's. */
static const char *models[N_MODELS] = {"pbd", "table-radial", "table-gwc+single", "table-gwc",
                                       "pbd-single"};

typedef struct {
  int valid;        /* 0: the model refuses these parameters */
  double total_rel; /* model / reference - 1 */
  double total_z;   /* in reference standard errors */
  double far;       /* mean |rel| over resolved bins with r >= 1/sigma_t' */
  double all;       /* mean |rel| over every resolved bin, from r = 0 */
  int far_bins, all_bins;
} score;

static score scores[GRID_ETAS][GRID_THETAS][GRID_ALBEDOS][N_MODELS];
static double reference_r[GRID_ETAS][GRID_THETAS][GRID_ALBEDOS];
static double reference_ms[GRID_ETAS][GRID_THETAS][GRID_ALBEDOS];
static char gwc_refusal[sizeof(((ss_error *)0)->message)];

static score score_of(const ss_halfspace_result *ref, double ref_total, const double *ref_value,
                      double total, const double *radial) {
  score s = {.valid = 1};
  s.total_rel = total / ref_total - 1.0;
  s.total_z = (total - ref_total) / ref->reflectance.error;
  s.far = grid_profile_error(ref, ref_value, radial, 1.0, &s.far_bins);
  s.all = grid_profile_error(ref, ref_value, radial, 0.0, &s.all_bins);
  return s;
}

/* One reference run and every model on its bins. */
static void run_config(int e, int t, int a, const char *gwc_table) {
  ss_halfspace_params p;
  grid_params(e, t, a, &p);
  ss_halfspace_result *ref = NULL;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(&p, &ref, &err), SS_OK, "%s", err.message);
  double whole[GRID_MAX_BINS], ms[GRID_MAX_BINS], single[GRID_MAX_BINS], radial[GRID_MAX_BINS];
  double single_total, total, pbd_total = 0.0, pbd_radial[GRID_MAX_BINS];
  cr_assert_eq(grid_predict("single", &p, ref, NULL, &single_total, single, &err), SS_OK, "%s",
               err.message);
  for (int i = 0; i < ref->rbins; ++i) {
    whole[i] = ref->radial[i].value;
    ms[i] = whole[i] - single[i];
  }
  double ref_total = ref->reflectance.value;
  reference_r[e][t][a] = ref_total;
  reference_ms[e][t][a] = ref_total - single_total;
  score *s = scores[e][t][a];
  for (int m = 0; m < PBD_MS; ++m) {
    ss_status st = grid_predict(models[m], &p, ref, gwc_table, &total, radial, &err);
    if (st != SS_OK) {
      /* Only Ferrier's table may refuse, and only index matched. */
      cr_assert(m >= GWC_SS && grid_eta[e] == 1.0, "%s: %s", models[m], err.message);
      snprintf(gwc_refusal, sizeof gwc_refusal, "%s", err.message);
      s[m].valid = 0;
      continue;
    }
    s[m] = m == GWC_MS ? score_of(ref, ref_total - single_total, ms, total, radial)
                       : score_of(ref, ref_total, whole, total, radial);
    if (m == PBD) {
      pbd_total = total;
      memcpy(pbd_radial, radial, sizeof radial);
    }
  }
  if (grid_theta[t] == 0.0) {
    for (int i = 0; i < ref->rbins; ++i) {
      pbd_radial[i] -= single[i];
    }
    s[PBD_MS] = score_of(ref, ref_total - single_total, ms, pbd_total - single_total, pbd_radial);
  }
  ss_halfspace_result_destroy(ref);
}

static void run_all(void) {
  /* Ferrier's table is built once (eta 1.33, g 0) and loaded by every
   * table-gwc model, instead of each model building its own. */
  char path[64];
  snprintf(path, sizeof path, "/tmp/subsurf-validate-gwc-%ld.sstab", (long)getpid());
  ss_table_gwc *table = NULL;
  ss_error err;
  cr_assert_eq(ss_table_gwc_build(grid_eta[1], 0.0, SS_TABLE_GWC_TWO_LOBE, &table, &err), SS_OK,
               "%s", err.message);
  cr_assert_eq(ss_table_gwc_save(table, path, &err), SS_OK, "%s", err.message);
  ss_table_gwc_destroy(table);
  for (int e = 0; e < GRID_ETAS; ++e) {
    for (int t = 0; t < GRID_THETAS; ++t) {
      for (int a = 0; a < GRID_ALBEDOS; ++a) {
        run_config(e, t, a, path);
      }
    }
  }
  remove(path);
}

static void print_table(FILE *f) {
  fprintf(f, "| eta | theta_i | albedo | reference R | its multiple scattering |");
  for (int m = 0; m < N_MODELS; ++m) {
    fprintf(f, " %s%s |", models[m], m >= GWC_MS ? " (vs multiple)" : "");
  }
  fprintf(f, "\n|---|---|---|---|---|");
  for (int m = 0; m < N_MODELS; ++m) {
    fprintf(f, "---|");
  }
  fprintf(f, "\n");
  for (int e = 0; e < GRID_ETAS; ++e) {
    for (int t = 0; t < GRID_THETAS; ++t) {
      for (int a = 0; a < GRID_ALBEDOS; ++a) {
        fprintf(f, "| %.2f | %.0f | %.3f | %.4f | %.4f |", grid_eta[e], grid_theta[t],
                grid_albedo[a], reference_r[e][t][a], reference_ms[e][t][a]);
        for (int m = 0; m < N_MODELS; ++m) {
          const score *s = &scores[e][t][a][m];
          if (!s->valid) {
            fprintf(f, m == PBD_MS ? " - |" : " refused |");
          } else {
            fprintf(f, " %+.1f%% / %.0f%% / %.0f%% |", 100.0 * s->total_rel, 100.0 * s->far,
                    100.0 * s->all);
          }
        }
        fprintf(f, "\n");
      }
    }
  }
}

Test(pbd_tables_vs_halfspace, table_and_regime_claims, .timeout = 1800) {
  run_all();
  print_table(stderr);
  const char *out = getenv("SUBSURF_VALIDATE_OUT");
  if (out) {
    FILE *f = fopen(out, "w");
    if (f) {
      print_table(f);
      fclose(f);
    }
  }
  cr_expect(strstr(gwc_refusal, "eta") != NULL, "table-gwc's refusal names eta: '%s'", gwc_refusal);
  /* Claims of docs/models.md. */
  for (int e = 0; e < GRID_ETAS; ++e) {
    for (int t = 0; t < GRID_THETAS; ++t) {
      for (int a = 0; a < GRID_ALBEDOS; ++a) {
        const score *s = scores[e][t][a];
        double eta = grid_eta[e], theta = grid_theta[t], albedo = grid_albedo[a];
        int matched = eta == 1.0, normal = theta == 0.0;
        /* Ferrier's table exists only for eta > 1. */
        cr_expect_eq(s[GWC_SS].valid, !matched);
        cr_expect_eq(s[GWC_MS].valid, !matched);
        if (normal) {
          /* The tables reproduce PBD at normal incidence (their own
           * accuracy, docs/tables.md): these differences do not depend on
           * the reference's noise beyond its scale. */
          cr_expect(fabs(s[RADIAL].total_rel - s[PBD].total_rel) < 0.006,
                    "table-radial vs pbd, eta %g albedo %g: %+.4f vs %+.4f", eta, albedo,
                    s[RADIAL].total_rel, s[PBD].total_rel);
          if (!matched) {
            cr_expect(fabs(s[GWC_SS].total_rel - s[PBD].total_rel) < 0.001,
                      "table-gwc+single vs pbd, albedo %g: %+.4f vs %+.4f", albedo,
                      s[GWC_SS].total_rel, s[PBD].total_rel);
          }
          /* PBD's multiple scattering overshoots the reference's: its
           * diffusion source is the first collision, so once-scattered light
           * is counted in both terms (docs/tables.md). Index matched, where
           * most single scattering escapes, by 12-34%. */
          cr_expect(s[PBD_MS].total_rel > (matched ? 0.10 : 0.03),
                    "pbd-single eta %g albedo %g: %+.4f", eta, albedo, s[PBD_MS].total_rel);
          if (matched) {
            cr_expect(s[PBD].total_rel > 0.08, "pbd index matched, albedo %g: %+.4f", albedo,
                      s[PBD].total_rel);
          }
        }
        if (!matched) {
          /* Ferrier's multiple scattering against the reference's: always
           * high, 4-5% at albedo >= 0.99, > 20% at albedo 0.5. */
          cr_expect(s[GWC_MS].total_rel > 0.03, "table-gwc theta %g albedo %g: %+.4f", theta,
                    albedo, s[GWC_MS].total_rel);
          if (albedo >= 0.99) {
            cr_expect(s[GWC_MS].total_rel < 0.055, "table-gwc theta %g albedo %g: %+.4f", theta,
                      albedo, s[GWC_MS].total_rel);
            /* The regime where pbd and Ferrier's table with exact single
             * scattering are within 5% in total and in profile, from the
             * entry point outward. */
            cr_expect(fabs(s[PBD].total_rel) < 0.05, "pbd theta %g albedo %g: %+.4f", theta, albedo,
                      s[PBD].total_rel);
            cr_expect(fabs(s[GWC_SS].total_rel) < 0.05,
                      "table-gwc+single theta %g albedo %g: %+.4f", theta, albedo,
                      s[GWC_SS].total_rel);
            cr_expect(s[PBD].far < 0.05 && s[PBD].all < 0.06,
                      "pbd profile theta %g albedo %g: %.4f / %.4f", theta, albedo, s[PBD].far,
                      s[PBD].all);
          }
          if (albedo <= 0.5) {
            cr_expect(s[GWC_MS].total_rel > 0.2);
            cr_expect(s[GWC_SS].total_rel > 0.08);
          }
          if (!normal) {
            /* At 60 degrees pbd's single scattering is the normal-incidence
             * profile, below the exact one: pbd lands within 5% at every
             * albedo partly by cancellation, below the exact-single-scattering
             * variant. table-radial, normal incidence by construction, is
             * within 5% in total too (its total is Ft(theta) rho_eff). */
            cr_expect(fabs(s[PBD].total_rel) < 0.05, "pbd 60 deg albedo %g: %+.4f", albedo,
                      s[PBD].total_rel);
            cr_expect(s[GWC_SS].total_rel > s[PBD].total_rel + 0.01,
                      "cancellation, albedo %g: %+.4f vs %+.4f", albedo, s[GWC_SS].total_rel,
                      s[PBD].total_rel);
            cr_expect(fabs(s[RADIAL].total_rel) < 0.05, "table-radial 60 deg albedo %g: %+.4f",
                      albedo, s[RADIAL].total_rel);
          }
        }
        if (matched && !normal && albedo >= 0.99) {
          /* Index matched at 60 degrees the exitance shifts forward: the
           * radially symmetric normal-incidence table misses it, pbd's
           * oblique beam follows it. */
          cr_expect(s[RADIAL].far > 0.15 && s[PBD].far < 0.10,
                    "60 deg albedo %g: table-radial %.4f, pbd %.4f", albedo, s[RADIAL].far,
                    s[PBD].far);
        }
      }
    }
  }
}
