/* Texture lookups: bilinear image filtering with wrap modes, the checker,
 * and the nesting of procedural colours (see texture.h; the noise is in
 * texture_noise.c). */
#include "subsurf/texture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct ss_texture {
  ss_texture_type type;
  ss_wrap wrap;
  double scale[2], offset[2];
  ss_image *image;            /* IMAGE, owned */
  ss_rgb colour[2];           /* CHECKER, NOISE: a and b ... */
  const ss_texture *input[2]; /* ... or textures in their place */
  ss_noise_params noise;      /* NOISE */
};

static ss_status create(ss_texture_type type, ss_texture **out, ss_error *err) {
  *out = calloc(1, sizeof **out);
  if (!*out) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "texture: out of memory");
  }
  (*out)->type = type;
  (*out)->scale[0] = (*out)->scale[1] = 1.0;
  return SS_OK;
}

ss_status ss_texture_create_image(ss_image *image, ss_wrap wrap, ss_texture **out, ss_error *err) {
  *out = NULL;
  size_t n = (size_t)image->width * (size_t)image->height * (size_t)image->channels;
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(image->data[i])) {
      ss_image_destroy(image);
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "texture: the image has a non-finite value (pixel %zu)",
                          i / (size_t)image->channels);
    }
  }
  ss_status st = create(SS_TEXTURE_IMAGE, out, err);
  if (st != SS_OK) {
    ss_image_destroy(image);
    return st;
  }
  (*out)->image = image;
  (*out)->wrap = wrap;
  return SS_OK;
}

ss_status ss_texture_create_checker(ss_rgb a, ss_rgb b, ss_texture **out, ss_error *err) {
  ss_status st = create(SS_TEXTURE_CHECKER, out, err);
  if (st == SS_OK) {
    (*out)->colour[0] = a;
    (*out)->colour[1] = b;
  }
  return st;
}

ss_status ss_texture_create_noise(ss_rgb a, ss_rgb b, const ss_noise_params *params,
                                  ss_texture **out, ss_error *err) {
  *out = NULL;
  const ss_noise_params *q = params;
  if (q->octaves < 1 || q->octaves > 16 || !(q->lacunarity > 1.0 && q->lacunarity <= 16.0) ||
      !(q->gain > 0.0 && q->gain < 1.0) || !(isfinite(q->lo) && isfinite(q->hi) && q->lo < q->hi)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "noise texture: octaves must be in [1, 16], lacunarity in (1, 16], gain "
                        "in (0, 1) and lo < hi");
  }
  ss_status st = create(SS_TEXTURE_NOISE, out, err);
  if (st == SS_OK) {
    (*out)->colour[0] = a;
    (*out)->colour[1] = b;
    (*out)->noise = *params;
  }
  return st;
}

void ss_texture_destroy(ss_texture *t) {
  if (t) {
    ss_image_destroy(t->image);
    free(t);
  }
}

void ss_texture_set_input(ss_texture *t, int which, const ss_texture *input) {
  t->input[which ? 1 : 0] = input;
}

void ss_texture_set_transform(ss_texture *t, const double scale[2], const double offset[2]) {
  memcpy(t->scale, scale, sizeof t->scale);
  memcpy(t->offset, offset, sizeof t->offset);
}

ss_texture_type ss_texture_get_type(const ss_texture *t) { return t->type; }

int ss_texture_uses_uv(const ss_texture *t) {
  int own = !(t->type == SS_TEXTURE_NOISE && t->noise.world);
  for (int k = 0; k < 2; ++k) {
    own = own || (t->input[k] && ss_texture_uses_uv(t->input[k]));
  }
  return own;
}

void ss_texture_range(const ss_texture *t, ss_rgb *lo, ss_rgb *hi) {
  if (t->type == SS_TEXTURE_IMAGE) {
    const ss_image *img = t->image;
    size_t n = (size_t)img->width * (size_t)img->height;
    *lo = ss_rgb_gray(INFINITY);
    *hi = ss_rgb_gray(-INFINITY);
    for (size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        double x = img->data[i * (size_t)img->channels + (size_t)(c < img->channels ? c : 0)];
        lo->c[c] = fmin(lo->c[c], x);
        hi->c[c] = fmax(hi->c[c], x);
      }
    }
    return;
  }
  ss_rgb l[2], h[2];
  for (int k = 0; k < 2; ++k) {
    if (t->input[k]) {
      ss_texture_range(t->input[k], &l[k], &h[k]);
    } else {
      l[k] = h[k] = t->colour[k];
    }
  }
  for (int c = 0; c < 3; ++c) {
    lo->c[c] = fmin(l[0].c[c], l[1].c[c]);
    hi->c[c] = fmax(h[0].c[c], h[1].c[c]);
  }
}

