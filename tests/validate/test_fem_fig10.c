/* Jakob2010 Fig. 10a-c: a 1 mm diffuse spot on a 4 x 4
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
 * tables' file (appended); SUBSURF_VALIDATE_DIR: where the figure fem_fig10.svg goes.
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
 * agreement is not reproduced along the fibres (docs/fem.md).
 *
 * The second test asks where diffusion applies: the FEM with the
 * similarity-reduced source against the Monte Carlo (10^6 paths per case)
 * over the anisotropy at the paper's size (uniform flakes, p = 1, 5, 20) and
 * over the optical size at p = 20 (a rho times 4), the errors also at
 * multiples of the transport mean free path 3 / M_ii of each slice's axis.
 * It asserts the agreement of the mildly anisotropic cases, the growth of
 * the fast axis's error with p, its fall with the optical size, the
 * surface-like flakes' agreement in the thick cube, and the fibres'
 * documented disagreement along x on the top face. */
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
#define FEM_SIMILARITY 2
static const char *const model_name[NMODELS] = {"FEM, boundary source (eq. 37)",
                                                "FEM, volume source, sigma_t(w)",
                                                "FEM, volume source, similarity", "aniso-dipole"};

typedef struct {
  const char *name;
  ss_flake_type type;
  double p;
  /* The optical size: a rho times `scale` in the same 4 cm cube with the
   * same 1 mm spot, i.e. in mean free paths of the paper's uniform flakes
   * every length times `scale` (side, spot, bins). */
  double scale;
  uint64_t paths;
  double side, spot;
  /* [slice][bin]: slice 0 along x (y = 0), 1 along y (x = 0) */
  double mc[2][NB], mc_err[2][NB];
  /* [model][slice][bin]: the models of model_name */
  double model[NMODELS][2][NB];
  double mc_total, fem_top, fem_escaped[NFEM], fem_injected[NFEM], fem_absorbed[NFEM];
  double ltr[3]; /* the transport mean free paths 3 / M_ii along x, y, z (mfp) */
  size_t tets;
  double rms[NMODELS][2];
} fig10;

static void fig10_init(fig10 *f) {
  f->side = f->scale * SIDE;
  f->spot = f->scale * SPOT;
}

static double bin_width(const fig10 *f) { return f->side / NB; }
static double bin_lo(const fig10 *f, int i) { return -0.5 * f->side + f->side * i / NB; }
static double bin_centre(const fig10 *f, int i) { return bin_lo(f, i) + 0.5 * bin_width(f); }

