/* 3 x 3 matrices: products, cofactor inverse, Jacobi eigendecomposition. */
#include "subsurf/mat3.h"

#include <math.h>

ss_mat3 ss_mat3_identity(void) {
  ss_mat3 r = {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
  return r;
}

ss_mat3 ss_mat3_scale(ss_mat3 a, double k) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      a.m[i][j] *= k;
    }
  }
  return a;
}

ss_mat3 ss_mat3_add(ss_mat3 a, ss_mat3 b) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      a.m[i][j] += b.m[i][j];
    }
  }
  return a;
}

ss_mat3 ss_mat3_mul(ss_mat3 a, ss_mat3 b) {
  ss_mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    }
  }
  return r;
}

ss_mat3 ss_mat3_transpose(ss_mat3 a) {
  ss_mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = a.m[j][i];
    }
  }
  return r;
}

ss_mat3 ss_mat3_outer(ss_vec3 a, ss_vec3 b) {
  double u[3] = {a.x, a.y, a.z}, v[3] = {b.x, b.y, b.z};
  ss_mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r.m[i][j] = u[i] * v[j];
    }
  }
  return r;
}

ss_vec3 ss_mat3_apply(ss_mat3 a, ss_vec3 v) {
  return ss_vec3_make(a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
                      a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
                      a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z);
}

double ss_mat3_max_abs_diff(ss_mat3 a, ss_mat3 b) {
  double d = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      d = fmax(d, fabs(a.m[i][j] - b.m[i][j]));
    }
  }
  return d;
}

static double cofactor(ss_mat3 a, int i, int j) {
  int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  return a.m[i1][j1] * a.m[i2][j2] - a.m[i1][j2] * a.m[i2][j1];
}

double ss_mat3_det(ss_mat3 a) {
  return a.m[0][0] * cofactor(a, 0, 0) + a.m[0][1] * cofactor(a, 0, 1) +
         a.m[0][2] * cofactor(a, 0, 2);
}

int ss_mat3_inverse(ss_mat3 a, ss_mat3 *inv) {
  double det = ss_mat3_det(a);
  if (!isfinite(det) || !(fabs(det) > 1e-300)) {
    return 0;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      inv->m[j][i] = cofactor(a, i, j) / det;
    }
  }
  return 1;
}

/* One Jacobi rotation in the (p, q) plane that zeroes a_pq (Golub & Van
 * Loan, algorithm 8.5.1, the stable choice of t), accumulated into v. */
static void jacobi_rotate(double a[3][3], double v[3][3], int p, int q) {
  if (a[p][q] == 0.0) {
    return;
  }
  double tau = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
  double t = (tau >= 0.0 ? 1.0 : -1.0) / (fabs(tau) + sqrt(1.0 + tau * tau));
  double c = 1.0 / sqrt(1.0 + t * t), s = t * c;
  for (int k = 0; k < 3; ++k) {
    double akp = a[k][p], akq = a[k][q];
    a[k][p] = c * akp - s * akq;
    a[k][q] = s * akp + c * akq;
  }
  for (int k = 0; k < 3; ++k) {
    double apk = a[p][k], aqk = a[q][k];
    a[p][k] = c * apk - s * aqk;
    a[q][k] = s * apk + c * aqk;
  }
  for (int k = 0; k < 3; ++k) {
    double vkp = v[k][p], vkq = v[k][q];
    v[k][p] = c * vkp - s * vkq;
    v[k][q] = s * vkp + c * vkq;
  }
}

void ss_mat3_sym_eigen(ss_mat3 m, double lambda[3], ss_mat3 *q) {
  double a[3][3], v[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      a[i][j] = i <= j ? m.m[i][j] : m.m[j][i];
    }
  }
  /* Quadratic convergence: a handful of sweeps reach rounding; 32 bounds it. */
  for (int sweep = 0; sweep < 32; ++sweep) {
    double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
    double diag = fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2]);
    if (!(off > 1e-300) || off <= 1e-18 * diag) {
      break;
    }
    jacobi_rotate(a, v, 0, 1);
    jacobi_rotate(a, v, 0, 2);
    jacobi_rotate(a, v, 1, 2);
  }
  int order[3] = {0, 1, 2};
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (a[order[j]][order[j]] < a[order[i]][order[i]]) {
        int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
    }
  }
  for (int k = 0; k < 3; ++k) {
    lambda[k] = a[order[k]][order[k]];
    for (int i = 0; i < 3; ++i) {
      q->m[i][k] = v[i][order[k]];
    }
  }
}

int ss_mat3_sym_power(ss_mat3 a, double power, ss_mat3 *out) {
  double lambda[3];
  ss_mat3 q;
  ss_mat3_sym_eigen(a, lambda, &q);
  for (int k = 0; k < 3; ++k) {
    if (!isfinite(lambda[k]) || lambda[k] < 0.0 || (power < 0.0 && !(lambda[k] > 0.0))) {
      return 0;
    }
  }
  ss_mat3 r = {{{0.0}}};
  for (int k = 0; k < 3; ++k) {
    double f = pow(lambda[k], power);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        r.m[i][j] += f * q.m[i][k] * q.m[j][k];
      }
    }
  }
  *out = r;
  return 1;
}