int ss_wrap_from_name(const char *name, ss_wrap *wrap) {
  static const char *const names[] = {"repeat", "clamp", "mirror"};
  for (int k = 0; k < 3; ++k) {
    if (!strcmp(name, names[k])) {
      *wrap = (ss_wrap)k;
      return 1;
    }
  }
  return 0;
}

int ss_texture_wrap_index(int i, int n, ss_wrap wrap) {
  if (wrap == SS_WRAP_CLAMP) {
    return i < 0 ? 0 : i >= n ? n - 1 : i;
  }
  if (wrap == SS_WRAP_REPEAT) {
    int k = i % n;
    return k < 0 ? k + n : k;
  }
  int k = i % (2 * n);
  k = k < 0 ? k + 2 * n : k;
  return k < n ? k : 2 * n - 1 - k;
}

/* Texel coordinate of a lookup: the texel centres sit at half-integers, so
 * x = u w - 1/2 puts texel i at x = i. Far outside [0, 1] (|u| > 1024) the
 * coordinate is reduced first so that the int conversion stays defined;
 * clamp needs no period and is clamped directly. */
static double texel_coord(double u, int n, ss_wrap wrap) {
  if (!isfinite(u)) {
    return 0.0;
  }
  if (fabs(u) > 1024.0) {
    u = wrap == SS_WRAP_CLAMP ? (u > 0.0 ? 2.0 : -1.0) : u - 2.0 * floor(0.5 * u);
  }
  return u * (double)n - 0.5;
}

ss_rgb ss_texture_image_lookup(const ss_image *img, ss_wrap wrap, double u, double v) {
  double x = texel_coord(u, img->width, wrap);
  double y = texel_coord(1.0 - v, img->height, wrap);
  double x0 = floor(x), y0 = floor(y);
  double fx = x - x0, fy = y - y0;
  int ix[2] = {ss_texture_wrap_index((int)x0, img->width, wrap),
               ss_texture_wrap_index((int)x0 + 1, img->width, wrap)};
  int iy[2] = {ss_texture_wrap_index((int)y0, img->height, wrap),
               ss_texture_wrap_index((int)y0 + 1, img->height, wrap)};
  const double w[2][2] = {{(1.0 - fx) * (1.0 - fy), fx * (1.0 - fy)}, {(1.0 - fx) * fy, fx * fy}};
  int nc = img->channels;
  ss_rgb out = ss_rgb_gray(0.0);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const float *px = img->data + ((size_t)iy[j] * (size_t)img->width + (size_t)ix[i]) * nc;
      for (int c = 0; c < 3; ++c) {
        out.c[c] += w[j][i] * px[c < nc ? c : 0];
      }
    }
  }
  return out;
}

static ss_rgb input_value(const ss_texture *t, int k, ss_texcoord tc) {
  return t->input[k] ? ss_texture_eval(t->input[k], tc) : t->colour[k];
}

/* a + (b - a) t: exactly a wherever b == a. */
static ss_rgb lerp(ss_rgb a, ss_rgb b, double t) { return ss_rgb_madd(a, ss_rgb_sub(b, a), t); }

ss_rgb ss_texture_eval(const ss_texture *t, ss_texcoord tc) {
  double u = tc.u * t->scale[0] + t->offset[0], v = tc.v * t->scale[1] + t->offset[1];
  switch (t->type) {
  case SS_TEXTURE_IMAGE:
    return ss_texture_image_lookup(t->image, t->wrap, u, v);
  case SS_TEXTURE_CHECKER: {
    double cell = floor(u) + floor(v);
    int odd = isfinite(cell) && fmod(fabs(cell), 2.0) == 1.0;
    return input_value(t, odd, tc);
  }
  default: {
    ss_vec3 p = t->noise.world ? ss_vec3_scale(tc.p, t->scale[0]) : ss_vec3_make(u, v, 0.0);
    double n = ss_noise_fbm(&t->noise, p);
    if (t->noise.ridged) {
      n = 1.0 - fabs(2.0 * n - 1.0);
    }
    double s = (n - t->noise.lo) / (t->noise.hi - t->noise.lo);
    s = s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
    if (s == 0.0) {
      return input_value(t, 0, tc);
    }
    if (s == 1.0) {
      return input_value(t, 1, tc);
    }
    return lerp(input_value(t, 0, tc), input_value(t, 1, tc), s);
  }
  }
}
