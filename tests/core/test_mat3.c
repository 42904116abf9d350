/* 3 x 3 matrices: the Jacobi eigendecomposition reconstructs the matrix with
 * orthonormal eigenvectors, the symmetric square root squares back, the
 * cofactor inverse is an inverse, the determinant is multiplicative. */
#include "subsurf/mat3.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>

static ss_mat3 random_matrix(ss_rng *rng) {
  ss_mat3 a;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      a.m[i][j] = 2.0 * ss_rng_uniform(rng) - 1.0;
    }
  }
  return a;
}

/* A random symmetric positive definite matrix: B B^T + eps I, with
 * condition numbers up to about 1e6. */
static ss_mat3 random_spd(ss_rng *rng) {
  ss_mat3 b = random_matrix(rng);
  double eps = pow(10.0, -6.0 * ss_rng_uniform(rng));
  return ss_mat3_add(ss_mat3_mul(b, ss_mat3_transpose(b)), ss_mat3_scale(ss_mat3_identity(), eps));
}

Test(mat3, jacobi_eigendecomposition_reconstructs_the_matrix) {
  ss_rng rng;
  ss_rng_seed(&rng, 11, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    ss_mat3 a = random_matrix(&rng);
    a = ss_mat3_add(a, ss_mat3_transpose(a));
    double lambda[3];
    ss_mat3 q;
    ss_mat3_sym_eigen(a, lambda, &q);
    cr_assert(lambda[0] <= lambda[1] && lambda[1] <= lambda[2]);
    ss_mat3 l = {{{lambda[0], 0, 0}, {0, lambda[1], 0}, {0, 0, lambda[2]}}};
    ss_mat3 back = ss_mat3_mul(q, ss_mat3_mul(l, ss_mat3_transpose(q)));
    cr_assert_lt(ss_mat3_max_abs_diff(back, a), 1e-14 * 8.0, "trial %d", trial);
    cr_assert_lt(ss_mat3_max_abs_diff(ss_mat3_mul(ss_mat3_transpose(q), q), ss_mat3_identity()),
                 1e-14, "trial %d", trial);
  }
}

Test(mat3, eigendecomposition_of_a_diagonal_or_degenerate_matrix_is_exact) {
  ss_mat3 a = {{{3.0, 0, 0}, {0, 1.0, 0}, {0, 0, 2.0}}};
  double lambda[3];
  ss_mat3 q;
  ss_mat3_sym_eigen(a, lambda, &q);
  cr_assert(lambda[0] == 1.0 && lambda[1] == 2.0 && lambda[2] == 3.0);
  ss_mat3 i3 = ss_mat3_scale(ss_mat3_identity(), 5.0);
  ss_mat3_sym_eigen(i3, lambda, &q);
  cr_assert(lambda[0] == 5.0 && lambda[2] == 5.0);
  cr_assert_eq(ss_mat3_max_abs_diff(q, ss_mat3_identity()), 0.0);
}

Test(mat3, symmetric_square_root_squares_back_and_inverts) {
  ss_rng rng;
  ss_rng_seed(&rng, 12, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    ss_mat3 a = random_spd(&rng), p, pinv;
    cr_assert(ss_mat3_sym_power(a, 0.5, &p));
    cr_assert(ss_mat3_sym_power(a, -0.5, &pinv));
    cr_assert_lt(ss_mat3_max_abs_diff(ss_mat3_mul(p, p), a), 1e-13 * 4.0, "trial %d", trial);
    cr_assert_lt(ss_mat3_max_abs_diff(ss_mat3_transpose(p), p), 1e-15 * 4.0);
    /* P has a condition number up to about 1e3. */
    cr_assert_lt(ss_mat3_max_abs_diff(ss_mat3_mul(p, pinv), ss_mat3_identity()), 1e-11, "trial %d",
                 trial);
  }
  ss_mat3 neg = ss_mat3_scale(ss_mat3_identity(), -1.0), out;
  cr_assert_not(ss_mat3_sym_power(neg, 0.5, &out));
  ss_mat3 singular = {{{1, 0, 0}, {0, 0, 0}, {0, 0, 1}}};
  cr_assert_not(ss_mat3_sym_power(singular, -0.5, &out));
}

Test(mat3, cofactor_inverse_is_an_inverse_and_det_is_multiplicative) {
  ss_rng rng;
  ss_rng_seed(&rng, 13, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    ss_mat3 a = random_matrix(&rng), b = random_matrix(&rng), inv;
    double da = ss_mat3_det(a), db = ss_mat3_det(b), dab = ss_mat3_det(ss_mat3_mul(a, b));
    cr_assert_float_eq(dab, da * db, 1e-13 * 8.0);
    if (fabs(da) > 1e-3) {
      cr_assert(ss_mat3_inverse(a, &inv));
      cr_assert_lt(ss_mat3_max_abs_diff(ss_mat3_mul(a, inv), ss_mat3_identity()), 1e-10, "trial %d",
                   trial);
    }
  }
  ss_mat3 singular = {{{1, 2, 3}, {2, 4, 6}, {0, 0, 1}}}, inv;
  cr_assert_not(ss_mat3_inverse(singular, &inv));
}
