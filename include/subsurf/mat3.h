/* 3 x 3 matrices for anisotropic diffusion (diffusion matrices, their square
 * roots and inverses): plain structs passed by value, row-major. */
#ifndef SUBSURF_MAT3_H
#define SUBSURF_MAT3_H

#include "subsurf/vec3.h"

typedef struct {
  double m[3][3];
} ss_mat3;

ss_mat3 ss_mat3_identity(void);
ss_mat3 ss_mat3_scale(ss_mat3 a, double k);
ss_mat3 ss_mat3_add(ss_mat3 a, ss_mat3 b);
ss_mat3 ss_mat3_mul(ss_mat3 a, ss_mat3 b);
ss_mat3 ss_mat3_transpose(ss_mat3 a);
/* a b^T */
ss_mat3 ss_mat3_outer(ss_vec3 a, ss_vec3 b);
ss_vec3 ss_mat3_apply(ss_mat3 a, ss_vec3 v);
double ss_mat3_det(ss_mat3 a);
/* max_ij |a_ij - b_ij| */
double ss_mat3_max_abs_diff(ss_mat3 a, ss_mat3 b);
/* The inverse by cofactors; 0 when a is singular (|det| below 1e-300 or not
 * finite), *inv untouched. */
int ss_mat3_inverse(ss_mat3 a, ss_mat3 *inv);

/* Eigendecomposition a = Q diag(lambda) Q^T of a symmetric matrix by cyclic
 * Jacobi rotations (Golub & Van Loan, Matrix Computations, sec. 8.5), to
 * rounding: lambda ascending, Q's columns the unit eigenvectors. Reads the
 * upper triangle only. */
void ss_mat3_sym_eigen(ss_mat3 a, double lambda[3], ss_mat3 *q);

/* Q f(Lambda) Q^T for a symmetric positive semi-definite a: its square root
 * (power 0.5) or inverse square root (power -0.5). Returns 0 when an
 * eigenvalue is not positive (for power < 0) or negative. */
int ss_mat3_sym_power(ss_mat3 a, double power, ss_mat3 *out);

#endif
