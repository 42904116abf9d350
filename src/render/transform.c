#include "subsurf/transform.h"

#include "subsurf/sampling.h"

#include <math.h>

ss_mat4 ss_mat4_identity(void) {
  ss_mat4 r = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
  return r;
}

ss_mat4 ss_mat4_mul(ss_mat4 a, ss_mat4 b) {
  ss_mat4 r;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) {
        s += a.m[i][k] * b.m[k][j];
      }
      r.m[i][j] = s;
    }
  }
  return r;
}

ss_mat4 ss_mat4_transpose(ss_mat4 a) {
  ss_mat4 r;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      r.m[i][j] = a.m[j][i];
    }
  }
  return r;
}

ss_mat4 ss_mat4_translate(ss_vec3 t) {
  ss_mat4 r = {{{1, 0, 0, t.x}, {0, 1, 0, t.y}, {0, 0, 1, t.z}, {0, 0, 0, 1}}};
  return r;
}

ss_mat4 ss_mat4_scale(ss_vec3 s) {
  ss_mat4 r = {{{s.x, 0, 0, 0}, {0, s.y, 0, 0}, {0, 0, s.z, 0}, {0, 0, 0, 1}}};
  return r;
}

/* Rodrigues' rotation formula in matrix form. */
ss_mat4 ss_mat4_rotate(double degrees, ss_vec3 axis) {
  ss_vec3 a = ss_vec3_normalize(axis);
  double th = degrees * (SS_PI / 180.0), s = sin(th), c = cos(th), t = 1.0 - c;
  ss_mat4 r = ss_mat4_identity();
  r.m[0][0] = c + a.x * a.x * t;
  r.m[0][1] = a.x * a.y * t - a.z * s;
  r.m[0][2] = a.x * a.z * t + a.y * s;
  r.m[1][0] = a.y * a.x * t + a.z * s;
  r.m[1][1] = c + a.y * a.y * t;
  r.m[1][2] = a.y * a.z * t - a.x * s;
  r.m[2][0] = a.z * a.x * t - a.y * s;
  r.m[2][1] = a.z * a.y * t + a.x * s;
  r.m[2][2] = c + a.z * a.z * t;
  return r;
}

int ss_mat4_look_at(ss_vec3 eye, ss_vec3 target, ss_vec3 up, ss_mat4 *out) {
  *out = ss_mat4_identity();
  ss_vec3 dir = ss_vec3_sub(target, eye);
  double len = ss_vec3_length(dir);
  if (!(len > 0.0) || !isfinite(len)) {
    return 0;
  }
  dir = ss_vec3_scale(dir, 1.0 / len);
  ss_vec3 right = ss_vec3_cross(dir, up);
  double rl = ss_vec3_length(right);
  if (!(rl > 1e-12 * ss_vec3_length(up))) {
    return 0;
  }
  right = ss_vec3_scale(right, 1.0 / rl);
  ss_vec3 new_up = ss_vec3_cross(right, dir);
  ss_vec3 cols[4] = {right, new_up, dir, eye};
  for (int j = 0; j < 4; ++j) {
    out->m[0][j] = cols[j].x;
    out->m[1][j] = cols[j].y;
    out->m[2][j] = cols[j].z;
  }
  return 1;
}

int ss_mat4_inverse(ss_mat4 a, ss_mat4 *inv) {
  ss_mat4 r = ss_mat4_identity();
  double scale = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (!isfinite(a.m[i][j])) {
        return 0;
      }
      scale = fmax(scale, fabs(a.m[i][j]));
    }
  }
  if (!(scale > 0.0)) {
    return 0;
  }
  for (int col = 0; col < 4; ++col) {
    int piv = col;
    for (int i = col + 1; i < 4; ++i) {
      if (fabs(a.m[i][col]) > fabs(a.m[piv][col])) {
        piv = i;
      }
    }
    if (!(fabs(a.m[piv][col]) > 1e-14 * scale)) {
      return 0;
    }
    if (piv != col) {
      for (int j = 0; j < 4; ++j) {
        double t = a.m[col][j];
        a.m[col][j] = a.m[piv][j];
        a.m[piv][j] = t;
        t = r.m[col][j];
        r.m[col][j] = r.m[piv][j];
        r.m[piv][j] = t;
      }
    }
    double d = 1.0 / a.m[col][col];
    for (int j = 0; j < 4; ++j) {
      a.m[col][j] *= d;
      r.m[col][j] *= d;
    }
    for (int i = 0; i < 4; ++i) {
      if (i == col) {
        continue;
      }
      double f = a.m[i][col];
      for (int j = 0; j < 4; ++j) {
        a.m[i][j] -= f * a.m[col][j];
        r.m[i][j] -= f * r.m[col][j];
      }
    }
  }
  *inv = r;
  return 1;
}

double ss_mat4_det3(ss_mat4 a) {
  return a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
         a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
         a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
}

ss_vec3 ss_mat4_apply_point(ss_mat4 a, ss_vec3 p) {
  double x = a.m[0][0] * p.x + a.m[0][1] * p.y + a.m[0][2] * p.z + a.m[0][3];
  double y = a.m[1][0] * p.x + a.m[1][1] * p.y + a.m[1][2] * p.z + a.m[1][3];
  double z = a.m[2][0] * p.x + a.m[2][1] * p.y + a.m[2][2] * p.z + a.m[2][3];
  double w = a.m[3][0] * p.x + a.m[3][1] * p.y + a.m[3][2] * p.z + a.m[3][3];
  if (w != 1.0) {
    return ss_vec3_make(x / w, y / w, z / w);
  }
  return ss_vec3_make(x, y, z);
}

ss_vec3 ss_mat4_apply_vector(ss_mat4 a, ss_vec3 v) {
  return ss_vec3_make(a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
                      a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
                      a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z);
}

ss_vec3 ss_mat4_apply_normal(ss_mat4 inverse, ss_vec3 n) {
  return ss_vec3_make(inverse.m[0][0] * n.x + inverse.m[1][0] * n.y + inverse.m[2][0] * n.z,
                      inverse.m[0][1] * n.x + inverse.m[1][1] * n.y + inverse.m[2][1] * n.z,
                      inverse.m[0][2] * n.x + inverse.m[1][2] * n.y + inverse.m[2][2] * n.z);
}
