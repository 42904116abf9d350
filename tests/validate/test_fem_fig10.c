/* Jakob et al. 2010, Fig. 10a-c (issue 16): a 1 mm diffuse spot on a 4 x 4
 * cm cube of micro-flakes (a rho = 5.2482 / cm, alpha = 0.998, flakes about
 * the x axis, p = 20, fibre- and surface-like), the exitance on the top face
 * along horizontal (x, y = 0) and vertical (y, x = 0) slices through the
 * spot's centre: the finite elements (ss_fem_solve) against the micro-flake
 * Monte Carlo of the same cube and spot (ss_halfspace_run with width,
 * thickness and spot_radius: exact flake free flights and phase sampling)
 * and against the anisotropic dipole of a half-space (`aniso-dipole`).
 *
 * Lengths are in mean free paths of the uniformly oriented flakes,
 * 2 / (a rho) = 0.3811 cm (sigma_s = 0.998, sigma_a = 0.002): the cube's side
 * 4 cm is 10.496, the spot's radius 0.5 mm is 0.1312. Index matched (the
 * paper does not give eta). Bins of 1/41 of the side (0.256 = 0.98 mm)
 * along each slice, 1 bin wide across it; the models are averaged over the
 * same bins. Reported (docs/fem.md): the relative error of the finite
 * elements and of the dipole against the reference at 1-5 mean free paths
 * from the centre and their root mean square over 1.5-4.5 (outside the
 * spot's neighbourhood, inside the cube's sides). SUBSURF_VALIDATE_OUT: the
 * table's file; SUBSURF_VALIDATE_DIR: where the figure fem_fig10.svg goes.
 * The FEM runs with three sources: the boundary flux of eq. 37 and the
 * first scattering events along the spot's refracted rays (fem_rays.c),
 * with the flakes' sigma_t(w) and with it reduced by the similarity
 * relation (ss_flake_reduced_first_event, what `subsurf fem` and the `fem`
 * integrator use). Measured (2026-12-03): with the boundary source the FEM
 * is within 11-30 % of the Monte Carlo at 1-4 mfp along the slow direction
 * and 4-9 times too bright along the fast one; with the rays and sigma_t(w)
 * RMS 18-27 % along the slow direction and 2.2-2.6 times too bright along
 * the fast one; the similarity relation cuts the surface-like flakes' RMS
 * to 19 % (x) and 88 % (y) and leaves the fibres' (117 %, 21 %): the paper's
 * agreement is still not reproduced along the fibres (docs/fem.md). */
#include "fwddip_plot.h"
#include "subsurf/bssrdf.h"
#include "subsurf/fem.h"
#include "subsurf/flake_diffusion.h"
#include "subsurf/halfspace.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define SIDE (4.0 * 5.2482 / 2.0)
#define SPOT (0.05 * 5.2482 / 2.0)
#define NB 41
#define SUB 4 /* midpoints per bin side for the models' averages */
#define SIGMA_S 0.998
#define SIGMA_A 0.002
/* FEM with the boundary source, FEM with the rays' volume source (the
 * flakes' sigma_t(w), and reduced by the similarity relation as `subsurf
 * fem` takes it), dipole */
#define NMODELS 4
#define NFEM 3
static const char *const model_name[NMODELS] = {
    "FEM, boundary source (eq. 37)", "FEM, volume source, sigma_t(w)",
    "FEM, volume source, similarity", "aniso-dipole"};

typedef struct {
  const char *name;
  ss_flake_type type;
  /* [slice][bin]: slice 0 along x (y = 0), 1 along y (x = 0) */
  double mc[2][NB], mc_err[2][NB];
  /* [model][slice][bin]: the models of model_name */
  double model[NMODELS][2][NB];
  double mc_total, fem_escaped[NFEM], fem_injected[NFEM], fem_absorbed[NFEM];
  size_t tets;
  double rms[NMODELS][2];
} fig10;

static double bin_lo(int i) { return -0.5 * SIDE + SIDE * i / NB; }
static double bin_centre(int i) { return bin_lo(i) + 0.5 * SIDE / NB; }

