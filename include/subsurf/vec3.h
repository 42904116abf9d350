/* Three-vectors and orthonormal frames: plain structs passed by value. */
#ifndef SUBSURF_VEC3_H
#define SUBSURF_VEC3_H

#include <math.h>

typedef struct {
  double x, y, z;
} ss_vec3;

/* An orthonormal frame; n is the "up" axis of local coordinates. */
typedef struct {
  ss_vec3 s, t, n;
} ss_frame;

static inline ss_vec3 ss_vec3_make(double x, double y, double z) {
  ss_vec3 v = {x, y, z};
  return v;
}
static inline ss_vec3 ss_vec3_add(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline ss_vec3 ss_vec3_sub(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline ss_vec3 ss_vec3_scale(ss_vec3 a, double k) {
  return ss_vec3_make(a.x * k, a.y * k, a.z * k);
}
/* a + k b */
static inline ss_vec3 ss_vec3_madd(ss_vec3 a, ss_vec3 b, double k) {
  return ss_vec3_make(a.x + k * b.x, a.y + k * b.y, a.z + k * b.z);
}
static inline ss_vec3 ss_vec3_mul(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(a.x * b.x, a.y * b.y, a.z * b.z);
}
static inline ss_vec3 ss_vec3_neg(ss_vec3 a) { return ss_vec3_make(-a.x, -a.y, -a.z); }
static inline double ss_vec3_dot(ss_vec3 a, ss_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline ss_vec3 ss_vec3_cross(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double ss_vec3_length2(ss_vec3 a) { return ss_vec3_dot(a, a); }
static inline double ss_vec3_length(ss_vec3 a) { return sqrt(ss_vec3_dot(a, a)); }
static inline ss_vec3 ss_vec3_normalize(ss_vec3 a) {
  return ss_vec3_scale(a, 1.0 / ss_vec3_length(a));
}
static inline double ss_vec3_max_component(ss_vec3 a) {
  double m = a.x > a.y ? a.x : a.y;
  return m > a.z ? m : a.z;
}
static inline double ss_vec3_component(ss_vec3 a, int i) {
  return i == 0 ? a.x : (i == 1 ? a.y : a.z);
}

/* Branchless orthonormal basis around a unit normal (Duff et al. 2017,
 * "Building an Orthonormal Basis, Revisited", listing 3). */
static inline ss_frame ss_frame_from_normal(ss_vec3 n) {
  double sign = copysign(1.0, n.z);
  double a = -1.0 / (sign + n.z);
  double b = n.x * n.y * a;
  ss_frame f;
  f.s = ss_vec3_make(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  f.t = ss_vec3_make(b, sign + n.y * n.y * a, -n.y);
  f.n = n;
  return f;
}
static inline ss_vec3 ss_frame_to_local(ss_frame f, ss_vec3 v) {
  return ss_vec3_make(ss_vec3_dot(v, f.s), ss_vec3_dot(v, f.t), ss_vec3_dot(v, f.n));
}
static inline ss_vec3 ss_frame_to_world(ss_frame f, ss_vec3 v) {
  return ss_vec3_make(f.s.x * v.x + f.t.x * v.y + f.n.x * v.z,
                      f.s.y * v.x + f.t.y * v.y + f.n.y * v.z,
                      f.s.z * v.x + f.t.z * v.y + f.n.z * v.z);
}

/* Direction from spherical coordinates about +z. */
static inline ss_vec3 ss_spherical_direction(double cos_theta, double phi) {
  double sin_theta = sqrt(fmax(0.0, 1.0 - cos_theta * cos_theta));
  return ss_vec3_make(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

#endif
