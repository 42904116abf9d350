/* Finite elements against the Monte Carlo reference on a large homogeneous
 * isotropic block: a small diffuse spot (radius 0.25) on the top
 * of a 24 x 24 x 12 block (sigma_s = 1, sigma_a = 0.01, g = 0, index
 * matched), the radial exitance of ss_halfspace_run (exact free flights and
 * isotropic scattering in the same box, cosine-distributed incidence over
 * the disc, light through the sides and the bottom counted as transmitted)
 * against the FEM with the spot's rays as volume source (fem_rays.c, as
 * `subsurf fem` by default: 2 x 6^2 disc points x 72 cosine-distributed
 * directions, extinction sigma_t, power alpha) averaged over the same
 * annuli. Near the spot the diffusion approximation fails (the light there
 * has scattered a few times). Measured (Monte Carlo standard errors 0.3-0.6
 * %): FEM/MC - 1 = -31 % at 0.27 mfp, -0.8 % at 0.5, +16 % at 1.3-1.7,
 * +12 % at 2.7, +10.5 % at 3.2, +9.0 % at 3.7, +7.3 % at 4.3, +5.2 % at
 * 5.1, +3.1 % at 5.9, +2.1 % at 6.9, +0.8 % at 8.0, -1.9 % at 9.4; the
 * top-face reflectance 0.852 against the Monte Carlo's 0.779. The test asks
 * 10 % from 3.5 mfp and 5 % from 5.5 mfp, to 9.5 mfp (the sides are 12
 * away), or 3 standard errors. Slow (make validate, 80 s wall under load,
 * 16 CPU s). */
#include "fem/iso_medium.h"
#include "subsurf/fem.h"
#include "subsurf/halfspace.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#define WIDTH 24.0
#define THICKNESS 12.0
#define SPOT 0.25
#define SIGMA_S 1.0
#define SIGMA_A 0.01

static double sigma_t(void *ctx, ss_vec3 w) { return SIGMA_S + SIGMA_A; }

/* The FEM exitance averaged over the annulus [lo, hi] about the origin
 * (8 equal-area rings x 16 angles). */
static double annulus_mean(const ss_fem_mesh *m, const double *exitance, double lo, double hi) {
  double sum = 0.0;
  for (int i = 0; i < 8; ++i) {
    double r = sqrt(lo * lo + (hi * hi - lo * lo) * (i + 0.5) / 8.0);
    for (int k = 0; k < 16; ++k) {
      double a = 2.0 * SS_PI * (k + 0.5 * (i & 1)) / 16.0, v = 0.0;
      cr_assert(ss_fem_interpolate(m, exitance, ss_vec3_make(r * cos(a), r * sin(a), 0.0), &v));
      sum += v;
    }
  }
  return sum / (8.0 * 16.0);
}

Test(fem_vs_halfspace, spot_exitance_matches_the_monte_carlo_beyond_a_few_mean_free_paths,
     .timeout = 3600) {
  ss_error err = {0};
  ss_halfspace_params p;
  ss_halfspace_params_default(&p);
  p.medium.sigma_s = ss_rgb_gray(SIGMA_S);
  p.medium.sigma_a = ss_rgb_gray(SIGMA_A);
  p.thickness = THICKNESS;
  p.width = WIDTH;
  p.spot_radius = SPOT;
  p.paths = 2000000;
  p.seed = 16;
  p.rmin = 0.25;
  p.rmax = 10.0;
  p.rbins = 25;
  ss_halfspace_result *mc = NULL;
  cr_assert_eq(ss_halfspace_run(&p, &mc, &err), SS_OK, "%s", err.message);

  ss_fem_mesh_options mo = {.size_max = 1.0,
                            .size_min = 0.1,
                            .refine_center = ss_vec3_make(0, 0, 0),
                            .refine_radius = 1.0,
                            .refine_grade = 8.0};
  ss_fem_mesh *m = NULL;
  cr_assert_eq(ss_fem_mesh_box(ss_vec3_make(-0.5 * WIDTH, -0.5 * WIDTH, -THICKNESS),
                               ss_vec3_make(0.5 * WIDTH, 0.5 * WIDTH, 0.0), &mo, &m, &err),
               SS_OK, "%s", err.message);
  ss_fem_ray *rays = NULL;
  size_t num_rays = 0;
  double alpha = SIGMA_S / (SIGMA_S + SIGMA_A);
  cr_assert_eq(ss_fem_spot_rays(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, 1), SPOT, alpha, 1, 6, 6,
                                sigma_t, NULL, &rays, &num_rays, &err),
               SS_OK, "%s", err.message);
  iso_medium med = {SIGMA_S, SIGMA_A};
  ss_fem_problem pb = {.eta = 1.0, .rays = rays, .num_rays = num_rays};
  ss_fem_solve_options so = {.solver = SS_FEM_PCG, .tolerance = 1e-10, .max_iterations = 100000};
  ss_fem_solution *s = NULL;
  cr_assert_eq(ss_fem_solve(m, iso, &med, &pb, &so, &s, &err), SS_OK, "%s", err.message);
  cr_log_info("%zu tetrahedra; top-face reflectance: Monte Carlo %.4f +- %.4f, FEM %.4f",
              m->num_tets, mc->reflectance.value, mc->reflectance.error, s->escaped);
  double st = SIGMA_S + SIGMA_A;
  for (int k = 1; k < mc->rbins; ++k) {
    double lo = mc->r_lo[k], hi = mc->r_hi[k], mid = sqrt(lo * hi) * st;
    double fem = annulus_mean(m, s->exitance, lo, hi);
    ss_estimate ref = mc->radial[k];
    double rel = fem / ref.value - 1.0, se = ref.error / ref.value;
    cr_log_info("r = %5.2f mfp: FEM %.4e, Monte Carlo %.4e +- %.1f %%, FEM/MC - 1 = %+.1f %%", mid,
                fem, ref.value, 100.0 * se, 100.0 * rel);
    if (mid >= 3.5 && mid <= 9.5) {
      double tol = mid >= 5.5 ? 0.05 : 0.10;
      cr_expect(fabs(rel) < fmax(tol, 3.0 * se), "r = %g mfp: FEM %g, Monte Carlo %g +- %g", mid,
                fem, ref.value, ref.error);
    }
  }
  ss_fem_solution_destroy(s);
  free(rays);
  ss_fem_mesh_destroy(m);
  ss_halfspace_result_destroy(mc);
}