static void run_monte_carlo(fig10 *f) {
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.sigma_s = ss_rgb_gray(SIGMA_S);
  p.medium.sigma_a = ss_rgb_gray(SIGMA_A);
  p.medium.flakes = (ss_medium_flakes){.type = f->type, .p = 20.0, .axis = {1, 0, 0}};
  p.thickness = p.width = SIDE;
  p.spot_radius = SPOT;
  p.paths = 4000000;
  p.seed = 16;
  p.rbins = 2;
  p.xmin = p.ymin = -0.5 * SIDE;
  p.xmax = p.ymax = 0.5 * SIDE;
  p.xbins = p.ybins = NB;
  p.want_map = 1;
  ss_halfspace_result *r = NULL;
  ss_error err;
  cr_assert_eq(ss_halfspace_run(&p, &r, &err), SS_OK, "%s", err.message);
  for (int i = 0; i < NB; ++i) {
    f->mc[0][i] = r->map[(NB / 2) * NB + i].value;
    f->mc_err[0][i] = r->map[(NB / 2) * NB + i].error;
    f->mc[1][i] = r->map[i * NB + NB / 2].value;
    f->mc_err[1][i] = r->map[i * NB + NB / 2].error;
  }
  f->mc_total = r->reflectance.value;
  ss_halfspace_result_destroy(r);
}

static ss_status flake_medium(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err) {
  *out = *(const ss_fem_coeffs *)ctx;
  return SS_OK;
}

/* The mean of f over slice s's bin i (SUB x SUB midpoints). */
typedef double (*field_fn)(void *ctx, double x, double y);
static double bin_mean(field_fn fn, void *ctx, int s, int i) {
  double w = SIDE / NB, sum = 0.0;
  for (int a = 0; a < SUB; ++a) {
    for (int c = 0; c < SUB; ++c) {
      double u = bin_lo(i) + (a + 0.5) * w / SUB, v = -0.5 * w + (c + 0.5) * w / SUB;
      sum += s == 0 ? fn(ctx, u, v) : fn(ctx, v, u);
    }
  }
  return sum / (SUB * SUB);
}

typedef struct {
  const ss_fem_mesh *mesh;
  const double *exitance;
} fem_field;

static double fem_at(void *ctx, double x, double y) {
  const fem_field *ff = ctx;
  double v = 0.0;
  cr_assert(ss_fem_interpolate(ff->mesh, ff->exitance, ss_vec3_make(x, y, 0.0), &v));
  return v;
}

/* The flakes' extinction along w (ctx: the flakes; density a rho), as it
 * is or reduced by the similarity relation (flake_diffusion.h). */
typedef struct {
  const ss_microflake *mf;
  double density;
} flake_sigma;

static double flake_sigma_t(void *ctx, ss_vec3 w) {
  const flake_sigma *fs = ctx;
  return fs->density * ss_microflake_sigma_t(fs->mf, w);
}

static double flake_sigma_reduced(void *ctx, ss_vec3 w) {
  const flake_sigma *fs = ctx;
  return ss_flake_reduced_first_event(fs->mf, fs->density, w).sigma;
}

