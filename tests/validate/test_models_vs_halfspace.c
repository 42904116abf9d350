/* Every BSSRDF model against the exact half-space Monte Carlo reference:
 * index matched and eta = 1.33, albedo 0.5 to 0.999,
 * normal and 60 degree incidence. Prints the table docs/models.md quotes
 * (set SUBSURF_VALIDATE_OUT to also write it to a file) and asserts the
 * regime claims made there. */
#include "validate/halfspace_grid.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N_ALBEDO GRID_ALBEDOS
#define N_MODELS 6
/* "dipole+single" is Jensen et al.'s complete model S_d + S^(1). */
static const char *models[N_MODELS] = {"dipole",  "dipole+single", "better-dipole",
                                       "dirpole", "single",        "dipole-brdf"};

typedef struct {
  double total_rel;   /* model / reference - 1 */
  double total_z;     /* in reference standard errors */
  double profile_rel; /* mean |rel| over resolved bins with r >= 1/sigma_t' */
  int bins;
} score;

static score scores[2][2][N_ALBEDO][N_MODELS];
static double reference_r[2][2][N_ALBEDO];

static void run_all(void) {
  for (int e = 0; e < 2; ++e) {
    for (int t = 0; t < 2; ++t) {
      for (int a = 0; a < N_ALBEDO; ++a) {
        ss_halfspace_params p;
        grid_params(e, t, a, &p);
        ss_halfspace_result *ref = NULL;
        ss_error err;
        cr_assert_eq(ss_halfspace_run(&p, &ref, &err), SS_OK, "%s", err.message);
        reference_r[e][t][a] = ref->reflectance.value;
        double radial[GRID_MAX_BINS], ref_value[GRID_MAX_BINS];
        for (int i = 0; i < ref->rbins; ++i) {
          ref_value[i] = ref->radial[i].value;
        }
        for (int m = 0; m < N_MODELS; ++m) {
          double total;
          cr_assert_eq(grid_predict(models[m], &p, ref, NULL, &total, radial, &err), SS_OK, "%s",
                       err.message);
          score *s = &scores[e][t][a][m];
          s->total_rel = total / ref->reflectance.value - 1.0;
          s->total_z = (total - ref->reflectance.value) / ref->reflectance.error;
          s->profile_rel = grid_profile_error(ref, ref_value, radial, 1.0, &s->bins);
        }
        ss_halfspace_result_destroy(ref);
      }
    }
  }
}

static void print_table(FILE *f) {
  fprintf(f, "| eta | theta_i | albedo | reference R |");
  for (int m = 0; m < N_MODELS; ++m) {
    fprintf(f, " %s |", models[m]);
  }
  fprintf(f, "\n|---|---|---|---|");
  for (int m = 0; m < N_MODELS; ++m) {
    fprintf(f, "---|");
  }
  fprintf(f, "\n");
  for (int e = 0; e < 2; ++e) {
    for (int t = 0; t < 2; ++t) {
      for (int a = 0; a < N_ALBEDO; ++a) {
        fprintf(f, "| %.2f | %.0f | %.3f | %.4f |", grid_eta[e], grid_theta[t], grid_albedo[a],
                reference_r[e][t][a]);
        for (int m = 0; m < N_MODELS; ++m) {
          const score *s = &scores[e][t][a][m];
          if (!strcmp(models[m], "dipole-brdf")) {
            fprintf(f, " %+.1f%% |", 100.0 * s->total_rel);
          } else {
            fprintf(f, " %+.1f%% / %.0f%% |", 100.0 * s->total_rel, 100.0 * s->profile_rel);
          }
        }
        fprintf(f, "\n");
      }
    }
  }
}

Test(models_vs_halfspace, table_and_regime_claims, .timeout = 1800) {
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
  /* Claims of docs/models.md (model index into `models`). */
  enum { DIPOLE, DIPOLE_SS, BETTER, DIRPOLE, SINGLE, BRDF };
  for (int e = 0; e < 2; ++e) {
    for (int t = 0; t < 2; ++t) {
      for (int a = 0; a < N_ALBEDO; ++a) {
        score(*s) = scores[e][t][a];
        /* Single scattering alone always under-predicts the total. */
        cr_expect(s[SINGLE].total_rel < 0.0);
        /* The dipole with single scattering and the BRDF approximation carry
         * the same power (the BRDF integrates the BSSRDF). */
        cr_expect(fabs(s[DIPOLE_SS].total_rel - s[BRDF].total_rel) < 1e-3,
                  "eta %g theta %g albedo %g: %g vs %g", grid_eta[e], grid_theta[t], grid_albedo[a],
                  s[DIPOLE_SS].total_rel, s[BRDF].total_rel);
        /* The directional dipole overshoots the total everywhere (the
         * calibration point of test_dirpole.c: ~0.85 against 0.65 at eta 1.33, albedo 0.99). */
        cr_expect(s[DIRPOLE].total_rel > 0.2, "dirpole eta %g theta %g albedo %g: %+.3f",
                  grid_eta[e], grid_theta[t], grid_albedo[a], s[DIRPOLE].total_rel);
        if (grid_albedo[a] >= 0.99) {
          /* Diffusive regime: better dipole within 5% at normal incidence;
           * Jensen's complete model (dipole + single) within 5% at eta 1.33. */
          if (grid_theta[t] == 0.0) {
            cr_expect(fabs(s[BETTER].total_rel) < 0.05, "better-dipole eta %g albedo %g: %+.3f",
                      grid_eta[e], grid_albedo[a], s[BETTER].total_rel);
          }
          if (grid_eta[e] > 1.0) {
            cr_expect(fabs(s[DIPOLE_SS].total_rel) < 0.05,
                      "dipole+single theta %g albedo %g: %+.3f", grid_theta[t], grid_albedo[a],
                      s[DIPOLE_SS].total_rel);
          }
        }
        if (grid_albedo[a] <= 0.9) {
          /* Outside the diffusive regime every diffusion model is off by more
           * than 5% in total, except by cancellation (dipole at eta 1.33). */
          cr_expect(fabs(s[BETTER].total_rel) > 0.05);
          cr_expect(fabs(s[DIPOLE_SS].total_rel) > 0.05);
        }
      }
    }
  }
}
