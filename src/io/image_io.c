#include "subsurf/image_io.h"

#include "io/image_io_internal.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

typedef enum { FORMAT_NONE, FORMAT_EXR, FORMAT_PNG, FORMAT_PFM } image_format;

static image_format format_from_path(const char *path) {
  const char *dot = path ? strrchr(path, '.') : NULL;
  if (!dot || strchr(dot, '/')) {
    return FORMAT_NONE;
  }
  if (!strcasecmp(dot, ".exr")) {
    return FORMAT_EXR;
  }
  if (!strcasecmp(dot, ".png")) {
    return FORMAT_PNG;
  }
  if (!strcasecmp(dot, ".pfm")) {
    return FORMAT_PFM;
  }
  return FORMAT_NONE;
}

int ss_image_format_supported(const char *path) { return format_from_path(path) != FORMAT_NONE; }

ss_status ss_image_io_check(const char *path, const ss_image *img, ss_error *err) {
  if (!img || !img->data || img->width <= 0 || img->height <= 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "cannot write %s: empty image", path);
  }
  if (img->channels != 1 && img->channels != 3 && img->channels != 4) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "cannot write %s: images have 1, 3 or 4 channels (got %d)", path,
                        img->channels);
  }
  return SS_OK;
}

ss_status ss_image_write(const char *path, const ss_image *img, double exposure, ss_error *err) {
  switch (format_from_path(path)) {
  case FORMAT_EXR:
    return ss_image_write_exr(path, img, err);
  case FORMAT_PNG:
    return ss_image_write_png(path, img, exposure, err);
  case FORMAT_PFM:
    return ss_image_write_pfm(path, img, err);
  case FORMAT_NONE:
    break;
  }
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "%s: unsupported image format (expected .exr, .png or .pfm)",
                      path ? path : "(null)");
}

/* The format is told by the file's first bytes, not its name: EXR files start
 * with the magic number 20000630 (little endian), PFM files with "PF"/"Pf",
 * PNG files with 137 "PNG" (whose sRGB codes, as ss_image_write_png writes
 * them, are decoded to linear values). */
ss_status ss_image_read(const char *path, ss_image **out, ss_error *err) {
  *out = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) {
    return ss_error_set(err, SS_ERR_IO, "cannot read %s: %s", path, strerror(errno));
  }
  unsigned char magic[4] = {0, 0, 0, 0};
  static const unsigned char png[4] = {0x89, 'P', 'N', 'G'};
  size_t n = fread(magic, 1, sizeof magic, f);
  fclose(f);
  if (n == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01) {
    return ss_image_read_exr(path, out, err);
  }
  if (n >= 2 && magic[0] == 'P' && (magic[1] == 'F' || magic[1] == 'f')) {
    return ss_image_read_pfm(path, out, err);
  }
  if (n == 4 && !memcmp(magic, png, sizeof png)) {
    return ss_image_read_png(path, 1, out, err);
  }
  return ss_error_set(err, SS_ERR_PARSE, "cannot read %s: not an OpenEXR, PFM or PNG file", path);
}