static void run_fem(fig10 *f) {
  ss_error err = {0};
  ss_microflake mf;
  const double alpha = SIGMA_S / (SIGMA_S + SIGMA_A);
  cr_assert_eq(ss_microflake_init(&mf, f->type, 20.0, ss_vec3_make(1, 0, 0),
                                  (ss_flake_albedo){alpha, alpha, 1.0}, &err),
               SS_OK, "%s", err.message);
  ss_fem_coeffs k = ss_fem_coeffs_flakes(&mf, ss_flake_medium_density(SIGMA_S, SIGMA_A));
  ss_fem_mesh_options mo = {.size_max = 0.6,
                            .size_min = 0.08,
                            .refine_center = ss_vec3_make(0, 0, 0),
                            .refine_radius = 0.6,
                            .refine_grade = 4.0,
                            .rim_radius = SPOT,
                            .rim_size = 0.03};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-0.5 * SIDE, -0.5 * SIDE, -SIDE),
                               ss_vec3_make(0.5 * SIDE, 0.5 * SIDE, 0.0), &mo, &m, &err),
               SS_OK, "%s", err.message);
  /* Source 0, seed 003, eq. 37: the refracted power attenuated by
   * exp(-sigma_a/sigma_s) on the boundary. Sources 1 and 2: the first
   * scattering events along cosine-distributed refracted rays (the spot is
   * diffuse), extinction sigma_t(w) of the flakes and power times the
   * albedo (1), or both reduced by the similarity relation (2). */
  flake_sigma fs = {&mf, ss_flake_medium_density(SIGMA_S, SIGMA_A)};
  ss_fem_ray *rays[2] = {NULL, NULL};
  size_t num_rays[2] = {0, 0};
  cr_assert_eq(ss_fem_spot_rays(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, 1), SPOT, alpha, 1, 6, 6,
                                flake_sigma_t, &fs, &rays[0], &num_rays[0], &err),
               SS_OK, "%s", err.message);
  cr_assert_eq(ss_fem_spot_rays(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, 1), SPOT, 1.0, 1, 6, 6,
                                flake_sigma_reduced, &fs, &rays[1], &num_rays[1], &err),
               SS_OK, "%s", err.message);
  for (size_t r = 0; r < num_rays[1]; ++r) {
    rays[1][r].power *= ss_flake_reduced_first_event(&mf, fs.density, rays[1][r].dir).albedo;
  }
  ss_fem_problem pb[NFEM] = {
      {.eta = 1.0, .spot_radius = SPOT, .spot_power = exp(-SIGMA_A / SIGMA_S)},
      {.eta = 1.0, .rays = rays[0], .num_rays = num_rays[0]},
      {.eta = 1.0, .rays = rays[1], .num_rays = num_rays[1]}};
  for (int src = 0; src < NFEM; ++src) {
    ss_fem_solve_options so = {.solver = SS_FEM_CHOLMOD};
    ss_fem_solution *s = NULL;
    cr_assert_eq(ss_fem_solve(m, flake_medium, &k, &pb[src], &so, &s, &err), SS_OK, "%s",
                 err.message);
    fem_field ff = {m, s->exitance};
    for (int sl = 0; sl < 2; ++sl) {
      for (int i = 0; i < NB; ++i) {
        f->model[src][sl][i] = bin_mean(fem_at, &ff, sl, i);
      }
    }
    f->fem_injected[src] = s->injected;
    f->fem_escaped[src] = s->escaped;
    f->fem_absorbed[src] = s->absorbed;
    ss_fem_solution_destroy(s);
  }
  f->tets = m->num_tets;
  free(rays[0]);
  free(rays[1]);
  ss_fem_mesh_destroy(m);
}

/* The dipole's exitance at (x, y) from the spot: its point response
 * averaged over the disc (three equal-area rings of 8 points). */
static double dipole_at(void *ctx, double x, double y) {
  const ss_bssrdf *b = ctx;
  double sum = 0.0, v[3];
  for (int ring = 0; ring < 3; ++ring) {
    double r = SPOT * sqrt((ring + 0.5) / 3.0);
    for (int k = 0; k < 8; ++k) {
      double a = 2.0 * SS_PI * (k + 0.5 * ring) / 8.0;
      ss_bssrdf_exitance(b, 1.0, x - r * cos(a), y - r * sin(a), v);
      sum += v[0];
    }
  }
  return sum / 24.0;
}

static void run_dipole(fig10 *f) {
  ss_bssrdf_params bp;
  ss_bssrdf_params_default(&bp);
  bp.medium.sigma_s = ss_rgb_gray(SIGMA_S);
  bp.medium.sigma_a = ss_rgb_gray(SIGMA_A);
  bp.medium.flakes = (ss_medium_flakes){.type = f->type, .p = 20.0, .axis = {1, 0, 0}};
  bp.eta = 1.0;
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("aniso-dipole", &bp, &b, &err), SS_OK, "%s", err.message);
  for (int sl = 0; sl < 2; ++sl) {
    for (int i = 0; i < NB; ++i) {
      f->model[3][sl][i] = bin_mean(dipole_at, b, sl, i);
    }
  }
  ss_bssrdf_destroy(b);
}

/* Distances of the table (mean free paths), and the RMS window. */
static const double at[5] = {1.0, 2.0, 3.0, 4.0, 5.0};
#define RMS_LO 1.5
#define RMS_HI 4.5

/* The relative error of `model` against the reference at distance d along
 * slice s: the two mirror bins nearest d, averaged. */