static void run_monte_carlo(fig10 *f) {
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.sigma_s = ss_rgb_gray(SIGMA_S);
  p.medium.sigma_a = ss_rgb_gray(SIGMA_A);
  p.medium.flakes = (ss_medium_flakes){.type = f->type, .p = f->p, .axis = {1, 0, 0}};
  p.thickness = p.width = f->side;
  p.spot_radius = f->spot;
  p.paths = f->paths;
  p.seed = 16;
  p.rbins = 2;
  p.xmin = p.ymin = -0.5 * f->side;
  p.xmax = p.ymax = 0.5 * f->side;
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
static double bin_mean(const fig10 *f, field_fn fn, void *ctx, int s, int i) {
  double w = bin_width(f), sum = 0.0;
  for (int a = 0; a < SUB; ++a) {
    for (int c = 0; c < SUB; ++c) {
      double u = bin_lo(f, i) + (a + 0.5) * w / SUB, v = -0.5 * w + (c + 0.5) * w / SUB;
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

/* The exitance integrated over the top face (z = 0; linear over each
 * boundary triangle): the light leaving through the top, the Monte Carlo's
 * reflectance. */
static double top_face_exitance(const ss_fem_mesh *m, const double *exitance) {
  double sum = 0.0;
  for (size_t t = 0; t < m->num_faces; ++t) {
    ss_vec3 q[3];
    ss_fem_face_vertices(m, t, q);
    if (q[0].z != 0.0 || q[1].z != 0.0 || q[2].z != 0.0) {
      continue;
    }
    double area =
        0.5 * fabs((q[1].x - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (q[1].y - q[0].y));
    const uint32_t *v = &m->faces[3 * t];
    sum += area * (exitance[v[0]] + exitance[v[1]] + exitance[v[2]]) / 3.0;
  }
  return sum;
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

/* Element sizes (mfp): at the paper's size 0.08 within 0.6 of the spot
 * growing to 0.6, 0.03 along its rim (52 k tetrahedra); optically thicker
 * cubes 0.1 scale within 2 scale growing to 0.6 scale over 4 scale (the
 * fibres at scale 4: 181 k tetrahedra; with all sizes two thirds and the
 * finest 0.25, 656 k, the errors of docs/fem.md's table moved by at most 3
 * points at 0.5-2 transport mean free paths along x and 5 along y). */
static ss_fem_mesh_options mesh_options(const fig10 *f) {
  if (f->scale == 1.0) {
    return (ss_fem_mesh_options){.size_max = 0.6,
                                 .size_min = 0.08,
                                 .refine_radius = 0.6,
                                 .refine_grade = 4.0,
                                 .rim_radius = f->spot,
                                 .rim_size = 0.03};
  }
  return (ss_fem_mesh_options){.size_max = 0.6 * f->scale,
                               .size_min = 0.1 * f->scale,
                               .refine_radius = 2.0 * f->scale,
                               .refine_grade = 4.0 * f->scale,
                               .rim_radius = f->spot,
                               .rim_size = 0.03};
}

/* The finite elements with the sources first_source .. NFEM - 1. */
static void run_fem(fig10 *f, int first_source) {
  ss_error err = {0};
  ss_microflake mf;
  const double alpha = SIGMA_S / (SIGMA_S + SIGMA_A);
  cr_assert_eq(ss_microflake_init(&mf, f->type, f->p, ss_vec3_make(1, 0, 0),
                                  (ss_flake_albedo){alpha, alpha, 1.0}, &err),
               SS_OK, "%s", err.message);
  ss_fem_coeffs k = ss_fem_coeffs_flakes(&mf, ss_flake_medium_density(SIGMA_S, SIGMA_A));
  for (int a = 0; a < 3; ++a) {
    f->ltr[a] = 3.0 / k.M[4 * a];
  }
  ss_fem_mesh_options mo = mesh_options(f);
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-0.5 * f->side, -0.5 * f->side, -f->side),
                               ss_vec3_make(0.5 * f->side, 0.5 * f->side, 0.0), &mo, &m, &err),
               SS_OK, "%s", err.message);
  /* Source 0, Jakob2010 eq. 37: the refracted power attenuated by
   * exp(-sigma_a/sigma_s) on the boundary. Sources 1 and 2: the first
   * scattering events along cosine-distributed refracted rays (the spot is
   * diffuse), extinction sigma_t(w) of the flakes and power times the
   * albedo (1), or both reduced by the similarity relation (2). */
  flake_sigma fs = {&mf, ss_flake_medium_density(SIGMA_S, SIGMA_A)};
  ss_fem_ray *rays[2] = {NULL, NULL};
  size_t num_rays[2] = {0, 0};
  cr_assert_eq(ss_fem_spot_rays(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, 1), f->spot, alpha, 1, 6,
                                6, flake_sigma_t, &fs, &rays[0], &num_rays[0], &err),
               SS_OK, "%s", err.message);
  cr_assert_eq(ss_fem_spot_rays(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, 1), f->spot, 1.0, 1, 6, 6,
                                flake_sigma_reduced, &fs, &rays[1], &num_rays[1], &err),
               SS_OK, "%s", err.message);
  for (size_t r = 0; r < num_rays[1]; ++r) {
    rays[1][r].power *= ss_flake_reduced_first_event(&mf, fs.density, rays[1][r].dir).albedo;
  }
  ss_fem_problem pb[NFEM] = {
      {.eta = 1.0, .spot_radius = f->spot, .spot_power = exp(-SIGMA_A / SIGMA_S)},
      {.eta = 1.0, .rays = rays[0], .num_rays = num_rays[0]},
      {.eta = 1.0, .rays = rays[1], .num_rays = num_rays[1]}};
  for (int src = first_source; src < NFEM; ++src) {
    ss_fem_solve_options so = {.solver = SS_FEM_CHOLMOD};
    ss_fem_solution *s = NULL;
    cr_assert_eq(ss_fem_solve(m, flake_medium, &k, &pb[src], &so, &s, &err), SS_OK, "%s",
                 err.message);
    fem_field ff = {m, s->exitance};
    for (int sl = 0; sl < 2; ++sl) {
      for (int i = 0; i < NB; ++i) {
        f->model[src][sl][i] = bin_mean(f, fem_at, &ff, sl, i);
      }
    }
    f->fem_injected[src] = s->injected;
    f->fem_escaped[src] = s->escaped;
    f->fem_absorbed[src] = s->absorbed;
    if (src == FEM_SIMILARITY) {
      f->fem_top = top_face_exitance(m, s->exitance);
    }
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
  bp.medium.flakes = (ss_medium_flakes){.type = f->type, .p = f->p, .axis = {1, 0, 0}};
  bp.eta = 1.0;
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("aniso-dipole", &bp, &b, &err), SS_OK, "%s", err.message);
  for (int sl = 0; sl < 2; ++sl) {
    for (int i = 0; i < NB; ++i) {
      f->model[3][sl][i] = bin_mean(f, dipole_at, b, sl, i);
    }
  }
  ss_bssrdf_destroy(b);
}

/* Distances of the table (mean free paths), and the RMS window. */
static const double at[5] = {1.0, 2.0, 3.0, 4.0, 5.0};
#define RMS_LO 1.5
#define RMS_HI 4.5

/* The relative error of `model` against the reference at distance d along
 * slice s (the two mirror bins nearest d, averaged) and the reference's
 * standard error relative to its value there; 0 when d is beyond the bins. */
typedef struct {
  double rel, sigma;
} rel_error;

static rel_error rel_at(const fig10 *f, const double model[NB], int s, double d) {
  int k = (int)lround(d / bin_width(f));
  if (k > NB / 2) {
    return (rel_error){0.0, 0.0};
  }
  double m = 0.5 * (model[NB / 2 + k] + model[NB / 2 - k]);
  double r = 0.5 * (f->mc[s][NB / 2 + k] + f->mc[s][NB / 2 - k]);
  double e = 0.5 * hypot(f->mc_err[s][NB / 2 + k], f->mc_err[s][NB / 2 - k]);
  return (rel_error){m / r - 1.0, e / r};
}

/* The root mean square of the relative error over the bins whose centres
 * lie lo..hi from the spot along slice s. */
static double rms_over(const fig10 *f, const double model[NB], int s, double lo, double hi) {
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < NB; ++i) {
    double d = fabs(bin_centre(f, i));
    if (d >= lo && d <= hi) {
      double e = model[i] / f->mc[s][i] - 1.0;
      sum += e * e;
      ++n;
    }
  }
  return sqrt(sum / n);
}

