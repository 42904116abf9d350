/* Texture images: PNG and Radiance HDR (stb_image) and EXR (image_exr.c)
 * decoded to linear float (see texture_io.h). */
#include "subsurf/texture_io.h"

#include "core/input_file.h"
#include "io/image_io_internal.h"

#include <math.h>
#include <stb/stb_image.h>
#include <stdlib.h>
#include <string.h>

/* A PNG larger than this is refused before it is read into memory. */

double ss_srgb_decode(double v) {
  /* IEC 61966-2-1, the inverse of the encoding in image_png.c. */
  return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static int has_suffix(const char *path, const char *suffix) {
  size_t n = strlen(path), k = strlen(suffix);
  if (n < k) {
    return 0;
  }
  for (size_t i = 0; i < k; ++i) {
    char c = path[n - k + i];
    if ((c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c) != suffix[i]) {
      return 0;
    }
  }
  return 1;
}

ss_status ss_image_read_png(const char *path, int srgb, ss_image **out, ss_error *err) {
  unsigned char *file = NULL;
  size_t size = 0;
  ss_status st = ss_input_file_read(path, path, SS_INPUT_TEXTURE, &file, &size, err);
  if (st != SS_OK) {
    return st;
  }
  int w, h, comp;
  if (size > INT32_MAX || !stbi_info_from_memory(file, (int)size, &w, &h, &comp)) {
    free(file);
    return ss_error_set(err, SS_ERR_PARSE, "%s: not a readable PNG image (%s)", path,
                        stbi_failure_reason() ? stbi_failure_reason() : "unknown format");
  }
  if (w < 1 || h < 1 || w > SS_TEXTURE_MAX_SIZE || h > SS_TEXTURE_MAX_SIZE) {
    free(file);
    return ss_error_set(err, SS_ERR_PARSE, "%s: %d x %d texels (at most %d on a side)", path, w, h,
                        SS_TEXTURE_MAX_SIZE);
  }
  int nc = comp <= 2 ? 1 : 3;
  int wide = stbi_is_16_bit_from_memory(file, (int)size);
  void *pixels = wide ? (void *)stbi_load_16_from_memory(file, (int)size, &w, &h, &comp, nc)
                      : (void *)stbi_load_from_memory(file, (int)size, &w, &h, &comp, nc);
  free(file);
  if (!pixels) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: cannot decode the PNG image (%s)", path,
                        stbi_failure_reason() ? stbi_failure_reason() : "corrupt data");
  }
  ss_image *img = ss_image_create(w, h, nc);
  if (!img) {
    stbi_image_free(pixels);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", path);
  }
  /* The decoded value of each code: a table of 256 for 8 bits. */
  double table[256];
  for (int k = 0; k < 256; ++k) {
    table[k] = srgb ? ss_srgb_decode(k / 255.0) : k / 255.0;
  }
  size_t n = (size_t)w * (size_t)h * (size_t)nc;
  for (size_t i = 0; i < n; ++i) {
    double v = wide ? ((const unsigned short *)pixels)[i] / 65535.0
                    : table[((const unsigned char *)pixels)[i]];
    img->data[i] = (float)(wide && srgb ? ss_srgb_decode(v) : v);
  }
  stbi_image_free(pixels);
  *out = img;
  return SS_OK;
}

/* A Radiance RGBE picture (Ward1991), linear already. */
static ss_status read_hdr(const char *path, ss_image **out, ss_error *err) {
  unsigned char *file = NULL;
  size_t size = 0;
  ss_status st = ss_input_file_read(path, path, SS_INPUT_TEXTURE, &file, &size, err);
  if (st != SS_OK) {
    return st;
  }
  int w, h, comp;
  if (size > INT32_MAX || !stbi_is_hdr_from_memory(file, (int)size) ||
      !stbi_info_from_memory(file, (int)size, &w, &h, &comp)) {
    free(file);
    return ss_error_set(err, SS_ERR_PARSE, "%s: not a readable Radiance HDR image", path);
  }
  if (w < 1 || h < 1 || w > SS_TEXTURE_MAX_SIZE || h > SS_TEXTURE_MAX_SIZE) {
    free(file);
    return ss_error_set(err, SS_ERR_PARSE, "%s: %d x %d texels (at most %d on a side)", path, w, h,
                        SS_TEXTURE_MAX_SIZE);
  }
  float *pixels = stbi_loadf_from_memory(file, (int)size, &w, &h, &comp, 3);
  free(file);
  if (!pixels) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: cannot decode the HDR image (%s)", path,
                        stbi_failure_reason() ? stbi_failure_reason() : "corrupt data");
  }
  ss_image *img = ss_image_create(w, h, 3);
  if (!img) {
    stbi_image_free(pixels);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", path);
  }
  memcpy(img->data, pixels, (size_t)w * (size_t)h * 3 * sizeof *pixels);
  stbi_image_free(pixels);
  *out = img;
  return SS_OK;
}

ss_status ss_texture_image_read(const char *path, int srgb, ss_image **out, ss_error *err) {
  *out = NULL;
  if (has_suffix(path, ".png")) {
    return ss_image_read_png(path, srgb, out, err);
  }
  if (has_suffix(path, ".hdr")) {
    return read_hdr(path, out, err);
  }
  if (!has_suffix(path, ".exr")) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "%s: unknown texture format (expected .png, .hdr or .exr)", path);
  }
  FILE *f;
  ss_status st = ss_input_file_open(path, path, &f, NULL, err);
  if (st != SS_OK) {
    return st;
  }
  fclose(f);
  ss_image *img;
  if ((st = ss_image_read_exr(path, &img, err)) != SS_OK) {
    return st;
  }
  if (img->width > SS_TEXTURE_MAX_SIZE || img->height > SS_TEXTURE_MAX_SIZE) {
    ss_image_destroy(img);
    return ss_error_set(err, SS_ERR_PARSE, "%s: larger than %d texels on a side", path,
                        SS_TEXTURE_MAX_SIZE);
  }
  *out = img;
  return SS_OK;
}