static double rel_at(const fig10 *f, const double model[NB], int s, double d) {
  int k = (int)lround(d / (SIDE / NB));
  double m = 0.5 * (model[NB / 2 + k] + model[NB / 2 - k]);
  double r = 0.5 * (f->mc[s][NB / 2 + k] + f->mc[s][NB / 2 - k]);
  return m / r - 1.0;
}

static double rms(const fig10 *f, const double model[NB], int s) {
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < NB; ++i) {
    double d = fabs(bin_centre(i));
    if (d >= RMS_LO && d <= RMS_HI) {
      double e = model[i] / f->mc[s][i] - 1.0;
      sum += e * e;
      ++n;
    }
  }
  return sqrt(sum / n);
}

static void print_table(FILE *out, const fig10 *f, int n) {
  fprintf(out, "| flakes (p = 20, axis x) | slice | model |");
  for (int k = 0; k < 5; ++k) {
    fprintf(out, " %g mfp |", at[k]);
  }
  fprintf(out, " RMS %g-%g mfp |\n|---|---|---|---|---|---|---|---|---|\n", RMS_LO, RMS_HI);
  for (int i = 0; i < n; ++i) {
    for (int s = 0; s < 2; ++s) {
      for (int m = 0; m < NMODELS; ++m) {
        fprintf(out, "| %s | %s | %s |", f[i].name, s ? "vertical (y)" : "horizontal (x)",
                model_name[m]);
        for (int k = 0; k < 5; ++k) {
          fprintf(out, " %+.1f %% |", 100.0 * rel_at(&f[i], f[i].model[m][s], s, at[k]));
        }
        fprintf(out, " %.1f %% |\n", 100.0 * f[i].rms[m][s]);
      }
    }
  }
}

static void write_plot(const fig10 *f, int n) {
  const char *dir = getenv("SUBSURF_VALIDATE_DIR");
  if (!dir) {
    return;
  }
  static plot_panel panels[4];
  for (int i = 0; i < n; ++i) {
    for (int s = 0; s < 2; ++s) {
      plot_panel *p = &panels[2 * i + s];
      static char titles[4][64];
      snprintf(titles[2 * i + s], sizeof titles[0], "%s flakes, %s slice", f[i].name,
               s ? "vertical (x = 0)" : "horizontal (y = 0)");
      p->title = titles[2 * i + s];
      p->n_series = 1 + NMODELS;
      p->n_points = NB;
      p->name[0] = "Monte Carlo (cube)";
      p->name[1] = "FEM (cube), boundary source";
      p->name[2] = "FEM (cube), volume source, sigma_t(w)";
      p->name[3] = "FEM (cube), volume source, similarity";
      p->name[4] = "aniso-dipole (half-space)";
      for (int b = 0; b < NB; ++b) {
        p->x[b] = bin_centre(b) * 2.0 / 5.2482; /* cm */
        p->y[0][b] = f[i].mc[s][b];
        for (int m = 0; m < NMODELS; ++m) {
          p->y[1 + m][b] = f[i].model[m][s][b];
        }
      }
    }
  }
  char path[1024];
  snprintf(path, sizeof path, "%s/fem_fig10.svg", dir);
  cr_expect_eq(plot_write_svg(path, panels, 2 * n, 2, "position on the top face (cm)"), 0,
               "cannot write %s", path);
}

