/* The micro-flake diffusion coefficients (Jakob et al. 2010, section 5.3):
 * uniform flakes give the isotropic diffusion equation (M = 3 sigma_t' I,
 * mu0 / (4 pi) = sigma_a), the second moment matches its closed forms about
 * the axis, M is symmetric positive definite over a grid of distributions,
 * axes and albedos, rotating the axis rotates M, and the albedo constants of
 * eq. 29, 32, 33 match a quadrature. */
#include "subsurf/flake_diffusion.h"
#include "subsurf/quadrature.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include "optics/flake_init.h"

#include <criterion/criterion.h>
#include <math.h>

static const ss_flake_albedo white = {1.0, 1.0, 0.0};

static ss_vec3 random_direction(ss_rng *rng) {
  return ss_spherical_direction(2.0 * ss_rng_uniform(rng) - 1.0, 2.0 * SS_PI * ss_rng_uniform(rng));
}

Test(flake_diffusion, uniform_flakes_give_the_isotropic_diffusion_equation) {
  ss_rng rng;
  ss_rng_seed(&rng, 34, 1);
  for (int trial = 0; trial < 6; ++trial) {
    double sigma_s = pow(10.0, 3.0 * ss_rng_uniform(&rng) - 1.5);
    double sigma_a = sigma_s * pow(10.0, 4.0 * ss_rng_uniform(&rng) - 4.0);
    double albedo = sigma_s / (sigma_s + sigma_a);
    ss_microflake mf;
    ss_flake_albedo a = {albedo, albedo, 0.0};
    init_flakes(&mf, SS_FLAKE_UNIFORM, 0.0, random_direction(&rng), a);
    double density = ss_flake_medium_density(sigma_s, sigma_a);
    ss_mat3 m = ss_flake_diffusion_matrix(&mf, density);
    /* Isotropic scattering (g = 0): sigma_t' = sigma_t. */
    ss_mat3 want = ss_mat3_scale(ss_mat3_identity(), 3.0 * (sigma_s + sigma_a));
    cr_assert_lt(ss_mat3_max_abs_diff(m, want), 1e-13 * 3.0 * (sigma_s + sigma_a), "trial %d",
                 trial);
    double mu0 = ss_flake_diffusion_mu0(&mf, density);
    cr_assert_float_eq(mu0 / (4.0 * SS_PI), sigma_a, 1e-12 * (sigma_s + sigma_a), "trial %d",
                       trial);
  }
}

/* About the axis, mu2 = (1 - b)/2 (I - v v^T) + b v v^T with
 * b = int (m.v)^2 D: surface-like (p + 1)/(p + 3), fibre-like 1/(p + 3)
 * (the ratio of two beta functions). */
Test(flake_diffusion, second_moment_matches_its_closed_form) {
  const double ps[] = {0.0, 0.5, 1.0, 3.0, 7.3, 20.0, 20.5, 100.0, 1000.0};
  ss_vec3 axis = ss_vec3_normalize(ss_vec3_make(1.0, -2.0, 0.5));
  for (int t = 0; t < 2; ++t) {
    ss_flake_type type = t == 0 ? SS_FLAKE_SURFACE : SS_FLAKE_FIBER;
    for (size_t k = 0; k < sizeof ps / sizeof ps[0]; ++k) {
      ss_microflake mf;
      init_flakes(&mf, type, ps[k], axis, white);
      double b = t == 0 ? (ps[k] + 1.0) / (ps[k] + 3.0) : 1.0 / (ps[k] + 3.0);
      ss_mat3 vv = ss_mat3_outer(axis, axis);
      ss_mat3 want = ss_mat3_add(
          ss_mat3_scale(ss_mat3_add(ss_mat3_identity(), ss_mat3_scale(vv, -1.0)), 0.5 * (1 - b)),
          ss_mat3_scale(vv, b));
      ss_mat3 mu2 = ss_flake_second_moment(&mf);
      cr_assert_lt(ss_mat3_max_abs_diff(mu2, want), 1e-10, "%s p %g: off by %.3g",
                   ss_flake_type_name(type), ps[k], ss_mat3_max_abs_diff(mu2, want));
    }
  }
}

static int is_spd(ss_mat3 m, double *min_eigen) {
  double lambda[3];
  ss_mat3 q;
  ss_mat3_sym_eigen(m, lambda, &q);
  *min_eigen = lambda[0];
  return ss_mat3_max_abs_diff(m, ss_mat3_transpose(m)) <= 1e-14 * fabs(lambda[2]) &&
         lambda[0] > 0.0;
}

/* Section 5.3: M is positive definite because c1, c2 >= 0, c1 <= 1/2 and
 * mu2 is; its smallest eigenvalue is at least (9 a rho / 8)(1 - 2 c1). */