static double rms(const fig10 *f, const double model[NB], int s) {
  return rms_over(f, model, s, RMS_LO, RMS_HI);
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
          fprintf(out, " %+.1f %% |", 100.0 * rel_at(&f[i], f[i].model[m][s], s, at[k]).rel);
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
        p->x[b] = bin_centre(&f[i], b) * 2.0 / 5.2482; /* cm */
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

/* The table goes to SUBSURF_VALIDATE_OUT (appended: both tests write it). */
static void append_table(void (*print)(FILE *, const fig10 *, int), const fig10 *f, int n) {
  print(stderr, f, n);
  const char *out = getenv("SUBSURF_VALIDATE_OUT");
  if (out) {
    FILE *file = fopen(out, "a");
    if (file) {
      print(file, f, n);
      fputc('\n', file);
      fclose(file);
    }
  }
}

Test(fem_fig10, finite_elements_match_the_flake_monte_carlo_outside_the_spot, .timeout = 3600) {
  static fig10 f[2] = {
      {.name = "fiber", .type = SS_FLAKE_FIBER, .p = 20.0, .scale = 1.0, .paths = 4000000},
      {.name = "surface", .type = SS_FLAKE_SURFACE, .p = 20.0, .scale = 1.0, .paths = 4000000}};
  for (int i = 0; i < 2; ++i) {
    fig10_init(&f[i]);
    run_monte_carlo(&f[i]);
    run_fem(&f[i], 0);
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
                    f[i].name, s ? 'y' : 'x', bin_centre(&f[i], b), f[i].mc[s][b],
                    f[i].mc_err[s][b], f[i].model[0][s][b], f[i].model[1][s][b],
                    f[i].model[2][s][b], f[i].model[3][s][b]);
      }
    }
  }
  append_table(print_table, f, 2);
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
    int j = (int)lround(d / bin_width(&f[0]));
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
        cr_expect_lt(f[i].rms[m][s], f[i].rms[0][s], "%s, slice %d: %s %g, boundary %g", f[i].name,
                     s, model_name[m], f[i].rms[m][s], f[i].rms[0][s]);
      }
    }
  }
  /* The similarity relation moves the surface-like flakes' sources deeper
   * (they keep the light going down: w.g = 0.83 at normal incidence) and
   * cuts their error on both slices by at least a quarter (measured: 27 to
   * 19 % along x, 155 to 88 % along y). */
  for (int s = 0; s < 2; ++s) {
    cr_expect_lt(f[1].rms[2][s], 0.75 * f[1].rms[1][s],
                 "surface, slice %d: similarity %g, "
                 "sigma_t(w) %g",
                 s, f[1].rms[2][s], f[1].rms[1][s]);
  }
  for (int k = 1; k < 4; ++k) {
    cr_expect(rel_at(&f[0], f[0].model[0][0], 0, at[k]).rel > 1.0, "fiber along x at %g", at[k]);
    cr_expect(rel_at(&f[1], f[1].model[0][1], 1, at[k]).rel > 1.0, "surface along y at %g", at[k]);
  }
}