Test(fem_fig10, finite_elements_match_the_flake_monte_carlo_outside_the_spot, .timeout = 3600) {
  static fig10 f[2] = {{.name = "fiber", .type = SS_FLAKE_FIBER},
                       {.name = "surface", .type = SS_FLAKE_SURFACE}};
  for (int i = 0; i < 2; ++i) {
    run_monte_carlo(&f[i]);
    run_fem(&f[i]);
    run_dipole(&f[i]);
    for (int s = 0; s < 2; ++s) {
      for (int m = 0; m < NMODELS; ++m) {
        f[i].rms[m][s] = rms(&f[i], f[i].model[m][s], s);
      }
    }
    for (int src = 0; src < NFEM; ++src) {
      cr_log_info("%s: %zu tetrahedra; reflectance MC %.4f, %s: escaped %.4f of %.4f (absorbed "
                  "%.4f)",
                  f[i].name, f[i].tets, f[i].mc_total, model_name[src], f[i].fem_escaped[src],
                  f[i].fem_injected[src], f[i].fem_absorbed[src]);
    }
    for (int s = 0; s < 2; ++s) {
      for (int b = 0; b < NB; ++b) {
        cr_log_info("%s %c %7.3f: mc %.4e +- %.1e fem %.4e rays %.4e reduced %.4e dip %.4e",
                    f[i].name, s ? 'y' : 'x', bin_centre(b), f[i].mc[s][b], f[i].mc_err[s][b],
                    f[i].model[0][s][b], f[i].model[1][s][b], f[i].model[2][s][b],
                    f[i].model[3][s][b]);
      }
    }
  }
  print_table(stderr, f, 2);
  const char *out = getenv("SUBSURF_VALIDATE_OUT");
  if (out) {
    FILE *file = fopen(out, "w");
    if (file) {
      print_table(file, f, 2);
      fclose(file);
    }
  }
  write_plot(f, 2);
  /* Claims of docs/fem.md. The solve conserves energy. */
  for (int i = 0; i < 2; ++i) {
    for (int src = 0; src < NFEM; ++src) {
      cr_expect_float_eq(f[i].fem_escaped[src] + f[i].fem_absorbed[src], f[i].fem_injected[src],
                         1e-8 * f[i].fem_injected[src], "%s, %s: energy balance", f[i].name,
                         model_name[src]);
    }
  }
  /* Both spread the light the same way at 2-4 mfp: along the fibres (x),
   * across the surface-like flakes' normals (y). */
  for (int k = 1; k < 4; ++k) {
    double d = at[k];
    int j = (int)lround(d / (SIDE / NB));
    for (int m = 0; m <= NMODELS; ++m) {
      const fig10 *fi = &f[0], *su = &f[1];
      const double *fx = m ? fi->model[m - 1][0] : fi->mc[0];
      const double *fy = m ? fi->model[m - 1][1] : fi->mc[1];
      const double *sx = m ? su->model[m - 1][0] : su->mc[0];
      const double *sy = m ? su->model[m - 1][1] : su->mc[1];
      const char *name = m ? model_name[m - 1] : "MC";
      cr_expect(fx[NB / 2 + j] + fx[NB / 2 - j] > fy[NB / 2 + j] + fy[NB / 2 - j],
                "%s, fiber at %g mfp: along x below along y", name, d);
      cr_expect(sy[NB / 2 + j] + sy[NB / 2 - j] > sx[NB / 2 + j] + sx[NB / 2 - j],
                "%s, surface at %g mfp: along y below along x", name, d);
    }
  }
  /* Diffusion exaggerates the fast direction in a cube of 10.5 mfp: along
   * it the transport mean free path 3 / M_ii is 7.7 mfp (M of eq. 34 is
   * right: the mean square displacement of long flake random walks gives
   * M^-1 within 4 %), so the finite elements (and the dipole) are more than
   * twice as bright as the Monte Carlo at 2-4 mfp along x for fibres and
   * along y for surface-like flakes. */
  /* The rays' volume source, either way, is closer to the Monte Carlo
   * than the boundary source on every slice (RMS 1.5-4.5 mfp). */
  for (int i = 0; i < 2; ++i) {
    for (int s = 0; s < 2; ++s) {
      for (int m = 1; m <= 2; ++m) {
        cr_expect_lt(f[i].rms[m][s], f[i].rms[0][s], "%s, slice %d: %s %g, boundary %g",
                     f[i].name, s, model_name[m], f[i].rms[m][s], f[i].rms[0][s]);
      }
    }
  }
  /* The similarity relation moves the surface-like flakes' sources deeper
   * (they keep the light going down: w.g = 0.83 at normal incidence) and
   * cuts their error on both slices by at least a quarter (measured: 27 to
   * 19 % along x, 155 to 88 % along y). */
  for (int s = 0; s < 2; ++s) {
    cr_expect_lt(f[1].rms[2][s], 0.75 * f[1].rms[1][s], "surface, slice %d: similarity %g, "
                 "sigma_t(w) %g", s, f[1].rms[2][s], f[1].rms[1][s]);
  }
  for (int k = 1; k < 4; ++k) {
    cr_expect(rel_at(&f[0], f[0].model[0][0], 0, at[k]) > 1.0, "fiber along x at %g", at[k]);
    cr_expect(rel_at(&f[1], f[1].model[0][1], 1, at[k]) > 1.0, "surface along y at %g", at[k]);
  }
}