Test(flake_diffusion, diffusion_matrix_is_symmetric_positive_definite) {
  const ss_flake_type types[] = {SS_FLAKE_UNIFORM, SS_FLAKE_SURFACE, SS_FLAKE_FIBER};
  const double ps[] = {0.0, 4.5, 20.0, 1000.0};
  const ss_flake_albedo albedos[] = {
      {1.0, 1.0, 0.0}, {0.3, 0.3, 0.0}, {0.0, 0.0, 0.0}, {0.2, 0.95, 3.0}};
  ss_rng rng;
  ss_rng_seed(&rng, 35, 1);
  for (int t = 0; t < 2; ++t) {
    for (int k = 0; k < 4; ++k) {
      for (int a = 0; a < 2; ++a) {
        ss_microflake mf;
        init_flakes(&mf, types[t], ps[k], random_direction(&rng), albedos[a]);
        double density = 0.7, min_eigen;
        ss_mat3 m = ss_flake_diffusion_matrix(&mf, density);
        cr_assert(is_spd(m, &min_eigen), "%s p %g albedo %d: smallest eigenvalue %g",
                  ss_flake_type_name(types[t]), ps[k], a, min_eigen);
        ss_flake_albedo_moments c = ss_flake_albedo_constants(&mf);
        cr_assert_geq(min_eigen, 9.0 * density / 8.0 * (1.0 - 2.0 * c.c1) * (1.0 - 1e-12));
      }
    }
  }
}

Test(flake_diffusion, rotating_the_axis_rotates_the_diffusion_matrix) {
  ss_rng rng;
  ss_rng_seed(&rng, 36, 1);
  for (int trial = 0; trial < 6; ++trial) {
    ss_flake_type type = trial % 2 ? SS_FLAKE_FIBER : SS_FLAKE_SURFACE;
    double p = 30.0 * ss_rng_uniform(&rng);
    ss_vec3 v = random_direction(&rng);
    /* A rotation R: the frame of a random direction. */
    ss_frame f = ss_frame_from_normal(random_direction(&rng));
    ss_mat3 r = {{{f.s.x, f.t.x, f.n.x}, {f.s.y, f.t.y, f.n.y}, {f.s.z, f.t.z, f.n.z}}};
    ss_microflake a, b;
    ss_flake_albedo alb = {0.9, 0.9, 0.0};
    init_flakes(&a, type, p, v, alb);
    init_flakes(&b, type, p, ss_mat3_apply(r, v), alb);
    ss_mat3 ma = ss_flake_diffusion_matrix(&a, 2.0), mb = ss_flake_diffusion_matrix(&b, 2.0);
    ss_mat3 rotated = ss_mat3_mul(r, ss_mat3_mul(ma, ss_mat3_transpose(r)));
    cr_assert_lt(ss_mat3_max_abs_diff(mb, rotated), 1e-12, "%s p %g: off by %.3g",
                 ss_flake_type_name(type), p, ss_mat3_max_abs_diff(mb, rotated));
  }
}

typedef struct {
  const ss_microflake *mf;
  int which;
} albedo_ctx;

/* Eq. 29, 32, 33 over theta in [0, pi] as the paper writes them. */
static double albedo_integrand(void *vctx, double theta) {
  albedo_ctx *x = vctx;
  double c = fabs(cos(theta)), s = sin(theta), a = ss_microflake_albedo(x->mf, c);
  return x->which == 0 ? a * c * s : (x->which == 1 ? a * c * s * s * s : 2.0 * a * c * c * c * s);
}

Test(flake_diffusion, albedo_constants_match_their_integrals) {
  const ss_flake_albedo albedos[] = {
      {0.8, 0.8, 0.0}, {0.1, 0.9, 1.0}, {0.5, 1.0, 2.5}, {0.0, 0.7, 20.0}};
  for (int a = 0; a < 4; ++a) {
    ss_microflake mf;
    init_flakes(&mf, SS_FLAKE_UNIFORM, 0.0, ss_vec3_make(0, 0, 1), albedos[a]);
    ss_flake_albedo_moments c = ss_flake_albedo_constants(&mf);
    double got[3] = {c.alpha_hat, c.c1, c.c2};
    for (int k = 0; k < 3; ++k) {
      albedo_ctx x = {&mf, k};
      double want = ss_gl_integrate(albedo_integrand, &x, 0.0, 0.5 * SS_PI, 64) +
                    ss_gl_integrate(albedo_integrand, &x, 0.5 * SS_PI, SS_PI, 64);
      cr_assert_float_eq(got[k], want, 1e-7, "albedo %d constant %d: %.10f vs %.10f", a, k, got[k],
                         want);
    }
  }
}