/* Where diffusion applies: the same cube and spot, the FEM with
 * the similarity-reduced volume source (as `subsurf fem`), against the Monte
 * Carlo, over the flakes' anisotropy at the paper's size (uniform flakes,
 * p = 1, 5, 20) and over the optical size at p = 20 (a rho times 1 and 4).
 * Jakob2010's conclusion: diffusion "applies only when radiance becomes
 * uniform in direction, which happens only ... far from the source -- and
 * these are satisfied more quickly the lower the degree of anisotropy". */
#define SWEEP_PATHS 1000000
enum { UNI, FIB1, FIB5, FIB20, SUR1, SUR5, SUR20, FIB20_THICK, SUR20_THICK, NSWEEP };
#define NDIST 7
/* The distances of the optical-size table, in transport mean free paths
 * 3 / M_ii of the slice's axis. */
static const double ltr_at[NDIST] = {0.5, 1.0, 1.5, 2.0, 4.0, 8.0, 16.0};

static const char *const slice_name[2] = {"x", "y"};

/* A distribution's cases and the slice along its fast axis (the fibres'
 * x, the surface-like flakes' y). */
typedef struct {
  int p1, p5, p20, p20_thick, fast_slice;
} flake_family;
static const flake_family family[2] = {{FIB1, FIB5, FIB20, FIB20_THICK, 0},
                                       {SUR1, SUR5, SUR20, SUR20_THICK, 1}};

/* The relative error at d transport mean free paths of slice s's axis,
 * when inside 0.85 of the half side (else NAN). */
static rel_error rel_at_ltr(const fig10 *f, int s, double d) {
  double x = d * f->ltr[s];
  if (x > 0.85 * 0.5 * f->side) {
    return (rel_error){NAN, NAN};
  }
  return rel_at(f, f->model[FEM_SIMILARITY][s], s, x);
}

static void print_rel(FILE *out, rel_error e) {
  if (isnan(e.rel)) {
    fprintf(out, " - |");
  } else {
    fprintf(out, " %+.0f +- %.0f %% |", 100.0 * e.rel, 100.0 * e.sigma);
  }
}

static void print_flakes(FILE *out, const fig10 *f) {
  if (f->type == SS_FLAKE_UNIFORM) {
    fprintf(out, "| uniform |");
  } else {
    fprintf(out, "| %s, p = %g |", f->name, f->p);
  }
}

static void print_anisotropy_table(FILE *out, const fig10 *f, int n) {
  fprintf(out,
          "| flakes | 3 / M_ii along x, y, z (mfp; / side) | slice | 2 mfp | 3 mfp | 4 mfp "
          "| RMS %g-%g mfp | top-face reflectance MC / FEM |\n"
          "|---|---|---|---|---|---|---|---|\n",
          RMS_LO, RMS_HI);
  for (int i = 0; i < n; ++i) {
    if (f[i].scale != 1.0) {
      continue;
    }
    for (int s = 0; s < 2; ++s) {
      print_flakes(out, &f[i]);
      fprintf(out, " %.2f, %.2f, %.2f (%.2f, %.2f, %.2f) | %s |", f[i].ltr[0], f[i].ltr[1],
              f[i].ltr[2], f[i].ltr[0] / f[i].side, f[i].ltr[1] / f[i].side,
              f[i].ltr[2] / f[i].side, slice_name[s]);
      for (int k = 1; k < 4; ++k) {
        print_rel(out, rel_at(&f[i], f[i].model[FEM_SIMILARITY][s], s, at[k]));
      }
      fprintf(out, " %.1f %% | %.3f / %.3f |\n", 100.0 * f[i].rms[FEM_SIMILARITY][s], f[i].mc_total,
              f[i].fem_top);
    }
  }
}

