/* 4x4 affine transforms (row-major, column vectors: p' = M p), plain structs
 * passed by value. Angles are in degrees, as in scene files. */
#ifndef SUBSURF_TRANSFORM_H
#define SUBSURF_TRANSFORM_H

#include "subsurf/vec3.h"

typedef struct {
  double m[4][4]; /* m[row][col] */
} ss_mat4;

ss_mat4 ss_mat4_identity(void);
/* a * b: applies b first, then a. */
ss_mat4 ss_mat4_mul(ss_mat4 a, ss_mat4 b);
ss_mat4 ss_mat4_transpose(ss_mat4 a);
ss_mat4 ss_mat4_translate(ss_vec3 t);
ss_mat4 ss_mat4_scale(ss_vec3 s);
/* Rotation by `degrees` about `axis` (any length > 0), right-handed. */
ss_mat4 ss_mat4_rotate(double degrees, ss_vec3 axis);
/* Camera-to-world matrix of a camera at `eye` looking at `target`: camera
 * space has +x to the image's right, +y to the image's up (the projection of
 * `up`), +z along the view direction. Returns 0 (and the identity) when eye ==
 * target or up is parallel to the view direction. */
int ss_mat4_look_at(ss_vec3 eye, ss_vec3 target, ss_vec3 up, ss_mat4 *out);
/* General 4x4 inverse (Gauss-Jordan with partial pivoting). Returns 0 when
 * the matrix is singular or not finite (a pivot below 1e-14 times the largest
 * entry); *inv is then unchanged. */
int ss_mat4_inverse(ss_mat4 a, ss_mat4 *inv);
/* Determinant of the upper-left 3x3 block: < 0 when the transform mirrors. */
double ss_mat4_det3(ss_mat4 a);

ss_vec3 ss_mat4_apply_point(ss_mat4 a, ss_vec3 p);  /* w = 1 */
ss_vec3 ss_mat4_apply_vector(ss_mat4 a, ss_vec3 v); /* w = 0 */
/* Transforms a normal by the inverse transpose; pass the INVERSE of the
 * point transform. The result is not normalised. */
ss_vec3 ss_mat4_apply_normal(ss_mat4 inverse, ss_vec3 n);

#endif
