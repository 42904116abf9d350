/* Gradient noise and its fractal sum, for the procedural noise texture
 * (texture.h). Perlin's improved noise on the integer lattice, with the
 * permutation replaced by an integer hash of (lattice point, seed) so that
 * seeds pick independent patterns and nothing is tabulated. */
#include "subsurf/texture.h"

#include <math.h>

/* A 32-bit integer hash (the "lowbias32" finaliser of C. Wellons' hash
 * prospector) of a lattice point and the seed. */
static uint32_t hash3(int32_t x, int32_t y, int32_t z, uint32_t seed) {
  uint32_t h = seed ^ 0x9E3779B9u;
  const uint32_t k[3] = {(uint32_t)x, (uint32_t)y, (uint32_t)z};
  for (int i = 0; i < 3; ++i) {
    h ^= k[i] + 0x7FEB352Du * (uint32_t)(i + 1);
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
  }
  return h;
}

/* Perlin 2002, "Improving Noise": the gradient is one of the 12 edge
 * midpoints of the cube (16 entries, four repeated), dotted with the offset. */
static double grad(uint32_t h, double x, double y, double z) {
  int k = (int)(h >> 28);
  double u = k < 8 ? x : y;
  double v = k < 4 ? y : (k == 12 || k == 14) ? x : z;
  return ((k & 1) ? -u : u) + ((k & 2) ? -v : v);
}

/* Perlin 2002: the quintic fade 6t^5 - 15t^4 + 10t^3 (C2 continuous). */
static double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

static double lerp(double a, double b, double t) { return a + t * (b - a); }

double ss_gradient_noise(ss_vec3 p, uint32_t seed) {
  double fx = floor(p.x), fy = floor(p.y), fz = floor(p.z);
  if (!(fabs(fx) < 1e9 && fabs(fy) < 1e9 && fabs(fz) < 1e9)) {
    return 0.0; /* beyond the int lattice (or NaN): flat */
  }
  int32_t x = (int32_t)fx, y = (int32_t)fy, z = (int32_t)fz;
  double dx = p.x - fx, dy = p.y - fy, dz = p.z - fz;
  double g[8];
  for (int c = 0; c < 8; ++c) {
    int i = c & 1, j = (c >> 1) & 1, k = c >> 2;
    g[c] = grad(hash3(x + i, y + j, z + k, seed), dx - i, dy - j, dz - k);
  }
  double u = fade(dx), v = fade(dy), w = fade(dz);
  double x00 = lerp(g[0], g[1], u), x10 = lerp(g[2], g[3], u);
  double x01 = lerp(g[4], g[5], u), x11 = lerp(g[6], g[7], u);
  double n = lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
  return n < -1.0 ? -1.0 : n > 1.0 ? 1.0 : n;
}

/* Musgrave et al. 1994 (Texturing and Modeling, ch. "fBm"): the sum over
 * octaves k of gain^k noise(lacunarity^k p), normalised by the sum of the
 * amplitudes and mapped from [-1, 1] to [0, 1]. Each octave gets its own
 * seed so that the lattices do not line up at the origin. */
double ss_noise_fbm(const ss_noise_params *q, ss_vec3 p) {
  double sum = 0.0, norm = 0.0, amp = 1.0;
  for (int k = 0; k < q->octaves; ++k) {
    sum += amp * ss_gradient_noise(p, q->seed + 0x632BE5ABu * (uint32_t)k);
    norm += amp;
    amp *= q->gain;
    p = ss_vec3_scale(p, q->lacunarity);
  }
  return 0.5 + 0.5 * sum / norm;
}