static void print_size_table(FILE *out, const fig10 *f, int n) {
  fprintf(out, "| flakes | a rho x | side (mfp) | slice | 3 / M_ii of the slice's axis (mfp; / "
               "side) |");
  for (int k = 0; k < NDIST; ++k) {
    fprintf(out, " %g |", ltr_at[k]);
  }
  fprintf(out, " top-face reflectance MC / FEM |\n|---|---|---|---|---|");
  for (int k = 0; k <= NDIST; ++k) {
    fprintf(out, "---|");
  }
  fprintf(out, "\n");
  for (int i = 0; i < n; ++i) {
    if (f[i].p != 20.0) {
      continue;
    }
    for (int s = 0; s < 2; ++s) {
      print_flakes(out, &f[i]);
      fprintf(out, " %g | %.1f | %s | %.2f (%.2f) |", f[i].scale, f[i].side, slice_name[s],
              f[i].ltr[s], f[i].ltr[s] / f[i].side);
      for (int k = 0; k < NDIST; ++k) {
        print_rel(out, rel_at_ltr(&f[i], s, ltr_at[k]));
      }
      fprintf(out, " %.3f / %.3f |\n", f[i].mc_total, f[i].fem_top);
    }
  }
}

static void print_sweep_tables(FILE *out, const fig10 *f, int n) {
  print_anisotropy_table(out, f, n);
  fprintf(out, "\n");
  print_size_table(out, f, n);
}

