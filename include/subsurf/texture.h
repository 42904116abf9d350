/* Textures: spatially varying colour (or data) values of material
 * parameters.
 *
 * A texture maps a surface point to an RGB triple. Image textures hold a
 * linear float image (io/ decodes PNG and EXR files into one) and are
 * filtered bilinearly, with texel centres at ((i + 1/2) / width,
 * (j + 1/2) / height) and v pointing up (row 0 of the image is the top,
 * v = 1), the convention of OBJ and PLY texture coordinates. Procedural
 * textures (a checkerboard, gradient-noise fBm) need no file; a procedural
 * texture's two colours may themselves be textures, so patterns nest.
 *
 * Lookups are in texture coordinates (u, v) after the texture's own
 * transform uv' = uv * scale + offset, or, for textures in world space, at
 * the 3D point p * scale (the noise only). A texture is immutable once
 * built and safe to share between threads; lookups never allocate. */
#ifndef SUBSURF_TEXTURE_H
#define SUBSURF_TEXTURE_H

#include "subsurf/image.h"
#include "subsurf/rgb.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <stdint.h>

typedef enum {
  SS_TEXTURE_IMAGE,   /* a bilinearly filtered image */
  SS_TEXTURE_CHECKER, /* colour a on even cells, b on odd ones */
  SS_TEXTURE_NOISE,   /* lerp(a, b, remapped fBm of gradient noise) */
} ss_texture_type;

/* What happens outside [0, 1) (images; the procedural patterns are
 * infinite). */
typedef enum {
  SS_WRAP_REPEAT, /* periodic */
  SS_WRAP_CLAMP,  /* the edge texels extend outward */
  SS_WRAP_MIRROR, /* periodic with period 2, every other copy mirrored */
} ss_wrap;

/* The point a texture is looked up at. */
typedef struct {
  double u, v; /* interpolated texture coordinates of the mesh (0 when none) */
  ss_vec3 p;   /* world position */
} ss_texcoord;

/* fBm of Perlin's gradient noise (Perlin 2002, "Improving Noise"; Musgrave
 * et al. 1994 for the sum of octaves), remapped: with n in [0, 1] the fBm
 * value, t = clamp((n - lo) / (hi - lo), 0, 1) blends a to b. "ridged"
 * turns n into 1 - |2n - 1| first: thin bright lines where the noise
 * crosses its mean (veins). */
typedef struct {
  int octaves;       /* 1..16 */
  double lacunarity; /* frequency ratio of successive octaves, > 1 */
  double gain;       /* amplitude ratio of successive octaves, (0, 1) */
  double lo, hi;     /* remap range of n, lo < hi */
  int ridged;
  uint32_t seed; /* picks the lattice's gradients */
  int world;     /* 1: looked up at the world position, 0: at (u, v, 0) */
} ss_noise_params;

typedef struct ss_texture ss_texture;

/* Takes ownership of `image` (also on failure); values must be finite. */
ss_status ss_texture_create_image(ss_image *image, ss_wrap wrap, ss_texture **out, ss_error *err);
/* Squares of side 1 in (u', v'): set the transform's scale to the number of
 * squares per unit of (u, v). */
ss_status ss_texture_create_checker(ss_rgb a, ss_rgb b, ss_texture **out, ss_error *err);
ss_status ss_texture_create_noise(ss_rgb a, ss_rgb b, const ss_noise_params *params,
                                  ss_texture **out, ss_error *err);
void ss_texture_destroy(ss_texture *t);

/* Replaces colour a (which = 0) or b (1) of a procedural texture by another
 * texture, which must outlive this one (scenes own all their textures). */
void ss_texture_set_input(ss_texture *t, int which, const ss_texture *input);
/* uv' = uv * scale + offset (world-space noise: p * scale[0]). */
void ss_texture_set_transform(ss_texture *t, const double scale[2], const double offset[2]);

ss_texture_type ss_texture_get_type(const ss_texture *t);
/* 1 when a lookup reads (u, v) (and so the mesh needs texture coordinates). */
int ss_texture_uses_uv(const ss_texture *t);
/* Componentwise bounds of every value a lookup can return. */
void ss_texture_range(const ss_texture *t, ss_rgb *lo, ss_rgb *hi);

ss_rgb ss_texture_eval(const ss_texture *t, ss_texcoord tc);

/* The bilinear lookup of an image at (u, v) with a wrap mode (exposed for
 * tests and benchmarks; ss_texture_eval uses it). */
ss_rgb ss_texture_image_lookup(const ss_image *img, ss_wrap wrap, double u, double v);
/* Wraps texel index i into [0, n). */
int ss_texture_wrap_index(int i, int n, ss_wrap wrap);
/* Parses "repeat", "clamp", "mirror"; 0 on an unknown name. */
int ss_wrap_from_name(const char *name, ss_wrap *wrap);

/* Gradient noise (Perlin 2002) in [-1, 1] at p, lattice picked by seed. */
double ss_gradient_noise(ss_vec3 p, uint32_t seed);
/* The noise texture's n in [0, 1] (before the remap) at p. */
double ss_noise_fbm(const ss_noise_params *params, ss_vec3 p);

#endif