Test(fem_fig10, diffusion_applies_where_the_flakes_are_mildly_anisotropic, .timeout = 3600) {
  static fig10 f[NSWEEP] = {
      [UNI] = {.name = "uniform", .type = SS_FLAKE_UNIFORM, .p = 0.0, .scale = 1.0},
      [FIB1] = {.name = "fiber", .type = SS_FLAKE_FIBER, .p = 1.0, .scale = 1.0},
      [FIB5] = {.name = "fiber", .type = SS_FLAKE_FIBER, .p = 5.0, .scale = 1.0},
      [FIB20] = {.name = "fiber", .type = SS_FLAKE_FIBER, .p = 20.0, .scale = 1.0},
      [SUR1] = {.name = "surface", .type = SS_FLAKE_SURFACE, .p = 1.0, .scale = 1.0},
      [SUR5] = {.name = "surface", .type = SS_FLAKE_SURFACE, .p = 5.0, .scale = 1.0},
      [SUR20] = {.name = "surface", .type = SS_FLAKE_SURFACE, .p = 20.0, .scale = 1.0},
      [FIB20_THICK] = {.name = "fiber", .type = SS_FLAKE_FIBER, .p = 20.0, .scale = 4.0},
      [SUR20_THICK] = {.name = "surface", .type = SS_FLAKE_SURFACE, .p = 20.0, .scale = 4.0}};
  for (int i = 0; i < NSWEEP; ++i) {
    f[i].paths = SWEEP_PATHS;
    fig10_init(&f[i]);
    run_monte_carlo(&f[i]);
    run_fem(&f[i], FEM_SIMILARITY);
    for (int s = 0; s < 2; ++s) {
      f[i].rms[FEM_SIMILARITY][s] = rms(&f[i], f[i].model[FEM_SIMILARITY][s], s);
    }
    cr_log_info("%s p = %g, a rho x %g: %zu tetrahedra; top-face reflectance MC %.4f, FEM %.4f",
                f[i].name, f[i].p, f[i].scale, f[i].tets, f[i].mc_total, f[i].fem_top);
  }
  append_table(print_sweep_tables, f, NSWEEP);
  /* Where diffusion applies at the paper's size: uniform flakes and p = 1
   * (3 / M_ii 0.67-1.33 mfp, 8-16 of them across the cube), on both slices
   * within the isotropic set-up's own error (measured RMS over 1.5-4.5 mfp
   * 8-20 %, uniform flakes 13 %; top-face reflectance within 2.6 %; a
   * source 20 % too strong fails both). */
  const int mild[3] = {UNI, FIB1, SUR1};
  for (int i = 0; i < 3; ++i) {
    const fig10 *fi = &f[mild[i]];
    for (int s = 0; s < 2; ++s) {
      cr_expect_lt(fi->rms[FEM_SIMILARITY][s], 0.25, "%s p = %g, slice %s: RMS %g", fi->name, fi->p,
                   slice_name[s], fi->rms[FEM_SIMILARITY][s]);
    }
    cr_expect_lt(fabs(fi->fem_top / fi->mc_total - 1.0), 0.05, "%s p = %g: top face FEM %g, MC %g",
                 fi->name, fi->p, fi->fem_top, fi->mc_total);
  }
  /* Across the fast axis up to p = 5 as well (measured 11-16 %). */
  for (int t = 0; t < 2; ++t) {
    const fig10 *f5 = &f[family[t].p5];
    int slow = 1 - family[t].fast_slice;
    cr_expect_lt(f5->rms[FEM_SIMILARITY][slow], 0.25, "%s p = 5, %s: %g", f5->name,
                 slice_name[slow], f5->rms[FEM_SIMILARITY][slow]);
  }
  /* Along the fast axis the error grows with the anisotropy (Jakob2010's
   * conclusion; measured fibres along x 20 / 43 / 117 %, surface-like along
   * y 19 / 27 / 86 % for p = 1 / 5 / 20). */
  for (int t = 0; t < 2; ++t) {
    const flake_family *fa = &family[t];
    int s = fa->fast_slice;
    double e1 = f[fa->p1].rms[FEM_SIMILARITY][s], e5 = f[fa->p5].rms[FEM_SIMILARITY][s];
    double e20 = f[fa->p20].rms[FEM_SIMILARITY][s];
    cr_expect_gt(e5, 1.2 * e1, "%s along %s: p = 5 %g, p = 1 %g", f[fa->p1].name, slice_name[s], e5,
                 e1);
    cr_expect_gt(e20, 1.5 * e5, "%s along %s: p = 20 %g, p = 5 %g", f[fa->p1].name, slice_name[s],
                 e20, e5);
  }
  /* Optically 4 times thicker (42 mfp, 5.5 transport mean free paths along
   * the fast axis), the error half a fast transport mean free path from the
   * spot falls (measured fibres 138 -> 99 %, surface-like 79 -> 46 %) ... */
  for (int t = 0; t < 2; ++t) {
    const flake_family *fa = &family[t];
    int s = fa->fast_slice;
    double e1 = rel_at_ltr(&f[fa->p20], s, 0.5).rel, e4 = rel_at_ltr(&f[fa->p20_thick], s, 0.5).rel;
    cr_expect_lt(e4, 0.8 * e1, "%s along %s at 0.5 transport mfp: a rho x 4 %g, x 1 %g",
                 f[fa->p20].name, slice_name[s], e4, e1);
  }
  /* ... the surface-like flakes then agree along the fast axis from 1 to 2
   * of its transport mean free paths (measured +20, +1, -8 %) and their
   * top-face reflectance error falls (+40 % -> +15 %) ... */
  for (int k = 1; k <= 3; ++k) {
    rel_error e = rel_at_ltr(&f[SUR20_THICK], 1, ltr_at[k]);
    cr_expect_lt(fabs(e.rel), 0.3, "surface, a rho x 4, y at %g transport mfp: %g", ltr_at[k],
                 e.rel);
  }
  const fig10 *s1 = &f[SUR20], *s4 = &f[SUR20_THICK];
  cr_expect_lt(fabs(s4->fem_top / s4->mc_total - 1.0), 0.5 * fabs(s1->fem_top / s1->mc_total - 1.0),
               "surface top face: a rho x 4 FEM %g MC %g, x 1 FEM %g MC %g", s4->fem_top,
               s4->mc_total, s1->fem_top, s1->mc_total);
  /* ... and the fibres across their axis at 8 transport mean free paths of
   * y (measured -6 +- 4 %); but along the fibres on the top face the
   * finite elements stay far too bright at 1-2 transport mean free paths
   * (measured +89, +73, +62 %; docs/fem.md: the light under the top face
   * keeps to the fibres' direction, and the unbounded medium is within 11 %
   * of diffusion there, test_flake_diffusion_range.c). */
  cr_expect_lt(fabs(rel_at_ltr(&f[FIB20_THICK], 1, 8.0).rel), 0.2, "fiber, a rho x 4, y at 8: %g",
               rel_at_ltr(&f[FIB20_THICK], 1, 8.0).rel);
  for (int k = 1; k <= 3; ++k) {
    rel_error e = rel_at_ltr(&f[FIB20_THICK], 0, ltr_at[k]);
    cr_expect_gt(e.rel, 0.4, "fiber, a rho x 4, x at %g transport mfp: %g", ltr_at[k], e.rel);
  }
}
